// What the surface classes are made from: light origins from the .map (or the BSP's entities) and
// the emitting shaders found through the game's shader scripts.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <limits>

#include "light_compare.h"
#include "light_compare_internal.h"
#include "log.h"
#include "map_file.h"
#include "shader_info.h"
#include "shader_loader.h"
#include "vfs.h"

namespace q3::conformance {
namespace fs = std::filesystem;

namespace {

bool startsWithLight(std::string_view classname) {
    if (classname.size() < 5) return false;
    for (size_t i = 0; i < 5; ++i)
        if (std::tolower(static_cast<unsigned char>(classname[i])) != "light"[i]) return false;
    return true;
}

std::vector<Vec3> lightsFromBspEntities(const bsp::Bsp& bsp) {
    std::vector<Vec3> origins;
    for (const bsp::Entity& e : bsp::parseEntities(bsp.entities, "reference entities")) {
        if (!startsWithLight(e.classname())) continue;
        Vec3 o;
        if (std::sscanf(e.value("origin").c_str(), "%f %f %f", &o.x, &o.y, &o.z) == 3) origins.push_back(o);
    }
    return origins;
}

bool shaderLightsFromSky(const ShaderInfo& info) {
    for (const ShaderSun& sun : info.suns)
        if (sun.intensity > 0) return true;
    for (const ShaderSkyLight& sky : info.skyLights)
        if (sky.value > 0) return true;
    return info.surfaceLight > 0;
}

}  // namespace

ClassInputs loadClassInputs(const bsp::Bsp& reference, const fs::path& mapSource,
                            const std::vector<fs::path>& basePaths, const std::string& game) {
    ClassInputs in;
    if (!mapSource.empty()) {
        const map::MapFile map = map::loadMap(mapSource);
        for (const map::MapEntity* e : map::lightEntities(map)) {
            Vec3 o;
            if (e->origin(o)) in.lightOrigins.push_back(o);
        }
        in.lightsKnown = true;
    } else {
        in.lightOrigins = lightsFromBspEntities(reference);
        in.lightsKnown = !in.lightOrigins.empty();
    }

    in.shaderIsSky.resize(reference.shaders.size());
    for (size_t i = 0; i < reference.shaders.size(); ++i)
        in.shaderIsSky[i] = (uint32_t(reference.shaders[i].surfaceFlags) & surfaceflags::Sky) != 0;
    if (basePaths.empty()) return in;

    Log quiet(false);
    VfsOptions options;
    options.basePaths = basePaths;
    if (!game.empty()) options.baseGame = game;
    const Vfs vfs(options, quiet);
    const ShaderTable table = loadShaderTable(vfs, quiet);
    in.shaderEmitsArea.resize(reference.shaders.size());
    for (size_t i = 0; i < reference.shaders.size(); ++i) {
        const ShaderInfo& info = table.find(reference.shaders[i].name);
        in.shaderEmitsArea[i] = info.surfaceLight > 0;
        if (in.shaderIsSky[i] && shaderLightsFromSky(info)) in.skyEmits = true;
    }
    in.shadersKnown = true;
    return in;
}

namespace detail {
namespace {

// Opaque drawn surfaces stop the upward ray; glass, fog and liquids let it through.
bool blocksSkyRay(const bsp::Bsp& bsp, const bsp::Surface& s) {
    if (s.shaderNum < 0 || s.shaderNum >= int(bsp.shaders.size())) return false;
    const bsp::Shader& shader = bsp.shaders[s.shaderNum];
    const uint32_t seeThrough = contents::Translucent | contents::Fog | contents::Water | contents::Slime | contents::Lava;
    return (uint32_t(shader.contentFlags) & seeThrough) == 0 && (uint32_t(shader.surfaceFlags) & surfaceflags::NoDraw) == 0;
}

// Distance along +z from `origin` to the triangle, or a negative value when the ray misses it.
float upwardHit(Vec3 origin, Vec3 a, Vec3 b, Vec3 c) {
    // Barycentric test in the xy plane, then the plane's height at that point.
    const float d = (b.y - c.y) * (a.x - c.x) + (c.x - b.x) * (a.y - c.y);
    if (std::fabs(d) < 1e-12f) return -1;  // vertical or degenerate: a vertical ray grazes it
    const float wa = ((b.y - c.y) * (origin.x - c.x) + (c.x - b.x) * (origin.y - c.y)) / d;
    const float wb = ((c.y - a.y) * (origin.x - c.x) + (a.x - c.x) * (origin.y - c.y)) / d;
    const float wc = 1 - wa - wb;
    if (wa < 0 || wb < 0 || wc < 0) return -1;
    return wa * a.z + wb * b.z + wc * c.z - origin.z;
}

}  // namespace

std::vector<bool> skyLitSurfaces(const bsp::Bsp& bsp, const std::vector<bool>& shaderIsSky) {
    constexpr float kCell = 64;
    struct Tri {
        Vec3 a, b, c;
        int surface;
    };
    std::vector<Tri> tris;
    Bounds world;
    for (int s = 0; s < int(bsp.surfaces.size()); ++s) {
        if (!blocksSkyRay(bsp, bsp.surfaces[s])) continue;
        for (const std::array<int, 3>& t : surfaceTriangles(bsp, s)) {
            Tri tri{vertexPosition(bsp, t[0]), vertexPosition(bsp, t[1]), vertexPosition(bsp, t[2]), s};
            world.add(tri.a);
            world.add(tri.b);
            world.add(tri.c);
            tris.push_back(tri);
        }
    }
    std::vector<bool> lit(bsp.surfaces.size(), false);
    if (tris.empty()) return lit;
    // Triangles binned into xy cells by their xy bounds: a vertical ray tests one cell only.
    const int nx = std::max(1, int(std::ceil((world.maxs.x - world.mins.x) / kCell)) + 1);
    const int ny = std::max(1, int(std::ceil((world.maxs.y - world.mins.y) / kCell)) + 1);
    auto cellOf = [&](float v, float lo, int n) { return std::clamp(int((v - lo) / kCell), 0, n - 1); };
    std::vector<std::vector<int>> cells(size_t(nx) * ny);
    for (int i = 0; i < int(tris.size()); ++i) {
        const Tri& t = tris[i];
        const int x0 = cellOf(std::min({t.a.x, t.b.x, t.c.x}), world.mins.x, nx);
        const int x1 = cellOf(std::max({t.a.x, t.b.x, t.c.x}), world.mins.x, nx);
        const int y0 = cellOf(std::min({t.a.y, t.b.y, t.c.y}), world.mins.y, ny);
        const int y1 = cellOf(std::max({t.a.y, t.b.y, t.c.y}), world.mins.y, ny);
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x) cells[size_t(y) * nx + x].push_back(i);
    }
    for (int s = 0; s < int(bsp.surfaces.size()); ++s) {
        const SurfaceShape shape = surfaceShape(bsp, s);
        if (shape.bounds.empty()) continue;
        const Vec3 origin = shape.centroid + shape.normal;
        if (origin.x < world.mins.x || origin.x > world.maxs.x || origin.y < world.mins.y || origin.y > world.maxs.y)
            continue;
        float nearest = std::numeric_limits<float>::max();
        int hitSurface = -1;
        for (int i : cells[size_t(cellOf(origin.y, world.mins.y, ny)) * nx + cellOf(origin.x, world.mins.x, nx)]) {
            const Tri& t = tris[i];
            if (t.surface == s) continue;
            const float d = upwardHit(origin, t.a, t.b, t.c);
            if (d > 0 && d < nearest) {
                nearest = d;
                hitSurface = t.surface;
            }
        }
        const int shaderNum = hitSurface >= 0 ? bsp.surfaces[hitSurface].shaderNum : -1;
        lit[s] = shaderNum >= 0 && shaderNum < int(shaderIsSky.size()) && shaderIsSky[shaderNum];
    }
    return lit;
}

}  // namespace detail
}  // namespace q3::conformance
