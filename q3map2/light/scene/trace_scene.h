// The shadow-casting world of the -light stage: one Embree 3 device and scene holding every
// surface that can block light. Shadow rays return a colour transmission, not a bool:
// `surfaceparm alphashadow` surfaces attenuate by the light image's alpha and `lightfilter`
// surfaces tint by its colour, at the texture coordinate of the hit. Sky surfaces end sun rays;
// each sun lights only through sky surfaces of its own sky index (unless the sun's index is -1).
//
// Results never depend on the order in which Embree reports hits: translucent hits are
// collected, sorted by distance and surface, de-duplicated and only then multiplied.
//
// Sky surfaces live in a scene of their own: a sun ray first finds the nearest sky surface there
// (a cheap search among few triangles), then asks the scene of all other casters only whether
// anything blocks the way to it. Both questions are any-hit occlusion queries except the sky
// search, so rays stop at the first opaque surface instead of looking for the nearest one.
#pragma once

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "lights.h"
#include "solid_segment_tree.h"
#include "solid_shell.h"
#include "vec3.h"

namespace q3::light {

struct SceneSurface {
    int surfaceNum = -1;
    const LightingShader* shader = nullptr;  // nullptr = plain opaque caster
    std::vector<Vec3> xyz;
    std::vector<float> st;             // 2 per vertex (texture coordinates), may be empty
    std::vector<uint32_t> triangles;   // 3 indices per triangle
    bool isPatch = false;
    int meshWidth = 0, meshHeight = 0;  // patches: xyz is this row-major vertex grid ...
    std::vector<Vec3> normals;          // ... with these (interpolated) vertex normals
    int castShadows = 1;               // shadow group (.srf castShadows, _castShadows); 0 = casts nothing
    int skyIndex = -1;                 // sky index of its shader (only meaningful for sky surfaces)
};

struct TraceSceneOptions {
    bool patchShadows = false;  // -patchshadows: tessellated patches cast shadows
    // False when no sun ray will be traced: the casters' pieces that only sun rays meet are then
    // left out (traceCasterPieces).
    bool sunRays = true;
    // Whether the segment from -> to enters structural solid (the BSP's solid leaves). Any ray that
    // does is blocked (a sun ray up to its sky), as q3map2's TraceLine stops at the first solid leaf
    // whatever the inhibit radius: a ray grazing up a wall that a vertex lies on stays in the dark,
    // and so does the light behind the wall. Empty: no test.
    std::function<bool(Vec3 from, Vec3 to)> solidBetween;
    // The same test for sun rays, up to their sky (q3map2 walks them otherwise: sky_ray_solid.h).
    // Empty: solidBetween.
    std::function<bool(Vec3 from, Vec3 to)> skySolidBetween;
    // Optional shortcut for many rays: clear when no segment inside the convex hull of the points
    // (both ends of each) can enter solid, so solidBetween need not be asked for them; otherwise
    // where their walks may begin (solidBetweenInHull).
    std::function<HullVerdict(std::span<const Vec3> points)> hullClearOfSolid;
    // solidBetween of a segment inside a hull that was not clear, begun where the verdict says.
    // Empty: solidBetween.
    std::function<bool(const HullVerdict& hull, Vec3 from, Vec3 to)> solidBetweenInHull;
    // The same two for sun rays under skySolidBetween's rule. Empty: hullClearOfSolid, and
    // skySolidBetween.
    std::function<HullVerdict(std::span<const Vec3> points)> skyHullClear;
    std::function<bool(const HullVerdict& hull, Vec3 from, Vec3 to)> skySolidBetweenInHull;
    // Cells around solidBetween's solid (solid_shell.h): point-light segments that meet none are
    // not walked. Empty: every segment is.
    SolidShell solidShell;
};

// Every shadow group: the ray mask of rays that any caster may block.
constexpr uint32_t kAllShadowGroups = 0xFFFFFFFFu;

// One shadow ray: a segment [tnear, tfar] towards a light, or (toSky) a ray towards a sun that
// must end on a sky surface of `skyIndex` (-1 = any sky).
struct ShadowRay {
    Vec3 from;
    Vec3 direction;  // unit
    float tnear = 0;
    float tfar = 0;
    bool toSky = false;
    int skyIndex = -1;
    uint32_t mask = kAllShadowGroups;  // shadow groups that may block it (TraceScene::receiverMask)
    bool clearOfSolid = false;         // the caller knows the segment enters no structural solid
};

class TraceScene {
public:
    // Throws CompileError when Embree cannot be initialised. `sunOnly`: opaque casters that stop sun
    // rays alone (traceCasterPieces' forSunOnly), each in its surface's shadow group.
    TraceScene(const std::vector<SceneSurface>& surfaces, const TraceSceneOptions& options,
               const std::vector<SceneSurface>& sunOnly = {});
    ~TraceScene();
    TraceScene(const TraceScene&) = delete;
    TraceScene& operator=(const TraceScene&) = delete;

