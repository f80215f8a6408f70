// Embree 3 scene of shadow casters and the colour-transmitting shadow rays (see trace_scene.h).
#include "trace_scene.h"

#include <embree3/rtcore.h>
#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <span>
#include <tuple>

#include "embree_ray.h"
#include "light_text.h"
#include "log.h"

namespace q3::light {

namespace {

constexpr size_t kInlineHits = 48;

// One translucent crossing. Trivially constructible: the inline list below is never cleared.
struct TranslucentHit {
    unsigned rayId;  // index of the ray in its batch (0 for single rays)
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
        const unsigned rayId = RTCRayN_id(args->ray, args->N, i);
        ctx->hits->add(TranslucentHit{rayId, t, geomID, primID, f.x, f.y, f.z});
        args->valid[i] = 0;  // keep going through the surface
    }
}

// Every hit of a list, sorted by ray, distance, surface and triangle: the order no longer depends
// on how Embree found them.
std::vector<TranslucentHit> sortedHits(const HitList& hits) {
    std::vector<TranslucentHit> sorted(hits.inlineHits, hits.inlineHits + hits.count);
    sorted.insert(sorted.end(), hits.overflow.begin(), hits.overflow.end());
    std::sort(sorted.begin(), sorted.end(), [](const TranslucentHit& a, const TranslucentHit& b) {
        if (a.rayId != b.rayId) return a.rayId < b.rayId;
        if (a.t != b.t) return a.t < b.t;
        if (a.geomID != b.geomID) return a.geomID < b.geomID;
        return a.primID < b.primID;
    });
    return sorted;
}

// Product of the translucent crossings of one ray (its hits, sorted).
Vec3 translucentProduct(std::span<const TranslucentHit> sorted) {
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

RTCRay makeRay(const ShadowRay& r, float tfar) {
    RTCRay ray;
    setRay(ray, r.from, r.direction, r.tnear, tfar, 0, r.mask);
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

// The solid shell's cells as Embree user primitives: bounded by their boxes, met by a segment
// (org + t dir, tnear <= t <= tfar) when the part of it inside every plane of the cell is not
// empty (the segment clipped plane by plane, in double).
void shellCellBounds(const RTCBoundsFunctionArguments* args) {
    const Bounds& b = static_cast<const SolidShell*>(args->geometryUserPtr)->boxes[args->primID];
    RTCBounds* out = args->bounds_o;
    out->lower_x = b.mins.x, out->lower_y = b.mins.y, out->lower_z = b.mins.z;
    out->upper_x = b.maxs.x, out->upper_y = b.maxs.y, out->upper_z = b.maxs.z;
}

void shellCellOccluded(const RTCOccludedFunctionNArguments* args) {
    const SolidShell& shell = *static_cast<const SolidShell*>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        RTCRayN* ray = args->ray;
        const DVec3 org{RTCRayN_org_x(ray, args->N, i), RTCRayN_org_y(ray, args->N, i),
                        RTCRayN_org_z(ray, args->N, i)};
        const DVec3 dir{RTCRayN_dir_x(ray, args->N, i), RTCRayN_dir_y(ray, args->N, i),
                        RTCRayN_dir_z(ray, args->N, i)};
        float& tfar = RTCRayN_tfar(ray, args->N, i);
        if (shell.segmentMeetsCell(args->primID, org, dir, RTCRayN_tnear(ray, args->N, i), tfar))
            tfar = -std::numeric_limits<float>::infinity();
    }
}

RTCScene newShellScene(RTCDevice device, const SolidShell& shell) {
    RTCScene scene = newScene(device);
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(geom, unsigned(shell.boxes.size()));
    auto* user = const_cast<SolidShell*>(&shell);
    rtcSetGeometryUserData(geom, user);
    rtcSetGeometryBoundsFunction(geom, shellCellBounds, user);
    rtcSetGeometryOccludedFunction(geom, shellCellOccluded);
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene, geom);
    rtcReleaseGeometry(geom);
    rtcCommitScene(scene);
    return scene;
}

}  // namespace

struct TraceScene::EmbreeState {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;       // every caster except sky surfaces
    RTCScene skyScene = nullptr;    // sky surfaces
    RTCScene shellScene = nullptr;  // the solid shell's cells, when there are any
    RTCScene sunOnlyScene = nullptr;  // opaque casters that only sun rays meet, when there are any
};

