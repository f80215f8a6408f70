// The shadow-casting world of the -light stage: one Embree 3 device and scene holding every
// surface that can block light. Shadow rays return a colour transmission, not a bool:
// `surfaceparm alphashadow` surfaces attenuate by the light image's alpha and `lightfilter`
// surfaces tint by its colour, at the texture coordinate of the hit. Sky surfaces end sun rays;
// each sun lights only through sky surfaces of its own sky index (unless the sun's index is -1).
//
// Results never depend on the order in which Embree reports hits: translucent hits are
// collected, sorted by distance and surface, de-duplicated and only then multiplied.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include "lights.h"
#include "vec3.h"

namespace q3::light {

struct SceneSurface {
    int surfaceNum = -1;
    const LightingShader* shader = nullptr;  // nullptr = plain opaque caster
    std::vector<Vec3> xyz;
    std::vector<float> st;             // 2 per vertex (texture coordinates), may be empty
    std::vector<uint32_t> triangles;   // 3 indices per triangle
    bool isPatch = false;
    bool castShadows = true;           // shadow group of its entity (.srf castShadows, _castShadows)
    int skyIndex = -1;                 // sky index of its shader (only meaningful for sky surfaces)
};

struct TraceSceneOptions {
    bool patchShadows = false;  // -patchshadows: tessellated patches cast shadows
};

class TraceScene {
public:
    // Throws CompileError when Embree cannot be initialised.
    TraceScene(const std::vector<SceneSurface>& surfaces, const TraceSceneOptions& options);
    ~TraceScene();
    TraceScene(const TraceScene&) = delete;
    TraceScene& operator=(const TraceScene&) = delete;

    // Whether a surface of this kind blocks light at all (trans/nodraw/fog do not, unless they
    // alpha-shadow or filter; patches only with -patchshadows; entities whose castShadows is 0 do
    // not).
    static bool castsShadow(const SceneSurface& surface, const TraceSceneOptions& options);

    // Colour transmitted from `from` to `to` (1 1 1 = unobstructed, 0 0 0 = blocked). Occluders
    // closer than `ignoreNear` to `from` are ignored. Sky surfaces block like any wall.
    Vec3 transmission(Vec3 from, Vec3 to, float ignoreNear = 0) const;

    // Colour transmitted from `from` along `direction` (unit) to the sky. Zero unless the first
    // opaque surface met is a sky surface whose index matches `skyIndex` (-1 accepts any sky).
    Vec3 skyTransmission(Vec3 from, Vec3 direction, int skyIndex, float ignoreNear = 0) const;

    size_t casterCount() const { return records_.size(); }
    uint64_t raysTraced() const { return rays_.load(std::memory_order_relaxed); }

    // Per-geometry data read by the Embree filter callback.
    struct Record {
        const LightingShader* shader = nullptr;
        bool sky = false;
        bool filters = false;  // alphashadow or lightfilter: attenuates instead of blocking
        int skyIndex = -1;
        std::vector<float> st;
        std::vector<uint32_t> triangles;
    };

private:
    struct Hit;
    Vec3 trace(Vec3 from, Vec3 direction, float tfar, float ignoreNear, bool toSky, int skyIndex) const;

    struct EmbreeState;
    std::unique_ptr<EmbreeState> embree_;
    std::vector<Record> records_;  // indexed by Embree geometry id
    mutable std::atomic<uint64_t> rays_{0};
};

}  // namespace q3::light
