// -shgather (see grid_sh_gather.h): a closest-hit Embree scene of the drawn surfaces, and per probe
// a fixed set of rays whose reflected radiance is projected onto L2 SH. The shadow scene of
// trace_scene.h answers occlusion only; the gather needs the hit surface, triangle and barycentrics,
// so it keeps a scene of its own, built from the same SceneSurface list.
#include "grid_sh_gather.h"

#include <embree3/rtcore.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <string>

#include "grid_sh.h"
#include "light_context.h"
#include "light_text.h"
#include "patch.h"
#include "shader_info.h"
#include "light_shaders.h"

namespace q3::light {
namespace {

constexpr float kRayStart = 0.25f;          // skip the probe's own position
constexpr double kGoldenAngle = 2.39996322972865332;  // pi * (3 - sqrt(5))

// A surface that hits can land on.
struct HitRecord {
    int surfaceNum = -1;
    bool sky = false;
    const SceneSurface* geometry = nullptr;
    const ShaderAlbedo* albedo = nullptr;
    const BakedSurfaceLight* baked = nullptr;  // lightmapped surfaces
    std::vector<std::array<float, 2>> luxelCoords;  // lightmapped: luxel coordinate per scene vertex
    std::vector<Vec3> vertexLight;             // vertex-lit surfaces: stored colours, per scene vertex
    Vec3 meanLight;                            // where no per-point value exists
};

bool gathersFrom(const SceneSurface& s) {
    if (s.triangles.empty() || s.xyz.empty()) return false;
    if (!s.shader) return true;
    if (s.shader->sky) return true;
    return !s.shader->nodraw && !s.shader->fog && !s.shader->translucent;
}

// Luxel coordinates of the vertices of a patch's lighting tessellation (the mesh of SceneSurface).
// The lightmap of a curved patch is linear in control-point index space (lightmap_layout.cpp):
// luxel = (width - 1) / (patchWidth - 1) * controlIndex + 0.5 per axis. The control index of each
// tessellated vertex comes from tessellating the control grid with st = its (column, row).
std::vector<std::array<float, 2>> patchLuxelCoords(const bsp::Bsp& bsp, const bsp::Surface& s, Vec3 offset,
                                                   const BakedSurfaceLight& baked, size_t sceneVertices) {
    if (s.patchWidth < 2 || s.patchHeight < 2) return {};
    patch::ControlGrid grid;
    grid.width = s.patchWidth;
    grid.height = s.patchHeight;
    for (int v = 0; v < s.numVerts; ++v) {
        const size_t vi = size_t(s.firstVert + v);
        if (vi >= bsp.drawVerts.size()) return {};
        patch::PatchVertex pv;
        pv.xyz = Vec3::fromArray(bsp.drawVerts[vi].xyz) + offset;  // as the scene built it
        pv.normal = Vec3::fromArray(bsp.drawVerts[vi].normal);
        pv.st[0] = float(v % s.patchWidth);
        pv.st[1] = float(v / s.patchWidth);
        grid.points.push_back(pv);
    }
    if (!patch::isValidGrid(grid)) return {};
    const patch::PatchMesh mesh = patch::tessellateForLighting(grid);
    if (mesh.verts.size() != sceneVertices) return {};
    const float sBasis = float(baked.width - 1) / float(s.patchWidth - 1);
    const float tBasis = float(baked.height - 1) / float(s.patchHeight - 1);
    std::vector<std::array<float, 2>> out;
    out.reserve(mesh.verts.size());
    for (const patch::PatchVertex& v : mesh.verts) out.push_back({sBasis * v.st[0] + 0.5f, tBasis * v.st[1] + 0.5f});
    return out;
}

Vec3 meanOf(std::span<const Vec3> values) {
    Vec3 sum;
    for (const Vec3& v : values) sum += v;
    return values.empty() ? Vec3{} : sum / float(values.size());
}

}  // namespace

const std::vector<ShaderAlbedo>& shaderAlbedo(LightContext& ctx, Log& log) {
    if (!ctx.albedo) {
        ctx.albedo = std::make_unique<ShaderAlbedoSet>();
        ctx.albedo->shaders = loadShaderAlbedo(ctx, ctx.albedo->images, log);
    }
    return ctx.albedo->shaders;
}

std::vector<Vec3> gatherDirections(int count) {
    std::vector<Vec3> out;
    out.reserve(size_t(std::max(0, count)));
    for (int i = 0; i < count; ++i) {
        // z at the centre of the i-th of `count` equal-area bands, azimuth advanced by the golden angle.
        const double z = 1.0 - (2.0 * i + 1.0) / double(count);
        const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
        const double phi = kGoldenAngle * i;
        out.push_back({float(r * std::cos(phi)), float(r * std::sin(phi)), float(z)});
    }
    return out;
}

std::vector<ShaderAlbedo> loadShaderAlbedo(const LightContext& ctx, std::vector<LightImage>& images, Log& log) {
    const size_t count = ctx.bsp.shaders.size();
    std::vector<ShaderAlbedo> out(count);
    if (!ctx.vfs || !ctx.shaderTable) return out;
    // Each shader's image is found and decoded on its own (in parallel: a map names dozens of
    // textures); the warnings are logged afterwards in shader order, as one shader after another
    // would log them. Images the lighting shaders decoded already are taken from their cache (a
    // read that succeeds logs nothing, so the messages stay the same).
    struct Found {
        const LightImage* cached = nullptr;
        std::unique_ptr<LightImage> image;
        Vec3 average;
        std::vector<std::string> warnings;
    };
    std::vector<Found> found(count);
    auto find = [&](size_t i) {
        const std::string name(ctx.bsp.shaders[i].name, strnlen(ctx.bsp.shaders[i].name, sizeof(ctx.bsp.shaders[i].name)));
        for (const std::string& candidate : ctx.shaderTable->find(name).lightImageCandidates()) {
            const auto cached = ctx.shaders.images.find(candidate);
            if (cached != ctx.shaders.images.end() && cached->second && cached->second->width > 0) {
                found[i].cached = cached->second.get();
                found[i].average = found[i].cached->averageColor();
                return;
            }
            LightImageRead read = readLightImage(*ctx.vfs, candidate);
            if (!read.warning.empty()) found[i].warnings.push_back(std::move(read.warning));
            if (!read.image || read.image->width <= 0) continue;
            found[i].average = read.image->averageColor();
            found[i].image = std::move(read.image);
            return;
        }
    };
    tbb::task_arena(ctx.threads > 0 ? ctx.threads : tbb::task_arena::automatic).execute([&] {
        tbb::parallel_for(size_t(0), count, find);
    });
    images.clear();
    images.reserve(count);  // pointers into it stay valid
    int missing = 0;
    for (size_t i = 0; i < count; ++i) {
        for (const std::string& warning : found[i].warnings) log.warning(warning);
        if (found[i].image) {
            images.push_back(std::move(*found[i].image));
            out[i].image = &images.back();
        } else if (found[i].cached) {
            out[i].image = found[i].cached;
        } else {
            ++missing;
            continue;
        }
        out[i].average = found[i].average;
    }
    if (missing > 0) log.info(strCat(missing, " shaders without an image reflect 0.5 grey"));
    return out;
}

struct GatherScene::Impl {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    std::vector<HitRecord> records;  // by Embree geometry id
    ~Impl() {
        if (scene) rtcReleaseScene(scene);
        if (device) rtcReleaseDevice(device);
    }
};

GatherScene::GatherScene(const LightContext& ctx, std::span<const ShaderAlbedo> albedo) : impl_(std::make_unique<Impl>()) {
    impl_->device = rtcNewDevice(nullptr);
    if (!impl_->device) throw CompileError("SH gather: Embree device could not be created");
    impl_->scene = rtcNewScene(impl_->device);
    rtcSetSceneBuildQuality(impl_->scene, RTC_BUILD_QUALITY_HIGH);
    static const ShaderAlbedo kDefaultAlbedo;
    for (const SceneSurface& s : ctx.surfaces) {
        if (!gathersFrom(s)) continue;
        HitRecord rec;
        rec.surfaceNum = s.surfaceNum;
        rec.sky = s.shader && s.shader->sky;
        rec.geometry = &s;
        const bsp::Surface* bs = s.surfaceNum >= 0 && size_t(s.surfaceNum) < ctx.bsp.surfaces.size()
                                     ? &ctx.bsp.surfaces[size_t(s.surfaceNum)]
                                     : nullptr;
        rec.albedo = bs && bs->shaderNum >= 0 && size_t(bs->shaderNum) < albedo.size() ? &albedo[size_t(bs->shaderNum)]
                                                                                      : &kDefaultAlbedo;
        if (s.surfaceNum >= 0 && size_t(s.surfaceNum) < ctx.bakedLight.size() &&
            ctx.bakedLight[size_t(s.surfaceNum)].width > 0) {
            rec.baked = &ctx.bakedLight[size_t(s.surfaceNum)];
            rec.meanLight = meanOf(rec.baked->color);
            if (!s.isPatch && rec.baked->vertexCoords.size() == s.xyz.size()) {
                rec.luxelCoords = rec.baked->vertexCoords;
            } else if (s.isPatch && bs) {
                const Vec3 offset =
                    size_t(s.surfaceNum) < ctx.surfaceOffsets.size() ? ctx.surfaceOffsets[size_t(s.surfaceNum)] : Vec3{};
                rec.luxelCoords = patchLuxelCoords(ctx.bsp, *bs, offset, *rec.baked, s.xyz.size());
            }
        } else if (bs) {
            // Vertex-lit: the colours lightVertexes stored (bytes, the same scale as legacy light).
            std::vector<Vec3> colors;
            for (int v = 0; v < bs->numVerts; ++v) {
                const size_t vi = size_t(bs->firstVert + v);
                if (vi >= ctx.bsp.drawVerts.size()) break;
                const uint8_t* c = ctx.bsp.drawVerts[vi].color;
                colors.push_back({float(c[0]), float(c[1]), float(c[2])});
            }
            rec.meanLight = meanOf(colors);
            if (!s.isPatch && colors.size() == s.xyz.size()) rec.vertexLight = std::move(colors);
        }
        RTCGeometry geom = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* vb = static_cast<float*>(
            rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), s.xyz.size()));
        for (size_t v = 0; v < s.xyz.size(); ++v) {
            vb[3 * v] = s.xyz[v].x;
            vb[3 * v + 1] = s.xyz[v].y;
            vb[3 * v + 2] = s.xyz[v].z;
        }
        const size_t triangles = s.triangles.size() / 3;
        auto* ib = static_cast<unsigned*>(
            rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), triangles));
        std::copy(s.triangles.begin(), s.triangles.begin() + long(triangles * 3), ib);
        rtcCommitGeometry(geom);
        const unsigned id = rtcAttachGeometry(impl_->scene, geom);
        rtcReleaseGeometry(geom);
        if (id >= impl_->records.size()) impl_->records.resize(id + 1);
        impl_->records[id] = std::move(rec);
    }
    rtcCommitScene(impl_->scene);
}