bool TraceScene::castsShadow(const SceneSurface& surface, const TraceSceneOptions& options) {
    if (surface.triangles.empty() || surface.castShadows == 0) return false;
    if (surface.isPatch && !options.patchShadows) return false;
    const LightingShader* sh = surface.shader;
    if (!sh) return true;
    const bool filters = sh->alphaShadow || sh->lightFilter;
    if (filters) return true;
    if (sh->sky) return true;
    if (sh->translucent || sh->nodraw || sh->fog) return false;
    return true;
}

TraceScene::TraceScene(const std::vector<SceneSurface>& surfaces, const TraceSceneOptions& options,
                       const std::vector<SceneSurface>& sunOnly)
    : embree_(std::make_unique<EmbreeState>()),
      solidBetween_(options.solidBetween),
      skySolidBetween_(options.skySolidBetween),
      hullClearOfSolid_(options.hullClearOfSolid),
      skyHullClear_(options.skyHullClear ? options.skyHullClear : options.hullClearOfSolid),
      solidBetweenInHull_(options.solidBetweenInHull),
      skySolidBetweenInHull_(options.skyHullClear ? options.skySolidBetweenInHull : nullptr),
      shell_(options.solidShell) {
    embree_->device = rtcNewDevice(nullptr);
    if (!embree_->device) throw CompileError("embree: cannot create a ray-tracing device");
    embree_->scene = newScene(embree_->device);
    embree_->skyScene = newScene(embree_->device);

    groupOfBit_ = {1};
    auto addGroupOf = [this](const SceneSurface& s) {
        const int group = std::abs(s.castShadows);
        if (group != 1 && groupOfBit_.size() < 32 &&
            std::find(groupOfBit_.begin(), groupOfBit_.end(), group) == groupOfBit_.end())
            groupOfBit_.push_back(group);
    };
    for (const SceneSurface& s : surfaces)
        if (castsShadow(s, options)) addGroupOf(s);
    for (const SceneSurface& s : sunOnly)
        if (!s.triangles.empty()) addGroupOf(s);
    // A caster's triangles as an Embree geometry with the given mask.
    auto newTriangles = [this](const SceneSurface& s, uint32_t mask) {
        RTCGeometry geom = rtcNewGeometry(embree_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
        rtcSetGeometryMask(geom, mask);
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
        return geom;
    };
    // Point-light segments meet sky surfaces as walls. When every sky caster is in one shadow group
    // and a mask bit is free, the sky surfaces also join the casters' scene under that bit alone,
    // which only segment rays carry: one traversal then answers for both.
    std::vector<const SceneSurface*> skyCasters;
    std::optional<uint32_t> skyGroup;
    bool oneSkyGroup = true;
    for (const SceneSurface& s : surfaces) {
        if (!castsShadow(s, options) || !(s.shader && s.shader->sky)) continue;
        skyCasters.push_back(&s);
        if (skyGroup && *skyGroup != groupBit(s.castShadows)) oneSkyGroup = false;
        skyGroup = groupBit(s.castShadows);
    }
    if (skyGroup && oneSkyGroup && *skyGroup != 0 && groupOfBit_.size() < 32) {
        skySegmentBit_ = 1u << groupOfBit_.size();
        skySegmentGroup_ = *skyGroup;
    }
    // Each caster's geometry made on the threads (copying the buffers is most of the set-up),
    // then attached in surface order, which the geometry ids follow.
    struct Made {
        RTCGeometry geom = nullptr;
        Record rec;
    };
    std::vector<Made> made(surfaces.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, surfaces.size(), 16), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i != r.end(); ++i) {
            const SceneSurface& s = surfaces[i];
            if (!castsShadow(s, options)) continue;
            RTCGeometry geom = newTriangles(s, groupBit(s.castShadows));
            const size_t numVerts = s.xyz.size();
            const size_t numTris = s.triangles.size() / 3;
            Record& rec = made[i].rec;
            rec.shader = s.shader;
            rec.sky = s.shader && s.shader->sky;
            rec.filters = s.shader && (s.shader->alphaShadow || s.shader->lightFilter) && !rec.sky;
            rec.skyIndex = s.skyIndex;
            if (rec.filters) {
                rec.st = s.st;
                const auto* ib = static_cast<const unsigned*>(rtcGetGeometryBufferData(geom, RTC_BUFFER_TYPE_INDEX, 0));
                rec.triangles.assign(ib, ib + numTris * 3);
                if (rec.st.size() < numVerts * 2) rec.st.clear();
                // Shadow rays are occlusion queries: only the occlusion filter is ever called.
                rtcSetGeometryOccludedFilterFunction(geom, collectTranslucentHits);
            }
            rtcCommitGeometry(geom);
            made[i].geom = geom;
        }
    });
    for (Made& m : made) {
        if (!m.geom) continue;
        std::vector<Record>& records = m.rec.sky ? skyRecords_ : records_;
        const unsigned id = rtcAttachGeometry(m.rec.sky ? embree_->skyScene : embree_->scene, m.geom);
        rtcReleaseGeometry(m.geom);
        if (id != records.size()) throw CompileError("embree: unexpected geometry numbering");
        records.push_back(std::move(m.rec));
    }
    casters_ = records_.size() + skyRecords_.size();
    if (skySegmentBit_ != 0)
        for (const SceneSurface* s : skyCasters) {
            RTCGeometry geom = newTriangles(*s, skySegmentBit_);
            rtcCommitGeometry(geom);
            const unsigned id = rtcAttachGeometry(embree_->scene, geom);
            rtcReleaseGeometry(geom);
            if (id != records_.size()) throw CompileError("embree: unexpected geometry numbering");
            Record rec;
            rec.shader = s->shader;
            rec.sky = true;
            rec.skyIndex = s->skyIndex;
            records_.push_back(std::move(rec));
        }
    for (const SceneSurface& s : sunOnly) {
        if (s.triangles.empty()) continue;
        if (!embree_->sunOnlyScene) embree_->sunOnlyScene = newScene(embree_->device);
        RTCGeometry geom = newTriangles(s, groupBit(s.castShadows));
        rtcCommitGeometry(geom);
        rtcAttachGeometry(embree_->sunOnlyScene, geom);
        rtcReleaseGeometry(geom);
    }
    rtcCommitScene(embree_->scene);
    rtcCommitScene(embree_->skyScene);
    if (embree_->sunOnlyScene) rtcCommitScene(embree_->sunOnlyScene);
    if (!shell_.empty() && solidBetweenInHull_)
        embree_->shellScene = newShellScene(embree_->device, shell_);
    if (rtcGetDeviceError(embree_->device) != RTC_ERROR_NONE)
        throw CompileError("embree: building the shadow scene failed");
}