    // Whether a surface of this kind blocks light at all (trans/nodraw/fog do not, unless they
    // alpha-shadow or filter; patches only with -patchshadows; entities whose castShadows is 0 do
    // not).
    static bool castsShadow(const SceneSurface& surface, const TraceSceneOptions& options);

    // Colour transmitted from `from` to `to` (1 1 1 = unobstructed, 0 0 0 = blocked). Occluders
    // closer than `ignoreNear` to `from` are ignored. Sky surfaces block like any wall.
    // `clearOfSolid`: the caller knows the segment enters no structural solid (no tree walk).
    Vec3 transmission(Vec3 from, Vec3 to, float ignoreNear = 0, uint32_t mask = kAllShadowGroups,
                      bool clearOfSolid = false) const;

    // Colour transmitted from `from` along `direction` (unit) to the sky. Zero unless the first
    // opaque surface met is a sky surface whose index matches `skyIndex` (-1 accepts any sky).
    Vec3 skyTransmission(Vec3 from, Vec3 direction, int skyIndex, float ignoreNear = 0,
                         uint32_t mask = kAllShadowGroups) const;

    // TraceSceneOptions::solidBetween (false without one).
    bool crossesSolid(Vec3 from, Vec3 to) const { return solidBetween_ && solidBetween_(from, to); }
    // TraceSceneOptions::skySolidBetween, or crossesSolid without one.
    bool skyRayCrossesSolid(Vec3 from, Vec3 to) const {
        return skySolidBetween_ ? skySolidBetween_(from, to) : crossesSolid(from, to);
    }

    // Ray mask of a receiver in shadow group `receiveShadows`, with q3map2's rules: group 1 (the
    // world) is shadowed by casters of group 1 only; a group above 1 by group 1 and its own casters;
    // a negative group by casters whose group has the same magnitude; 0 by nothing.
    uint32_t receiverMask(int receiveShadows) const;