GatherScene::~GatherScene() = default;

namespace {

// Reflected radiance of the surface hit at (primID, u, v) of record `rec`.
sh::Rgb reflectedAt(const HitRecord& rec, unsigned prim, float u, float v) {
    if (rec.sky) return {};  // sky and suns are direct light, already in TraceGridSH
    const SceneSurface& s = *rec.geometry;
    const uint32_t i0 = s.triangles[3 * size_t(prim)], i1 = s.triangles[3 * size_t(prim) + 1],
                   i2 = s.triangles[3 * size_t(prim) + 2];
    const float w1 = u, w2 = v, w0 = 1.0f - w1 - w2;

    Vec3 albedo = rec.albedo->average;
    if (rec.albedo->image && s.st.size() >= 2 * s.xyz.size()) {
        const float ts = w0 * s.st[2 * i0] + w1 * s.st[2 * i1] + w2 * s.st[2 * i2];
        const float tt = w0 * s.st[2 * i0 + 1] + w1 * s.st[2 * i1 + 1] + w2 * s.st[2 * i2 + 1];
        const uint8_t* t = rec.albedo->image->texel(ts, tt);
        albedo = Vec3{float(t[0]), float(t[1]), float(t[2])} / 255.0f;
    }

    Vec3 light = rec.meanLight;
    if (rec.baked && !rec.luxelCoords.empty()) {
        const BakedSurfaceLight& b = *rec.baked;
        const auto& c = rec.luxelCoords;
        const float x = w0 * c[i0][0] + w1 * c[i1][0] + w2 * c[i2][0];
        const float y = w0 * c[i0][1] + w1 * c[i1][1] + w2 * c[i2][1];
        const int lx = std::clamp(int(std::floor(x)), 0, b.width - 1);
        const int ly = std::clamp(int(std::floor(y)), 0, b.height - 1);
        light = b.color[size_t(ly) * size_t(b.width) + size_t(lx)];
    } else if (!rec.vertexLight.empty()) {
        light = rec.vertexLight[i0] * w0 + rec.vertexLight[i1] * w1 + rec.vertexLight[i2] * w2;
    }
    // Lambertian reflection: radiance = albedo * irradiance / pi, irradiance in legacy units.
    const double k = 1.0 / (sh::kPi * 255.0);
    return {albedo.x * light.x * k, albedo.y * light.y * k, albedo.z * light.z * k};
}

}  // namespace

