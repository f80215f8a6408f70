// Embree 3 scene of shadow casters and the colour-transmitting shadow rays (see trace_scene.h).
#include "trace_scene.h"

#include <embree3/rtcore.h>
#include <oneapi/tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <tuple>

#include "light_text.h"
#include "log.h"

namespace q3::light {

namespace {

constexpr size_t kInlineHits = 48;

// One translucent crossing. Trivially constructible: the inline list below is never cleared.
struct TranslucentHit {
    float t;
    unsigned geomID;
    unsigned primID;
    float r, g, b;
};

// Translucent hits of one ray, stored inline for the common case (most rays meet none).
struct HitList {
    size_t count = 0;
    TranslucentHit inlineHits[kInlineHits];
    std::vector<TranslucentHit> overflow;

    void add(const TranslucentHit& h) {
        if (count < kInlineHits)
            inlineHits[count++] = h;
        else
            overflow.push_back(h);
    }
    bool empty() const { return count == 0; }
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
        const Vec3 f = filterFactor(r, primID, u, v);
        if (maxComponent(f) <= 0) continue;  // fully opaque texel: a real hit
        ctx->hits->add(TranslucentHit{t, geomID, primID, f.x, f.y, f.z});
        args->valid[i] = 0;  // keep going through the surface
    }
}

// Order-independent product of the translucent crossings of one ray.
Vec3 translucentProduct(HitList& hits) {
    std::vector<TranslucentHit> sorted(hits.inlineHits, hits.inlineHits + hits.count);
    sorted.insert(sorted.end(), hits.overflow.begin(), hits.overflow.end());
    std::sort(sorted.begin(), sorted.end(), [](const TranslucentHit& a, const TranslucentHit& b) {
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
    for (const TranslucentHit& h : sorted) {
        bool duplicate = false;
        for (const auto& [geom, t] : counted)
            if (geom == h.geomID && h.t - t <= kSameCrossing) duplicate = true;
        if (duplicate) continue;
        counted.emplace_back(h.geomID, h.t);
        result *= Vec3{h.r, h.g, h.b};
    }
    return result;
}

RTCRay makeRay(Vec3 from, Vec3 direction, float tnear, float tfar) {
    RTCRay ray{};
    ray.org_x = from.x;
    ray.org_y = from.y;
    ray.org_z = from.z;
    ray.dir_x = direction.x;
    ray.dir_y = direction.y;
    ray.dir_z = direction.z;
    ray.tnear = tnear;
    ray.tfar = tfar;
    ray.mask = 0xFFFFFFFFu;
    ray.flags = 0;
    return ray;
}

RTCScene newScene(RTCDevice device) {
    RTCScene scene = rtcNewScene(device);
    // Robust traversal: grid points and luxels sit on the map's unit lattice and axial sun rays
    // graze brush edges exactly; without it such rays slip between two triangles of one wall.
    rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
    return scene;
}

}  // namespace

struct TraceScene::EmbreeState {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;     // every caster except sky surfaces
    RTCScene skyScene = nullptr;  // sky surfaces
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
    embree_->scene = newScene(embree_->device);
    embree_->skyScene = newScene(embree_->device);

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
        std::vector<Record>& records = rec.sky ? skyRecords_ : records_;
        const unsigned id = rtcAttachGeometry(rec.sky ? embree_->skyScene : embree_->scene, geom);
        rtcReleaseGeometry(geom);
        if (id != records.size()) throw CompileError("embree: unexpected geometry numbering");
        records.push_back(std::move(rec));
    }
    rtcCommitScene(embree_->scene);
    rtcCommitScene(embree_->skyScene);
    if (rtcGetDeviceError(embree_->device) != RTC_ERROR_NONE)
        throw CompileError("embree: building the shadow scene failed");
}

TraceScene::~TraceScene() {
    if (embree_->scene) rtcReleaseScene(embree_->scene);
    if (embree_->skyScene) rtcReleaseScene(embree_->skyScene);
    if (embree_->device) rtcReleaseDevice(embree_->device);
}

void TraceScene::countRay() const {
    const int slot = tbb::this_task_arena::current_thread_index();  // -1 outside any arena
    rays_[static_cast<size_t>(slot < 0 ? 0 : slot) % kRayCounters].rays.fetch_add(1, std::memory_order_relaxed);
}

uint64_t TraceScene::raysTraced() const {
    uint64_t total = 0;
    for (const RayCounter& c : rays_) total += c.rays.load(std::memory_order_relaxed);
    return total;
}

Vec3 TraceScene::occlusion(Vec3 from, Vec3 direction, float tnear, float tfar) const {
    HitList hits;
    RayContext ctx;
    rtcInitIntersectContext(&ctx.base);
    ctx.records = &records_;
    ctx.hits = &hits;
    RTCRay ray = makeRay(from, direction, tnear, tfar);
    rtcOccluded1(embree_->scene, &ctx.base, &ray);
    if (ray.tfar < 0) return {};  // Embree marks an occluded ray with tfar = -inf
    return hits.empty() ? Vec3{1, 1, 1} : translucentProduct(hits);
}

Vec3 TraceScene::transmission(Vec3 from, Vec3 to, float ignoreNear) const {
    Vec3 d = to - from;
    float dist = length(d);
    if (dist <= 0) return {1, 1, 1};
    // Stop just short of the end point so that the receiving/emitting surface itself never blocks.
    float tfar = dist - std::min(0.01f, dist * 0.5f);
    if (tfar <= ignoreNear) return {1, 1, 1};
    countRay();
    const Vec3 dir = d / dist;
    const float tnear = std::max(ignoreNear, 0.0f);
    if (!skyRecords_.empty()) {
        // Sky surfaces block point-light rays like any wall.
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        RTCRay ray = makeRay(from, dir, tnear, tfar);
        rtcOccluded1(embree_->skyScene, &ctx, &ray);
        if (ray.tfar < 0) return {};
    }
    return occlusion(from, dir, tnear, tfar);
}

Vec3 TraceScene::skyTransmission(Vec3 from, Vec3 direction, int skyIndex, float ignoreNear) const {
    countRay();
    if (skyRecords_.empty()) return {};
    const Vec3 dir = normalize(direction);
    const float tnear = std::max(ignoreNear, 0.0f);
    // The nearest sky surface along the ray must be one of this sun's sky...
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRayHit rh{};
    rh.ray = makeRay(from, dir, tnear, std::numeric_limits<float>::infinity());
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(embree_->skyScene, &ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return {};  // escapes the world without meeting the sky
    if (skyIndex >= 0 && skyRecords_[rh.hit.geomID].skyIndex != skyIndex) return {};
    // ...and nothing opaque may stand in front of it.
    return occlusion(from, dir, tnear, rh.ray.tfar);
}

}  // namespace q3::light
