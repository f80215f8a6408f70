#include "hit_scene.h"

#include <embree3/rtcore.h>
#include <oneapi/tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "embree_ray.h"
#include "log.h"

namespace q3::light {

struct HitScene::EmbreeState {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    RTCScene skyScene = nullptr;  // the sky surfaces again, on their own
    RTCScene openScene = nullptr;  // the triangles not backed by structural solid (null: the whole scene)
};

namespace {
RTCScene newScene(RTCDevice device) {
    RTCScene scene = rtcNewScene(device);
    rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
    return scene;
}

// Attaches the triangles of `s` (or the `only` ones, 3 indices each) to `scene` as one geometry;
// returns its id.
unsigned attachSurface(RTCDevice device, RTCScene scene, const SceneSurface& s,
                       const std::vector<uint32_t>* only = nullptr) {
    const size_t numVerts = s.xyz.size();
    const std::vector<uint32_t>& triangles = only ? *only : s.triangles;
    const size_t numTris = triangles.size() / 3;
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vb = static_cast<float*>(
        rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), numVerts));
    for (size_t i = 0; i < numVerts; ++i) s.xyz[i].toArray(vb + i * 3);
    auto* ib = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), numTris));
    for (size_t i = 0; i < numTris * 3; ++i) ib[i] = triangles[i] < numVerts ? triangles[i] : 0u;
    rtcCommitGeometry(geom);
    const unsigned id = rtcAttachGeometry(scene, geom);
    rtcReleaseGeometry(geom);
    return id;
}

// Whether `s` stops nearest-hit rays: a shadow caster, but not a filter (alphashadow, lightfilter)
// unless it is sky.
bool stopsNearestRays(const SceneSurface& s, const TraceSceneOptions& options) {
    if (!TraceScene::castsShadow(s, options)) return false;
    const LightingShader* sh = s.shader;
    return !sh || sh->sky || !(sh->alphaShadow || sh->lightFilter);
}

// The triangles of `s` that `solidBacked` rejects (degenerate index triples are left to Embree,
// which never hits them).
std::vector<uint32_t> openTriangles(const SceneSurface& s,
                                    const SolidBackedTest& solidBacked) {
    std::vector<uint32_t> open;
    for (size_t t = 0; t + 2 < s.triangles.size(); t += 3) {
        const uint32_t a = s.triangles[t], b = s.triangles[t + 1], c = s.triangles[t + 2];
        const size_t n = s.xyz.size();
        if (a < n && b < n && c < n) {
            const std::array<Vec3, 3> corners{s.xyz[a], s.xyz[b], s.xyz[c]};
            if (solidBacked(std::span<const Vec3, 3>(corners))) continue;
        }
        open.insert(open.end(), {a, b, c});
    }
    return open;
}
}  // namespace

HitScene::HitScene(const std::vector<SceneSurface>& surfaces, const TraceSceneOptions& options,
                   const SolidBackedTest& solidBacked)
    : embree_(std::make_unique<EmbreeState>()) {
    embree_->device = rtcNewDevice(nullptr);
    if (!embree_->device) throw CompileError("embree: cannot create a ray-tracing device");
    embree_->scene = newScene(embree_->device);
    embree_->skyScene = newScene(embree_->device);
    // The open triangles of every surface, found in parallel (in the caller's task arena).
    std::vector<std::vector<uint32_t>> openOf;
    if (solidBacked) {
        embree_->openScene = newScene(embree_->device);
        openOf.resize(surfaces.size());
        tbb::parallel_for(tbb::blocked_range<size_t>(0, surfaces.size(), 16), [&](const tbb::blocked_range<size_t>& r) {
            for (size_t i = r.begin(); i != r.end(); ++i)
                if (stopsNearestRays(surfaces[i], options)) openOf[i] = openTriangles(surfaces[i], solidBacked);
        });
    }
    for (size_t i = 0; i < surfaces.size(); ++i) {
        const SceneSurface& s = surfaces[i];
        if (!stopsNearestRays(s, options)) continue;
        const bool sky = s.shader && s.shader->sky;
        const unsigned id = attachSurface(embree_->device, embree_->scene, s);
        if (skyGeometry_.size() <= id) skyGeometry_.resize(id + 1, 0);
        skyGeometry_[id] = sky ? 1 : 0;
        if (sky) {
            attachSurface(embree_->device, embree_->skyScene, s);
            // Every corner Embree may use, an index out of range reading vertex 0 as attachSurface has it.
            for (size_t t = 0; t + 2 < s.triangles.size(); t += 3) {
                Bounds box;
                for (size_t k = 0; k < 3; ++k)
                    if (!s.xyz.empty()) box.add(s.xyz[s.triangles[t + k] < s.xyz.size() ? s.triangles[t + k] : 0]);
                skyTriangleBoxes_.push_back(box);
            }
        }
        if (!embree_->openScene) continue;
        const std::vector<uint32_t>& open = openOf[i];
        if (open.empty()) continue;
        const unsigned openId = attachSurface(embree_->device, embree_->openScene, s, &open);
        if (openSkyGeometry_.size() <= openId) openSkyGeometry_.resize(openId + 1, 0);
        openSkyGeometry_[openId] = sky ? 1 : 0;
    }
    rtcCommitScene(embree_->scene);
    rtcCommitScene(embree_->skyScene);
    if (embree_->openScene) rtcCommitScene(embree_->openScene);
    if (rtcGetDeviceError(embree_->device) != RTC_ERROR_NONE)
        throw CompileError("embree: building the nearest-hit scene failed");
}