TraceScene::~TraceScene() {
    if (embree_->scene) rtcReleaseScene(embree_->scene);
    if (embree_->skyScene) rtcReleaseScene(embree_->skyScene);
    if (embree_->shellScene) rtcReleaseScene(embree_->shellScene);
    if (embree_->sunOnlyScene) rtcReleaseScene(embree_->sunOnlyScene);
    if (embree_->device) rtcReleaseDevice(embree_->device);
}

uint64_t TraceScene::raysTraced() const {
    uint64_t total = 0;
    for (const RayCounter& c : rays_) total += c.rays.load(std::memory_order_relaxed);
    return total;
}

uint32_t TraceScene::groupBit(int castShadows) const {
    const int group = std::abs(castShadows);
    for (size_t bit = 0; bit < groupOfBit_.size(); ++bit)
        if (groupOfBit_[bit] == group) return 1u << bit;
    return groupOfBit_.size() >= 32 ? 1u << 31 : 0u;
}

uint32_t TraceScene::receiverMask(int receiveShadows) const {
    if (receiveShadows == 0) return 0;
    if (receiveShadows == 1) return groupBit(1);
    if (receiveShadows > 1) return groupBit(1) | groupBit(receiveShadows);
    return groupBit(receiveShadows);
}

ShadowRay TraceScene::skyRay(Vec3 from, Vec3 direction, int skyIndex, float ignoreNear) {
    return ShadowRay{from, normalize(direction), firstTestedDepth(ignoreNear), std::numeric_limits<float>::infinity(),
                     true, skyIndex, kAllShadowGroups};
}

