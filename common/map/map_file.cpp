// Entity helpers, plane construction and the light-entity filter of the .map model.
#include "map_file.h"

#include <cmath>
#include <sstream>

#include "file_io.h"
#include "script.h"

namespace q3::map {

bool planeFromPoints(const Vec3& a, const Vec3& b, const Vec3& c, MapPlane& out) {
    // Double precision: editor coordinates are integers or short decimals, and planes built from
    // them must not pick up float noise before the -bsp stage snaps them.
    const double ab[3] = {double(b.x) - a.x, double(b.y) - a.y, double(b.z) - a.z};
    const double ac[3] = {double(c.x) - a.x, double(c.y) - a.y, double(c.z) - a.z};
    double n[3] = {ac[1] * ab[2] - ac[2] * ab[1], ac[2] * ab[0] - ac[0] * ab[2], ac[0] * ab[1] - ac[1] * ab[0]};
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(len > 0) || !std::isfinite(len)) return false;
    for (double& v : n) v /= len;
    out.normal[0] = n[0];
    out.normal[1] = n[1];
    out.normal[2] = n[2];
    out.dist = n[0] * a.x + n[1] * a.y + n[2] * a.z;
    return true;
}

const std::string* MapEntity::find(std::string_view key) const {
    for (const auto& [k, v] : pairs)
        if (equalsNoCase(k, key)) return &v;
    return nullptr;
}

std::string MapEntity::value(std::string_view key, std::string_view fallback) const {
    const std::string* v = find(key);
    return v ? *v : std::string(fallback);
}

std::string_view MapEntity::classname() const {
    const std::string* v = find("classname");
    return v ? std::string_view(*v) : std::string_view();
}

bool MapEntity::origin(Vec3& out) const {
    const std::string* v = find("origin");
    if (!v) return false;
    std::istringstream in(*v);
    double x = 0, y = 0, z = 0;
    if (!(in >> x >> y >> z)) return false;
    out = {float(x), float(y), float(z)};
    return isFinite(out);
}

bool isLightEntity(const MapEntity& entity) {
    std::string_view name = entity.classname();
    return name.size() >= 5 && equalsNoCase(name.substr(0, 5), "light");
}

std::vector<const MapEntity*> lightEntities(const MapFile& map) {
    std::vector<const MapEntity*> lights;
    for (const MapEntity& e : map.entities)
        if (isLightEntity(e)) lights.push_back(&e);
    return lights;
}

std::string shaderNameForTexture(std::string_view texture) {
    return "textures/" + std::string(texture);
}

MapFile loadMap(const std::filesystem::path& path) {
    const std::string text = readFileText(path);
    return parseMap(text, path.string());
}

}  // namespace q3::map