sh::Rgb GatherScene::radianceAlong(Vec3 origin, Vec3 direction) const {
    sh::Rgb out;
    radianceAlong(origin, {&direction, 1}, {&out, 1});
    return out;
}

void GatherScene::radianceAlong(Vec3 origin, std::span<const Vec3> directions, std::span<sh::Rgb> out) const {
    // Packets of 16 rays from one origin: they share their first traversal steps.
    constexpr size_t kPacket = 16;
    for (size_t first = 0; first < directions.size(); first += kPacket) {
        const size_t count = std::min(kPacket, directions.size() - first);
        alignas(64) int valid[kPacket];
        alignas(64) RTCRayHit16 rh;
        for (size_t k = 0; k < kPacket; ++k) {
            const bool used = k < count;
            const Vec3 d = used ? directions[first + k] : Vec3{0, 0, 1};
            valid[k] = used ? -1 : 0;
            rh.ray.org_x[k] = origin.x;
            rh.ray.org_y[k] = origin.y;
            rh.ray.org_z[k] = origin.z;
            rh.ray.dir_x[k] = d.x;
            rh.ray.dir_y[k] = d.y;
            rh.ray.dir_z[k] = d.z;
            rh.ray.tnear[k] = kRayStart;
            rh.ray.tfar[k] = std::numeric_limits<float>::infinity();
            rh.ray.mask[k] = 0xFFFFFFFFu;
            rh.ray.time[k] = 0;
            rh.ray.flags[k] = 0;
            rh.ray.id[k] = unsigned(k);
            rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
            rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
        }
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        rtcIntersect16(valid, impl_->scene, &context, &rh);
        for (size_t k = 0; k < count; ++k) {
            const unsigned geom = rh.hit.geomID[k];
            out[first + k] = geom == RTC_INVALID_GEOMETRY_ID || geom >= impl_->records.size()
                                 ? sh::Rgb{}
                                 : reflectedAt(impl_->records[geom], rh.hit.primID[k], rh.hit.u[k], rh.hit.v[k]);
        }
    }
}