Vec3 TraceScene::transmission(Vec3 from, Vec3 to, float ignoreNear, uint32_t mask, bool clearOfSolid) const {
    std::optional<ShadowRay> ray = segmentRay(from, to, ignoreNear);
    if (!ray) return !clearOfSolid && crossesSolid(from, to) ? Vec3{} : Vec3{1, 1, 1};  // too short for occluders
    ray->mask = mask;
    ray->clearOfSolid = clearOfSolid;
    return traceOne(*ray);
}

Vec3 TraceScene::skyTransmission(Vec3 from, Vec3 direction, int skyIndex, float ignoreNear, uint32_t mask) const {
    ShadowRay ray = skyRay(from, direction, skyIndex, ignoreNear);
    ray.mask = mask;
    return traceOne(ray);
}

void TraceScene::countRays(size_t n) const {
    const int slot = tbb::this_task_arena::current_thread_index();  // -1 outside any arena
    // One writer per slot at a time (a worker thread, or the calling thread outside the arenas,
    // which runs as slot 0 inside them): a plain load and store, without the locked add that made
    // counting cost as much as a short ray.
    std::atomic<uint64_t>& counter = rays_[static_cast<size_t>(slot < 0 ? 0 : slot) % kRayCounters].rays;
    counter.store(counter.load(std::memory_order_relaxed) + n, std::memory_order_relaxed);
}

// The single-ray form of traceBatch, without any allocation.
Vec3 TraceScene::traceOne(const ShadowRay& r) const {
    countRays(1);
    return traceSingle(r);
}

Vec3 TraceScene::traceSingle(const ShadowRay& r) const {
    RTCIntersectContext plain;
    rtcInitIntersectContext(&plain);
    float tfar = r.tfar;
    if (r.toSky) {
        if (skyRecords_.empty()) return {};
        RTCRayHit rh{};
        setRayHit(rh, r.from, r.direction, r.tnear, r.tfar, 0, r.mask);
        rtcIntersect1(embree_->skyScene, &plain, &rh);
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return {};  // escapes without meeting the sky
        if (r.skyIndex >= 0 && skyRecords_[rh.hit.geomID].skyIndex != r.skyIndex) return {};
        tfar = rh.ray.tfar;  // the structural solid test waits until the casters leave it open
    } else if (!skyRecords_.empty() && skySegmentBit_ == 0) {
        RTCRay ray = makeRay(r, tfar);
        rtcOccluded1(embree_->skyScene, &plain, &ray);
        if (ray.tfar < 0) return {};  // sky surfaces block point-light rays like walls
    }
    HitList hits;
    RayContext ctx;
    rtcInitIntersectContext(&ctx.base);
    ctx.records = &records_;
    ctx.hits = &hits;
    RTCRay ray = makeRay(r, tfar);
    ray.mask = casterMask(r.mask, r.toSky);
    rtcOccluded1(embree_->scene, &ctx.base, &ray);
    if (ray.tfar < 0) return {};  // Embree marks an occluded ray with tfar = -inf
    if (r.toSky && blockedForSunOnly(r, tfar)) return {};
    // Open rays still stop at structural solid: sun rays up to their sky, the others to their end.
    if (!r.clearOfSolid && (r.toSky ? skyRayCrossesSolid(r.from, r.from + r.direction * tfar)
                                    : crossesSolid(r.from, r.from + r.direction * r.tfar)))
        return {};
    return hits.empty() ? Vec3{1, 1, 1} : translucentProduct(sortedHits(hits));
}

bool TraceScene::blockedForSunOnly(const ShadowRay& r, float tfar) const {
    if (!embree_->sunOnlyScene) return false;
    RTCIntersectContext plain;
    rtcInitIntersectContext(&plain);
    RTCRay ray = makeRay(r, tfar);
    ray.mask = casterMask(r.mask, true);
    rtcOccluded1(embree_->sunOnlyScene, &plain, &ray);
    return ray.tfar < 0;
}

