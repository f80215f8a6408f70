// Embree 3 scene of shadow casters and the colour-transmitting shadow rays (see trace_scene.h).
#include "trace_scene.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <tuple>

#include "light_text.h"
#include "log.h"

namespace q3::light {

struct TraceScene::Hit {
    float t;
    unsigned geomID;
    unsigned primID;
    Vec3 factor;
};

namespace {

constexpr size_t kInlineHits = 48;

// Translucent hits of one ray, stored inline for the common case.
struct HitList {
    size_t count = 0;
    std::array<float, kInlineHits> t{};
    std::array<unsigned, kInlineHits> geom{};
    std::array<unsigned, kInlineHits> prim{};
    std::array<Vec3, kInlineHits> factor{};
    std::vector<std::tuple<float, unsigned, unsigned, Vec3>> overflow;

    void add(float tt, unsigned g, unsigned p, Vec3 f) {
        if (count < kInlineHits) {
            t[count] = tt;
            geom[count] = g;
            prim[count] = p;
            factor[count] = f;
            ++count;
        } else {
            overflow.emplace_back(tt, g, p, f);
        }
    }
};

// Embree passes our context back to the filter: the Embree part must come first.
struct RayContext {
    RTCIntersectContext base;
    const std::vector<TraceScene::Record>* records;
    HitList* hits;
};

// Transmission of one translucent surface at barycentric (u, v) of triangle `prim`.
Vec3 filterFactor(const TraceScene::Record& r, unsigned prim, float u, float v) {
    const LightingShader& sh = *r.shader;
    const LightImage* image = sh.lightImage;
    if (!image || image->width <= 0 || r.st.empty()) return {};  // nothing to see through: opaque
    const uint32_t i0 = r.triangles[prim * 3], i1 = r.triangles[prim * 3 + 1], i2 = r.triangles[prim * 3 + 2];
    const float w = 1 - u - v;
    const float s = w * r.st[i0 * 2] + u * r.st[i1 * 2] + v * r.st[i2 * 2];
    const float t = w * r.st[i0 * 2 + 1] + u * r.st[i1 * 2 + 1] + v * r.st[i2 * 2 + 1];
    const uint8_t* px = image->texel(s, t);
    if (!px) return {};
    Vec3 f{1, 1, 1};
    if (sh.lightFilter) f *= Vec3{px[0] / 255.0f, px[1] / 255.0f, px[2] / 255.0f};
    if (sh.alphaShadow) f *= (255.0f - px[3]) / 255.0f;
    return f;
}

void collectTranslucentHits(const RTCFilterFunctionNArguments* args) {
    const RayContext* ctx = reinterpret_cast<const RayContext*>(args->context);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        const unsigned geomID = RTCHitN_geomID(args->hit, args->N, i);
        const TraceScene::Record& r = (*ctx->records)[geomID];
        if (!r.filters) continue;  // opaque or sky: accept the hit
        const unsigned primID = RTCHitN_primID(args->hit, args->N, i);
        const float u = RTCHitN_u(args->hit, args->N, i);
        const float v = RTCHitN_v(args->hit, args->N, i);
        const float t = RTCRayN_tfar(args->ray, args->N, i);
        Vec3 f = filterFactor(r, primID, u, v);
        if (maxComponent(f) <= 0) continue;  // fully opaque texel: a real hit
        ctx->hits->add(t, geomID, primID, f);
        args->valid[i] = 0;  // keep going through the surface
    }
}

}  // namespace

struct TraceScene::EmbreeState {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
};

bool TraceScene::castsShadow(const SceneSurface& surface, const TraceSceneOptions& options) {
    if (surface.triangles.empty() || !surface.castShadows) return false;
    if (surface.isPatch && !options.patchShadows) return false;
    const LightingShader* sh = surface.shader;
    if (!sh) return true;
    const bool filters = sh->alphaShadow || sh->lightFilter;
    if (filters) return true;
    if (sh->sky) return true;
    if (sh->translucent || sh->nodraw || sh->fog) return false;
    return true;
}