void GatherScene::clearTo(Vec3 a, std::span<const Vec3> targets, std::span<uint8_t> clear) const {
    constexpr size_t kPacket = 8;
    alignas(32) int valid[kPacket];
    alignas(32) RTCRay8 ray;
    bool any = false;
    for (size_t k = 0; k < kPacket; ++k) {
        const Vec3 d = k < targets.size() ? targets[k] - a : Vec3{};
        const float length = q3::length(d);
        const bool used = length > 2 * kRayStart;
        any = any || used;
        valid[k] = used ? -1 : 0;
        const Vec3 dir = used ? d / length : Vec3{0, 0, 1};
        ray.org_x[k] = a.x;
        ray.org_y[k] = a.y;
        ray.org_z[k] = a.z;
        ray.dir_x[k] = dir.x;
        ray.dir_y[k] = dir.y;
        ray.dir_z[k] = dir.z;
        ray.tnear[k] = kRayStart;
        ray.tfar[k] = used ? length - kRayStart : 0;
        ray.mask[k] = 0xFFFFFFFFu;
        ray.time[k] = 0;
        ray.flags[k] = 0;
        ray.id[k] = unsigned(k);
    }
    if (any) {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        rtcOccluded8(valid, impl_->scene, &context, &ray);
    }
    for (size_t k = 0; k < targets.size() && k < kPacket; ++k)
        clear[k] = !(valid[k] && ray.tfar[k] < 0);  // Embree sets tfar to -inf on a hit
}