namespace {

// Both ends of the segments of one chunk of rays that still need the structural solid test, and
// the chunk slot of each.
struct ChunkSegments {
    std::array<Vec3, 128> ends;
    std::array<uint8_t, 64> slots;
    size_t count = 0;  // segments
    void add(size_t slot, Vec3 from, Vec3 to) {
        if (count >= slots.size()) return;
        slots[count] = uint8_t(slot);
        ends[2 * count] = from;
        ends[2 * count + 1] = to;
        ++count;
    }
};

// The points whose hull a hull walk tests for a chunk: every start, then the ends, or when the
// ends all lie in a small box (the segments of one point light end a hundredth of a unit short of
// it, each rounded on its own path) that box's corners. The corners hold every end, so the hull
// only grows by that box and a clear verdict stays sound; the walk reads every point at each
// plane that cuts the hull's box, and 8 corners stand for up to 64 ends.
size_t hullPoints(const ChunkSegments& segs, std::array<Vec3, 128>& out) {
    constexpr float kSmall = 0.25f;
    Vec3 lo = segs.ends[1], hi = lo;
    float sum = 0;  // NaN or infinite when any end is: those keep every end (the walk refuses them)
    for (size_t i = 0; i < segs.count; ++i) {
        const Vec3 p = segs.ends[2 * i + 1];
        out[i] = segs.ends[2 * i];
        sum += p.x + p.y + p.z;
        lo = vmin(lo, p);
        hi = vmax(hi, p);
    }
    size_t n = segs.count;
    const Vec3 size = hi - lo;
    if (!std::isfinite(sum) || segs.count <= 8 || size.x > kSmall || size.y > kSmall || size.z > kSmall) {
        for (size_t i = 0; i < segs.count; ++i) out[n++] = segs.ends[2 * i + 1];
        return n;
    }
    for (int corner = 0; corner < 8; ++corner)
        out[n++] = {(corner & 1) ? hi.x : lo.x, (corner & 2) ? hi.y : lo.y, (corner & 4) ? hi.z : lo.z};
    return n;
}

// Drops the segments that meet no cell of the solid shell (both ends inside its region, and apart):
// they enter no solid.
void dropSegmentsClearOfShell(ChunkSegments& segs, RTCScene shellScene, const Bounds& region, bool coherent) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
    std::array<RTCRay, 64> rays;
    std::array<uint8_t, 64> tested;
    size_t numTested = 0;
    for (size_t i = 0; i < segs.count; ++i) {
        const Vec3 from = segs.ends[2 * i], to = segs.ends[2 * i + 1];
        if (!region.contains(from) || !region.contains(to) || from == to) continue;
        tested[numTested] = uint8_t(i);
        setRay(rays[numTested++], from, to - from, 0.0f, 1.0f);
    }
    if (numTested == 0) return;
    rtcOccluded1M(shellScene, &context, rays.data(), unsigned(numTested), sizeof(RTCRay));
    std::array<uint8_t, 64> clear{};
    for (size_t j = 0; j < numTested; ++j)
        if (rays[j].tfar >= 0) clear[tested[j]] = 1;
    size_t kept = 0;
    for (size_t i = 0; i < segs.count; ++i) {
        if (clear[i]) continue;
        segs.slots[kept] = segs.slots[i];
        segs.ends[2 * kept] = segs.ends[2 * i];
        segs.ends[2 * kept + 1] = segs.ends[2 * i + 1];
        ++kept;
    }
    segs.count = kept;
}

using HullWalk = std::function<HullVerdict(std::span<const Vec3>)>;
using SegmentWalk = std::function<bool(const HullVerdict&, Vec3, Vec3)>;

// Sets crosses[slot] for every segment of `segs`. One walk of the hull of their ends may tell that
// none of them enters solid (asked only of a few segments or more: a hull walk costs about what a
// segment walk does); when it cannot, each segment is walked from where the hull's walk parted.
// (Halving a hull that is not clear seldom gives clear halves: a hull walk does not clip the hull
// where a segment walk splits its segment, so it meets solid beside the segments.) Before the
// walks, `dropClear` may drop the segments it shows to be clear (the solid shell).
void settleSegments(ChunkSegments& segs, const HullWalk& hullWalk, const SegmentWalk& walk, bool* crosses,
                    const std::function<void(ChunkSegments&)>& dropClear = {}) {
    constexpr size_t kMinHull = 4;
    HullVerdict verdict;
    if (hullWalk && segs.count >= kMinHull) {
        std::array<Vec3, 128> points;
        verdict = hullWalk(std::span<const Vec3>(points.data(), hullPoints(segs, points)));
        if (verdict.clear) return;
    }
    // Asking the shell costs about what a long walk does: not worth it for walks begun in a low
    // subtree (measured on oacmpdm1, oacmpdm3, oacmpdm5 and oacmpctf2).
    constexpr int32_t kShellMinHeight = 18;
    if (dropClear && (!verdict.start || verdict.height >= kShellMinHeight)) dropClear(segs);
    for (size_t i = 0; i < segs.count; ++i) crosses[segs.slots[i]] = walk(verdict, segs.ends[2 * i], segs.ends[2 * i + 1]);
}

}  // namespace

