// WORLDLIGHTS records <-> JSON (see world_lights_json.h).
#include "world_lights_json.h"

#include <array>
#include <string_view>

#include "bspfile.h"
#include "world_lights.h"

namespace q3::json {
namespace {

constexpr std::array<std::string_view, 3> kTypeNames = {"point", "spot", "sun"};
constexpr std::array<std::string_view, 4> kFalloffNames = {"inverseSquare", "linear", "controlled", "parallel"};

template <size_t N>
uint32_t indexOf(const std::array<std::string_view, N>& names, const Value& v, const std::string& context) {
    const std::string& name = v.asString(context);
    for (size_t i = 0; i < N; ++i)
        if (names[i] == name) return uint32_t(i);
    v.fail(context, "unknown name \"" + name + "\"");
}

template <size_t N>
void readArray(const Value& v, std::array<float, N>& out, const std::string& context) {
    v.asArray(N, context);
    for (size_t i = 0; i < N; ++i) out[i] = v.items[i].asFloat(context);
}

}  // namespace

void writeWorldLightsMember(Writer& w, const std::vector<uint8_t>& lump, const std::string& where) {
    std::vector<sh::WorldLight> lights;
    std::string error;
    if (!sh::decodeWorldLights(lump.data(), lump.size(), lights, error)) throw bsp::BspError(where + ": " + error);
    w.key("lights");
    w.startArray();
    for (const sh::WorldLight& l : lights) {
        w.startObject();
        w.key("type"); w.string(kTypeNames[uint32_t(l.type)]);
        w.key("falloff"); w.string(kFalloffNames[uint32_t(l.falloff)]);
        w.key("inShGrid"); w.integer((l.flags & sh::kWorldLightInShGrid) ? 1 : 0);
        w.key("style"); w.integer(l.style);
        w.key("cluster"); w.integer(l.cluster);
        w.key("origin"); w.floats(l.origin.data(), 3);
        w.key("intensity"); w.floats(l.intensity.data(), 3);
        w.key("direction"); w.floats(l.direction.data(), 3);
        w.key("falloffConstants"); w.floats(l.falloffConstants.data(), 4);
        w.key("cone"); w.floats(l.cone.data(), 4);
        w.key("incidenceWeight"); w.number(l.incidenceWeight);
        w.key("radius"); w.number(l.radius);
        w.endObject();
    }
    w.endArray();
}

std::vector<uint8_t> readWorldLightsMember(const Value& lights, const std::string& context) {
    if (!lights.isArray()) lights.fail(context, "expected an array of lights");
    std::vector<sh::WorldLight> out(lights.size());
    for (size_t i = 0; i < lights.size(); ++i) {
        const std::string c = context + "[" + std::to_string(i) + "]";
        const Value& r = lights.items[i].asObject(c);
        sh::WorldLight& l = out[i];
        l.type = sh::WorldLightType(indexOf(kTypeNames, r.member("type", c), c + ".type"));
        l.falloff = sh::WorldLightFalloff(indexOf(kFalloffNames, r.member("falloff", c), c + ".falloff"));
        const int32_t inGrid = r.member("inShGrid", c).asInt(c + ".inShGrid");
        if (inGrid != 0 && inGrid != 1) r.member("inShGrid", c).fail(c + ".inShGrid", "expected 0 or 1");
        l.flags = inGrid ? sh::kWorldLightInShGrid : 0u;
        l.style = r.member("style", c).asInt(c + ".style");
        l.cluster = r.member("cluster", c).asInt(c + ".cluster");
        readArray(r.member("origin", c), l.origin, c + ".origin");
        readArray(r.member("intensity", c), l.intensity, c + ".intensity");
        readArray(r.member("direction", c), l.direction, c + ".direction");
        readArray(r.member("falloffConstants", c), l.falloffConstants, c + ".falloffConstants");
        readArray(r.member("cone", c), l.cone, c + ".cone");
        l.incidenceWeight = r.member("incidenceWeight", c).asFloat(c + ".incidenceWeight");
        l.radius = r.member("radius", c).asFloat(c + ".radius");
        if (std::string problem = sh::checkWorldLight(l); !problem.empty()) r.fail(c, problem);
    }
    return sh::encodeWorldLights(out);
}

}  // namespace q3::json