TraceScene::TraceScene(const std::vector<SceneSurface>& surfaces, const TraceSceneOptions& options)
    : embree_(std::make_unique<EmbreeState>()) {
    embree_->device = rtcNewDevice(nullptr);
    if (!embree_->device) throw CompileError("embree: cannot create a ray-tracing device");
    embree_->scene = rtcNewScene(embree_->device);
    rtcSetSceneFlags(embree_->scene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(embree_->scene, RTC_BUILD_QUALITY_HIGH);

    for (const SceneSurface& s : surfaces) {
        if (!castsShadow(s, options)) continue;
        RTCGeometry geom = rtcNewGeometry(embree_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
        const size_t numVerts = s.xyz.size();
        const size_t numTris = s.triangles.size() / 3;
        auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                               3 * sizeof(float), numVerts));
        for (size_t i = 0; i < numVerts; ++i) s.xyz[i].toArray(vb + i * 3);
        auto* ib = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                  3 * sizeof(unsigned), numTris));
        for (size_t i = 0; i < numTris * 3; ++i) {
            uint32_t idx = s.triangles[i];
            ib[i] = idx < numVerts ? idx : 0;
        }
        Record rec;
        rec.shader = s.shader;
        rec.sky = s.shader && s.shader->sky;
        rec.filters = s.shader && (s.shader->alphaShadow || s.shader->lightFilter) && !rec.sky;
        rec.skyIndex = s.skyIndex;
        if (rec.filters) {
            rec.st = s.st;
            rec.triangles.assign(ib, ib + numTris * 3);
            if (rec.st.size() < numVerts * 2) rec.st.clear();
            rtcSetGeometryIntersectFilterFunction(geom, collectTranslucentHits);
        }
        rtcCommitGeometry(geom);
        unsigned id = rtcAttachGeometry(embree_->scene, geom);
        rtcReleaseGeometry(geom);
        if (id != records_.size()) throw CompileError("embree: unexpected geometry numbering");
        records_.push_back(std::move(rec));
    }
    rtcCommitScene(embree_->scene);
    if (rtcGetDeviceError(embree_->device) != RTC_ERROR_NONE)
        throw CompileError("embree: building the shadow scene failed");
}

TraceScene::~TraceScene() {
    if (embree_->scene) rtcReleaseScene(embree_->scene);
    if (embree_->device) rtcReleaseDevice(embree_->device);
}

Vec3 TraceScene::trace(Vec3 from, Vec3 direction, float tfar, float ignoreNear, bool toSky, int skyIndex) const {
    rays_.fetch_add(1, std::memory_order_relaxed);
    HitList hits;
    RayContext ctx;
    rtcInitIntersectContext(&ctx.base);
    ctx.records = &records_;
    ctx.hits = &hits;

    RTCRayHit rh{};
    rh.ray.org_x = from.x;
    rh.ray.org_y = from.y;
    rh.ray.org_z = from.z;
    rh.ray.dir_x = direction.x;
    rh.ray.dir_y = direction.y;
    rh.ray.dir_z = direction.z;
    rh.ray.tnear = std::max(ignoreNear, 0.0f);
    rh.ray.tfar = tfar;
    rh.ray.mask = 0xFFFFFFFFu;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(embree_->scene, &ctx.base, &rh);

    float end = tfar;
    if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
        const Record& r = records_[rh.hit.geomID];
        if (!toSky || !r.sky) return {};
        if (skyIndex >= 0 && r.skyIndex != skyIndex) return {};
        end = rh.ray.tfar;
    } else if (toSky) {
        return {};  // escaped the world without meeting the sky
    }

    // Order-independent product of the translucent surfaces in front of the end point.
    std::vector<Hit> sorted;
    sorted.reserve(hits.count + hits.overflow.size());
    for (size_t i = 0; i < hits.count; ++i) sorted.push_back({hits.t[i], hits.geom[i], hits.prim[i], hits.factor[i]});
    for (const auto& [t, g, p, f] : hits.overflow) sorted.push_back({t, g, p, f});
    std::sort(sorted.begin(), sorted.end(), [](const Hit& a, const Hit& b) {
        if (a.t != b.t) return a.t < b.t;
        if (a.geomID != b.geomID) return a.geomID < b.geomID;
        return a.primID < b.primID;
    });
    // A ray through a shared triangle edge reports the same crossing of a surface twice (once per
    // triangle), and Embree may report one triangle more than once: such hits of one surface within
    // kSameCrossing of the previous counted one are the same crossing and count once.
    constexpr float kSameCrossing = 0.01f;
    Vec3 result{1, 1, 1};
    std::vector<std::pair<unsigned, float>> counted;  // (surface, distance) of counted crossings
    for (const Hit& h : sorted) {
        if (h.t >= end) break;
        bool duplicate = false;
        for (const auto& [geom, t] : counted)
            if (geom == h.geomID && h.t - t <= kSameCrossing) duplicate = true;
        if (duplicate) continue;
        counted.emplace_back(h.geomID, h.t);
        result *= h.factor;
    }
    return result;
}

Vec3 TraceScene::transmission(Vec3 from, Vec3 to, float ignoreNear) const {
    Vec3 d = to - from;
    float dist = length(d);
    if (dist <= 0) return {1, 1, 1};
    // Stop just short of the end point so that the receiving/emitting surface itself never blocks.
    float tfar = dist - std::min(0.01f, dist * 0.5f);
    if (tfar <= ignoreNear) return {1, 1, 1};
    return trace(from, d / dist, tfar, ignoreNear, false, -1);
}

Vec3 TraceScene::skyTransmission(Vec3 from, Vec3 direction, int skyIndex, float ignoreNear) const {
    return trace(from, normalize(direction), std::numeric_limits<float>::infinity(), ignoreNear, true, skyIndex);
}

}  // namespace q3::light