void TraceScene::traceBatch(std::span<const ShadowRay> rays, std::span<Vec3> out, bool coherent,
                            bool axialRaysAlone) const {
    const size_t n = std::min(rays.size(), out.size());
    if (n == 0) return;
    if (n == 1) {
        out[0] = traceOne(rays[0]);
        return;
    }
    countRays(n);
    // Chunks small enough for the ray arrays to stay in cache and on the stack.
    for (size_t first = 0; first < n; first += kBatchChunk) {
        const size_t count = std::min(kBatchChunk, n - first);
        traceChunk(rays.subspan(first, count), out.subspan(first, count), coherent, axialRaysAlone);
    }
}

namespace {

// A direction with a component too small to leave the axial plane through its origin within the
// world (sun vectors built from angles carry 1e-17 where they mean 0).
bool runsAlongAxialPlane(Vec3 d) {
    constexpr float kTiny = 1e-12f;
    return std::fabs(d.x) < kTiny || std::fabs(d.y) < kTiny || std::fabs(d.z) < kTiny;
}

}  // namespace

void TraceScene::traceChunk(std::span<const ShadowRay> rays, std::span<Vec3> out, bool coherent,
                            bool axialRaysAlone) const {
    const size_t n = rays.size();
    // Rays of one batch usually share a direction (one sun, many luxels) or an origin: Embree
    // groups them into packets when told they are coherent.
    RTCIntersectContext plain;
    rtcInitIntersectContext(&plain);
    plain.flags = coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
    for (size_t i = 0; i < n; ++i) out[i] = Vec3{};

    // 1. Sun rays: the nearest sky surface must belong to the sun's sky; it bounds the ray.
    //    Point-light rays: no sky surface may lie on the segment. Rays carry their batch index
    //    in `id`.
    RTCRayHit toSkyBuffer[kBatchChunk];
    RTCRay occlusionBuffer[kBatchChunk];
    RTCRay probe[kBatchChunk];
    size_t numToSky = 0, numOcclusion = 0;
    for (size_t i = 0; i < n; ++i) {
        const ShadowRay& r = rays[i];
        if (axialRaysAlone && runsAlongAxialPlane(r.direction)) {
            out[i] = traceSingle(r);
            continue;
        }
        if (!r.toSky) {
            setRay(occlusionBuffer[numOcclusion++], r.from, r.direction, r.tnear, r.tfar, static_cast<unsigned>(i),
                   casterMask(r.mask, false));
        } else if (!skyRecords_.empty()) {
            setRayHit(toSkyBuffer[numToSky++], r.from, r.direction, r.tnear, r.tfar, static_cast<unsigned>(i),
                      r.mask);
        }
    }
    const size_t numSegments = numOcclusion;  // point-light segments lead the buffer
    if (numToSky > 0) {
        rtcIntersect1M(embree_->skyScene, &plain, toSkyBuffer, static_cast<unsigned>(numToSky), sizeof(RTCRayHit));
        for (size_t k = 0; k < numToSky; ++k) {
            const RTCRayHit& rh = toSkyBuffer[k];
            const int wanted = rays[rh.ray.id].skyIndex;
            if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;  // escapes without meeting the sky
            if (wanted >= 0 && skyRecords_[rh.hit.geomID].skyIndex != wanted) continue;
            occlusionBuffer[numOcclusion] = rh.ray;  // tfar now ends at the sky surface
            occlusionBuffer[numOcclusion++].mask = casterMask(rh.ray.mask, true);
        }
    }

    // 2. Every surviving ray against the other casters; translucent crossings are collected.
    if (numOcclusion == 0) return;
    HitList hits;
    RayContext ctx;
    rtcInitIntersectContext(&ctx.base);
    ctx.base.flags = plain.flags;
    ctx.records = &records_;
    ctx.hits = &hits;
    rtcOccluded1M(embree_->scene, &ctx.base, occlusionBuffer, static_cast<unsigned>(numOcclusion), sizeof(RTCRay));
    // The rays of buffer slots [first, last) that the casters leave open, asked of another scene
    // (a blocked ray's translucent crossings no longer matter).
    auto probeOpen = [&](RTCScene scene, size_t first, size_t last) {
        uint8_t probed[kBatchChunk];
        size_t numProbes = 0;
        for (size_t k = first; k < last; ++k)
            if (occlusionBuffer[k].tfar >= 0) {
                probed[numProbes] = uint8_t(k);
                probe[numProbes++] = occlusionBuffer[k];
            }
        if (numProbes > 0) rtcOccluded1M(scene, &plain, probe, static_cast<unsigned>(numProbes), sizeof(RTCRay));
        for (size_t j = 0; j < numProbes; ++j)
            if (probe[j].tfar < 0) occlusionBuffer[probed[j]].tfar = probe[j].tfar;
    };
    // Sky surfaces block point-light segments like walls; the pieces that only sun rays meet.
    if (!skyRecords_.empty() && skySegmentBit_ == 0 && numSegments > 0) probeOpen(embree_->skyScene, 0, numSegments);
    if (embree_->sunOnlyScene && numOcclusion > numSegments)
        probeOpen(embree_->sunOnlyScene, numSegments, numOcclusion);
    // Segments that Embree leaves open still stop at structural solid (sun rays up to their sky,
    // whose distance their tfar now holds): the tree walk only for the rays that need it, and none
    // when the hull of their ends is clear (sun and point-light segments apart: one long sun prism
    // would spoil the point lights' hull). `crosses` starts false: clear hulls leave it so.
    static_assert(kBatchChunk <= 64, "ChunkSegments holds both ends of a chunk's rays");
    ChunkSegments toSky, toPoint;
    for (size_t k = 0; k < numOcclusion; ++k) {
        const ShadowRay& r = rays[occlusionBuffer[k].id];
        if (occlusionBuffer[k].tfar < 0 || r.clearOfSolid) continue;
        (r.toSky ? toSky : toPoint).add(k, r.from, r.from + r.direction * (r.toSky ? occlusionBuffer[k].tfar : r.tfar));
    }
    bool crosses[kBatchChunk] = {};
    if (toPoint.count > 0) {
        const SegmentWalk walk = [&](const HullVerdict& hull, Vec3 from, Vec3 to) {
            return hull.start && solidBetweenInHull_ ? solidBetweenInHull_(hull, from, to) : crossesSolid(from, to);
        };
        std::function<void(ChunkSegments&)> dropClear;
        if (embree_->shellScene)
            dropClear = [&](ChunkSegments& segs) {
                dropSegmentsClearOfShell(segs, embree_->shellScene, shell_.region, coherent);
            };
        settleSegments(toPoint, hullClearOfSolid_, walk, crosses, dropClear);
    }
    if (toSky.count > 0) {
        const SegmentWalk walk = [&](const HullVerdict& hull, Vec3 from, Vec3 to) {
            return hull.start && skySolidBetweenInHull_ ? skySolidBetweenInHull_(hull, from, to)
                                                       : skyRayCrossesSolid(from, to);
        };
        settleSegments(toSky, skyHullClear_, walk, crosses);
    }
    for (size_t k = 0; k < numOcclusion; ++k)
        if (occlusionBuffer[k].tfar >= 0 && !crosses[k]) out[occlusionBuffer[k].id] = Vec3{1, 1, 1};
    if (hits.empty()) return;
    const std::vector<TranslucentHit> sorted = sortedHits(hits);
    for (size_t a = 0; a < sorted.size();) {
        size_t b = a;
        while (b < sorted.size() && sorted[b].rayId == sorted[a].rayId) ++b;
        const unsigned i = sorted[a].rayId;
        if (i < n && out[i].x > 0) out[i] = translucentProduct(std::span<const TranslucentHit>(&sorted[a], b - a));
        a = b;
    }
}

}  // namespace q3::light