    // The depth a ray starts at when occluders up to `ignoreNear` are ignored: q3map2 passes a hit
    // at exactly the inhibit radius (TraceTriangle skips depth <= inhibitRadius), so a grid point
    // half a cell below a sky face does not see that sky and its sun ray runs on into the solid.
    // Inline with segmentRay: both are asked once per shadow ray. For a positive finite float the
    // next one up is the next bit pattern.
    static float firstTestedDepth(float ignoreNear) {
        if (!(ignoreNear > 0)) return 0.0f;
        if (!(ignoreNear < std::numeric_limits<float>::infinity())) return ignoreNear;
        return std::bit_cast<float>(std::bit_cast<uint32_t>(ignoreNear) + 1u);
    }
    // The ray transmission() traces from `from` to `to`; nullopt when nothing can block it.
    static std::optional<ShadowRay> segmentRay(Vec3 from, Vec3 to, float ignoreNear = 0) {
        const Vec3 d = to - from;
        const float dist = length(d);
        if (dist <= 0) return std::nullopt;
        return segmentRayAlong(from, d / dist, dist, ignoreNear);
    }
    // segmentRay for a caller that already has the segment's length and unit direction
    // (length(to - from) and (to - from) / length, as segmentRay computes them).
    static std::optional<ShadowRay> segmentRayAlong(Vec3 from, Vec3 direction, float dist, float ignoreNear = 0) {
        if (dist <= 0) return std::nullopt;
        // Stop just short of the end point so that the receiving/emitting surface itself never blocks.
        const float tfar = dist - std::min(0.01f, dist * 0.5f);
        if (tfar <= ignoreNear) return std::nullopt;
        return ShadowRay{from, direction, firstTestedDepth(ignoreNear), tfar, false, -1, kAllShadowGroups};
    }
    // The ray skyTransmission() traces.
    static ShadowRay skyRay(Vec3 from, Vec3 direction, int skyIndex, float ignoreNear = 0);
    // Transmission of many rays at once (out[i] for rays[i]), traced as Embree ray streams: cheaper
    // per ray when the rays are coherent (one sun over many luxels). `coherent` false: rays that
    // spread from one point to many lights. The answers are one call per ray's, but for rays running
    // along an axial plane: inside a wall's plane Embree's packet and single-ray kernels may disagree,
    // and `axialRaysAlone` traces those one by one to keep the single-ray answer.
    void traceBatch(std::span<const ShadowRay> rays, std::span<Vec3> out, bool coherent = true,
                    bool axialRaysAlone = false) const;

    // Casters of the same group magnitude share one bit of the Embree geometry mask (bit 0 for
    // group 1); beyond 31 other groups, the last bit is shared.
    uint32_t groupBit(int castShadows) const;

    size_t casterCount() const { return casters_; }
    uint64_t raysTraced() const;

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

    static constexpr size_t kBatchChunk = 64;
    Vec3 traceOne(const ShadowRay& ray) const;     // counted
    Vec3 traceSingle(const ShadowRay& ray) const;  // traceOne's work, not counted
    bool blockedForSunOnly(const ShadowRay& ray, float tfar) const;
    void traceChunk(std::span<const ShadowRay> rays, std::span<Vec3> out, bool coherent, bool axialRaysAlone) const;
    void countRays(size_t n) const;
    // A ray's mask in the casters' scene: segment rays of a receiver that the sky's group shadows
    // meet the sky surfaces there (skySegmentBit_), sun rays never do.
    uint32_t casterMask(uint32_t mask, bool toSky) const {
        const uint32_t groups = mask & ~skySegmentBit_;
        return toSky || !(mask & skySegmentGroup_) ? groups : groups | skySegmentBit_;
    }

    struct EmbreeState;
    std::unique_ptr<EmbreeState> embree_;
    std::vector<Record> records_;     // casters other than sky (then the sky copies), by Embree geometry id
    std::vector<Record> skyRecords_;  // sky surfaces, indexed by geometry id of the sky scene
    std::vector<int> groupOfBit_;     // group magnitude of each mask bit (bit 0 = group 1)
    size_t casters_ = 0;              // surfaces that cast shadows (sky surfaces once)
    uint32_t skySegmentBit_ = 0;      // mask of the sky surfaces' copies in the casters' scene (0: none)
    uint32_t skySegmentGroup_ = 0;    // the group bit of every sky surface, when they have copies
    std::function<bool(Vec3, Vec3)> solidBetween_;
    std::function<bool(Vec3, Vec3)> skySolidBetween_;
    std::function<HullVerdict(std::span<const Vec3>)> hullClearOfSolid_;
    std::function<HullVerdict(std::span<const Vec3>)> skyHullClear_;
    std::function<bool(const HullVerdict&, Vec3, Vec3)> solidBetweenInHull_;
    std::function<bool(const HullVerdict&, Vec3, Vec3)> skySolidBetweenInHull_;
    SolidShell shell_;
    // Rays counted per worker thread (one cache line each) so that counting never makes the
    // threads fight over one shared counter.
    struct alignas(64) RayCounter {
        std::atomic<uint64_t> rays{0};
    };
    static constexpr size_t kRayCounters = 64;
    mutable std::array<RayCounter, kRayCounters> rays_;
};

}  // namespace q3::light
