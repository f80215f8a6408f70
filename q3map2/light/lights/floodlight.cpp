#include "floodlight.h"

#include <charconv>
#include <sstream>

#include "log.h"
#include "shader_info.h"

namespace q3::light {

namespace {
constexpr int kFloodAzimuthSteps = 16;
constexpr int kFloodElevationSteps = 4;
constexpr float kFloodConeDegrees = 88;
constexpr int kLowQualityStride = 10;     // -lowquality keeps every tenth direction
constexpr float kFloodInhibitRadius = 1.5f;  // q3map2 DEFAULT_INHIBIT_RADIUS: ignore hits this close

const std::vector<Vec3>& floodConeDirections() {
    static const std::vector<Vec3> directions =
        coneDirections(kFloodAzimuthSteps, kFloodElevationSteps, kFloodConeDegrees);
    return directions;
}

std::vector<double> parseNumbers(const std::string& text, const std::string& what) {
    std::vector<double> values;
    std::istringstream in(text);
    std::string token;
    while (in >> token) {
        double v = 0;
        auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
        if (ec != std::errc() || end != token.data() + token.size())
            throw CompileError(what + ": '" + token + "' is not a number");
        values.push_back(v);
    }
    return values;
}
}  // namespace

Vec3 normalizeFloodColor(Vec3 color) {
    const float m = maxComponent(color);
    return m > 0 ? color / m : Vec3{};
}

std::optional<FloodlightSettings> globalFloodlight(bool option, bool lowQuality, const bsp::Entity& worldspawn,
                                                   const std::string& fileName) {
    FloodlightSettings s;
    s.lowQuality = lowQuality;
    const std::string* key = worldspawn.find("_floodlight");
    if (!key && !option) return std::nullopt;
    if (key) {
        const std::vector<double> v = parseNumbers(*key, fileName + ": worldspawn _floodlight");
        auto at = [&](size_t i, double fallback) { return i < v.size() ? v[i] : fallback; };
        Vec3 color{static_cast<float>(at(0, 0)), static_cast<float>(at(1, 0)), static_cast<float>(at(2, 0))};
        if (length(color) == 0) color = Vec3{0.94f, 0.94f, 1.0f};
        s.color = color;
        const double distance = at(3, s.distance), intensity = at(4, s.intensity), scale = at(5, s.directionScale);
        s.distance = distance < 1 ? 1024.0f : static_cast<float>(distance);
        s.intensity = intensity < 1 ? 128.0f : static_cast<float>(intensity);
        s.directionScale = scale < 0 ? 1.0f : static_cast<float>(scale);
    }
    s.color = normalizeFloodColor(s.color);
    return s;
}

std::optional<FloodlightSettings> shaderFloodlight(const std::optional<ShaderFloodLight>& directive) {
    if (!directive || directive->intensity == 0) return std::nullopt;
    FloodlightSettings s;
    s.color = normalizeFloodColor(directive->color);
    s.distance = directive->distance;
    s.intensity = directive->intensity;
    s.directionScale = directive->directionScale;
    return s;
}

float floodlightForSample(Vec3 origin, Vec3 normal, const HitScene& scene, const FloodlightSettings& settings) {
    if (settings.distance <= 0) return 0.0f;
    Vec3 right, up;
    tangentFrame(normal, right, up);
    const std::vector<Vec3>& cone = floodConeDirections();
    const size_t stride = settings.lowQuality ? kLowQualityStride : 1;
    std::vector<Vec3> directions;
    directions.reserve(cone.size() / stride + 1);
    for (size_t i = 0; i < cone.size(); i += stride) directions.push_back(toFrame(cone[i], right, up, normal));
    std::vector<RayHit> hits(directions.size());
    scene.nearestMany(origin, directions, kFloodInhibitRadius, settings.distance, hits);
    // Open space and sky count fully; a surface counts by how far away it is.
    float gathered = 0;
    const int rays = static_cast<int>(directions.size());
    for (const RayHit& hit : hits)
        gathered += (!hit.hit || hit.sky) ? 1.0f : std::min(1.0f, hit.distance / settings.distance);
    if (gathered <= 0) return 0.0f;
    return std::min(1.0f, gathered / static_cast<float>(std::max(1, rays)));
}

std::vector<Vec3> floodlightForLightmap(const std::vector<std::optional<SamplePoint>>& points,
                                        const HitScene& scene, const FloodlightSettings& settings) {
    std::vector<Vec3> out(points.size());
    for (size_t i = 0; i < points.size(); ++i) {
        if (!points[i]) continue;
        const float amount = floodlightForSample(points[i]->origin, points[i]->normal, scene, settings);
        out[i] = settings.color * (amount * settings.intensity);
    }
    return out;
}

void addFloodlight(LuxelImage& image, const std::vector<Vec3>& flood) {
    for (size_t i = 0; i < image.color.size() && i < flood.size(); ++i)
        if (image.state[i] == LuxelState::Mapped) image.color[i] += flood[i];
}

}  // namespace q3::light