HitScene::~HitScene() {
    if (embree_->scene) rtcReleaseScene(embree_->scene);
    if (embree_->skyScene) rtcReleaseScene(embree_->skyScene);
    if (embree_->openScene) rtcReleaseScene(embree_->openScene);
    if (embree_->device) rtcReleaseDevice(embree_->device);
}

namespace {
RayHit toRayHit(const RTCRayHit& rh, const std::vector<uint8_t>& skyGeometry) {
    RayHit out;
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return out;
    out.hit = true;
    out.distance = rh.ray.tfar;
    out.sky = rh.hit.geomID < skyGeometry.size() && skyGeometry[rh.hit.geomID] != 0;
    return out;
}
}  // namespace

RayHit HitScene::nearest(Vec3 from, Vec3 direction, float tnear, float tfar) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh{};
    setRayHit(rh, from, direction, tnear, tfar);
    rtcIntersect1(embree_->scene, &context, &rh);
    return toRayHit(rh, skyGeometry_);
}

namespace {
// Nearest hits of a fan of rays from one point, as one coherent Embree stream per 64 rays.
void nearestInScene(RTCScene scene, const std::vector<uint8_t>& skyGeometry, Vec3 from,
                    std::span<const Vec3> directions, float tnear, float tfar, std::span<RayHit> out) {
    constexpr size_t kChunk = 64;
    RTCRayHit rays[kChunk];
    for (size_t start = 0; start < directions.size(); start += kChunk) {
        const size_t n = std::min(kChunk, directions.size() - start);
        for (size_t i = 0; i < n; ++i) setRayHit(rays[i], from, directions[start + i], tnear, tfar);
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
        rtcIntersect1M(scene, &context, rays, static_cast<unsigned>(n), sizeof(RTCRayHit));
        for (size_t i = 0; i < n && start + i < out.size(); ++i) out[start + i] = toRayHit(rays[i], skyGeometry);
    }
}
}  // namespace

void HitScene::nearestMany(Vec3 from, std::span<const Vec3> directions, float tnear, float tfar,
                           std::span<RayHit> out) const {
    nearestInScene(embree_->scene, skyGeometry_, from, directions, tnear, tfar, out);
}

void HitScene::nearestOpenMany(Vec3 from, std::span<const Vec3> directions, float tnear, float tfar,
                               std::span<RayHit> out) const {
    if (!embree_->openScene) return nearestMany(from, directions, tnear, tfar, out);
    nearestInScene(embree_->openScene, openSkyGeometry_, from, directions, tnear, tfar, out);
}

void HitScene::skyAlongMany(Vec3 from, std::span<const Vec3> directions, float tnear, std::span<const float> tfars,
                            std::span<uint8_t> out) const {
    constexpr size_t kChunk = 64;
    RTCRay rays[kChunk];
    for (size_t start = 0; start < directions.size(); start += kChunk) {
        const size_t n = std::min(kChunk, directions.size() - start);
        for (size_t i = 0; i < n; ++i) setRay(rays[i], from, directions[start + i], tnear, tfars[start + i]);
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
        rtcOccluded1M(embree_->skyScene, &context, rays, static_cast<unsigned>(n), sizeof(RTCRay));
        // An occluded ray comes back with tfar = -inf.
        for (size_t i = 0; i < n && start + i < out.size(); ++i) out[start + i] = rays[i].tfar < 0 ? 1 : 0;
    }
}

void tangentFrame(Vec3 normal, Vec3& right, Vec3& up) {
    if (normal.x == 0 && normal.y == 0 && (normal.z == 1 || normal.z == -1)) {
        right = normal.z == 1 ? Vec3{1, 0, 0} : Vec3{-1, 0, 0};
        up = Vec3{0, 1, 0};
        return;
    }
    right = normalize(cross(normal, Vec3{0, 0, 1}));
    up = normalize(cross(right, normal));
}

std::vector<Vec3> coneDirections(int azimuthSteps, int elevationSteps, float coneDegrees) {
    std::vector<Vec3> out;
    const float azimuthStep = degToRad(360.0f / static_cast<float>(azimuthSteps));
    const float elevationStep = degToRad(coneDegrees / static_cast<float>(elevationSteps));
    for (int i = 0; i < azimuthSteps; ++i) {
        const float azimuth = azimuthStep * static_cast<float>(i);
        for (int j = 0; j < elevationSteps; ++j) {
            const float elevation = elevationStep * (0.5f + static_cast<float>(j));
            out.push_back({std::sin(elevation) * std::cos(azimuth), std::sin(elevation) * std::sin(azimuth),
                           std::cos(elevation)});
        }
    }
    return out;
}

}  // namespace q3::light