sh::SH9Color gatherProbe(const GatherScene& scene, Vec3 origin, std::span<const Vec3> directions) {
    sh::SH9Color radiance;
    if (directions.empty()) return radiance;
    const double weight = 4.0 * sh::kPi / double(directions.size());
    std::vector<sh::Rgb> seen(directions.size());
    scene.radianceAlong(origin, directions, seen);
    for (size_t k = 0; k < directions.size(); ++k) {
        const sh::Rgb& l = seen[k];
        if (l.r == 0 && l.g == 0 && l.b == 0) continue;
        const Vec3& d = directions[k];
        sh::addRadianceSample(radiance, {d.x, d.y, d.z}, l, weight);
    }
    return sh::convolveRadianceToIrradiance(radiance);
}

namespace {

// The probes of a lattice step: indices whose x, y and z are all multiples of `step`.
bool onCoarseLattice(size_t i, const int32_t bounds[3], int step) {
    const size_t bx = size_t(bounds[0]), by = size_t(bounds[1]);
    const size_t x = i % bx, y = (i / bx) % by, z = i / (bx * by);
    return x % size_t(step) == 0 && y % size_t(step) == 0 && z % size_t(step) == 0;
}

// Trilinear interpolation of the coarse probes around fine probe i, over the corners that were
// gathered (not in solid) and that it sees (light must not leak through walls and floors), their
// weights renormalised; false when no corner qualifies or the probe lies past the grid's last
// coarse plane.
bool interpolateCoarse(size_t i, const int32_t bounds[3], int step, const std::vector<sh::SH9Color>& indirect,
                       const std::vector<uint8_t>& have, const GatherScene& scene, std::span<const Vec3> origins,
                       sh::SH9Color& out) {
    const int b[3] = {bounds[0], bounds[1], bounds[2]};
    const int p[3] = {int(i % size_t(b[0])), int((i / size_t(b[0])) % size_t(b[1])), int(i / (size_t(b[0]) * size_t(b[1])))};
    int lo[3], hi[3];
    double t[3];
    for (int a = 0; a < 3; ++a) {
        lo[a] = p[a] / step * step;
        t[a] = double(p[a] - lo[a]) / step;
        hi[a] = t[a] > 0 ? lo[a] + step : lo[a];
        if (hi[a] >= b[a]) return false;
    }
    size_t corners[8];
    double weights[8];
    Vec3 targets[8];
    size_t n = 0;
    for (int corner = 0; corner < 8; ++corner) {
        double w = 1;
        int c[3];
        for (int a = 0; a < 3; ++a) {
            const bool upper = (corner >> a) & 1;
            w *= upper ? t[a] : 1 - t[a];
            c[a] = upper ? hi[a] : lo[a];
        }
        if (w == 0) continue;
        const size_t j = size_t(c[0]) + size_t(c[1]) * size_t(b[0]) + size_t(c[2]) * size_t(b[0]) * size_t(b[1]);
        if (!have[j]) continue;
        corners[n] = j;
        weights[n] = w;
        targets[n] = origins[j];
        ++n;
    }
    if (n == 0) return false;
    uint8_t clear[8];
    scene.clearTo(origins[i], {targets, n}, {clear, n});
    double total = 0;
    for (size_t k = 0; k < n; ++k) total += clear[k] ? weights[k] : 0;
    if (total <= 0) return false;
    out = sh::SH9Color{};
    for (size_t k = 0; k < n; ++k)
        if (clear[k]) out = sh::add(out, sh::scale(indirect[corners[k]], weights[k] / total));
    return true;
}

}  // namespace

ShGatherStats gatherIndirectSH(const LightContext& ctx, std::span<const ShaderAlbedo> albedo, sh::GridLumpImage& grid,
                               const ShTraceStats& traced, Log& log) {
    const auto start = std::chrono::steady_clock::now();
    const GatherScene scene(ctx, albedo);
    const std::vector<Vec3> directions = gatherDirections(ctx.options.shGatherSamples);
    const size_t numPoints = grid.numPoints();
    const std::array<int32_t, 3> bounds = grid.bounds();
    const double gridScale = ctx.options.gridScale;
    const int step = std::max(1, ctx.options.shGatherStep);
    // Indirect light varies slowly: probes of the coarse lattice (every `step`-th per axis) gather,
    // the others interpolate them, and gather themselves where a coarse corner is missing.
    std::vector<sh::SH9Color> indirect(numPoints);
    std::vector<uint8_t> have(numPoints, 0), gathered(numPoints, 0);
    auto free = [&](size_t i) { return i < traced.origins.size() && !(i < traced.solid.size() && traced.solid[i]); };
    auto gatherAt = [&](size_t i) {
        // Where TraceGridSH lit the probe (nudged out of solid).
        indirect[i] = gatherProbe(scene, traced.origins[i], directions);
        have[i] = gathered[i] = 1;
    };
    tbb::task_arena arena(ctx.threads > 0 ? ctx.threads : tbb::task_arena::automatic);
    auto parallel = [&](auto&& visit) {
        arena.execute([&] {
            tbb::parallel_for(tbb::blocked_range<size_t>(0, numPoints, 16), [&](const tbb::blocked_range<size_t>& r) {
                for (size_t i = r.begin(); i != r.end(); ++i)
                    if (free(i)) visit(i);
            });
        });
    };
    parallel([&](size_t i) {
        if (onCoarseLattice(i, bounds.data(), step)) gatherAt(i);
    });
    // Reads only what the first pass wrote, so the order of this pass does not matter.
    std::vector<uint8_t> fine(numPoints, 0);
    parallel([&](size_t i) {
        if (have[i]) return;
        sh::SH9Color value;
        if (interpolateCoarse(i, bounds.data(), step, indirect, have, scene, traced.origins, value)) {
            indirect[i] = value;
            fine[i] = 1;
        } else {
            indirect[i] = gatherProbe(scene, traced.origins[i], directions);
            gathered[i] = 1;
        }
    });
    for (size_t i = 0; i < numPoints; ++i) {
        if (!gathered[i] && !fine[i]) continue;
        const sh::SH9Color add = sh::scale(indirect[i], gridScale);
        sh::GridPointSH p = grid.point(i);
        for (int k = 0; k < sh::kCoeffCount; ++k)
            for (int ch = 0; ch < 3; ++ch) p.coeffs[k][ch] = float(double(p.coeffs[k][ch]) + add.c[k][ch]);
        grid.setPoint(i, p);
    }

    // Points in solid took their value from free neighbours before the gather: take it again.
    std::vector<uint8_t> unset(numPoints, 0);
    for (size_t i = 0; i < numPoints && i < traced.solid.size(); ++i) unset[i] = traced.solid[i];
    fillFromNeighbours(grid, unset);

    ShGatherStats stats;
    for (size_t i = 0; i < numPoints; ++i) {
        stats.probes += gathered[i];
        stats.interpolated += fine[i];
    }
    stats.rays = stats.probes * directions.size();
    stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    log.info(strCat("SH gather: ", stats.probes, " probes x ", directions.size(), " rays = ", stats.rays, " rays in ",
                    stats.seconds, " s (", stats.seconds > 0 ? uint64_t(double(stats.rays) / stats.seconds) : 0,
                    " rays/s), ", stats.interpolated, " probes interpolated (step ", step, ")"));
    return stats;
}

}  // namespace q3::light
