// Radiosity emitters of one bounce pass (q3map2 light_bounce.cpp: RadLight, RadLightForTriangles,
// RadSubdivideDiffuseLight, RadSample). Each triangle of a lit surface is chopped axially until
// it fits `subdivide`, then its colour is sampled from the surface's lightmap and texture; a piece
// whose colour varies too much is chopped again at half the size, down to 64 units.
#include "bounce_lights.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <string>

#include "log.h"
#include "winding_ops.h"

namespace q3::light {
namespace {

using Piece = std::vector<BouncePieceVertex>;

// Chopping below this size could never terminate with the 0.125 clip epsilon, and such pieces
// fall under the minimum emitter area anyway.
constexpr float kSmallestSubdivide = 1;
// Triangles wider than this lie far outside any Quake 3 world (q3map2: +-65536); chopping one
// would make billions of pieces.
constexpr float kLargestTriangleExtent = 4 * 65536;
constexpr float kMinPieceArea = 1;
constexpr float kMaxPieceArea = 20000000;
constexpr float kFormFactorValueScale = 3;
// q3map2 scales the radiosity value by 0.375 before the form factor (RadSubdivideDiffuseLight).
constexpr float kBounceValueFactor = 0.375f;
// RadSample's barycentric grid: weights 1..kGranularity-1 on each corner of a fan triangle.
constexpr int kGranularity = 6;
constexpr int kNoStyle = 255;  // LS_NONE

struct VertexPosition {
    Vec3& operator()(BouncePieceVertex& v) const { return v.vertex.xyz; }
    const Vec3& operator()(const BouncePieceVertex& v) const { return v.vertex.xyz; }
};

std::array<float, 2> lerp2(const std::array<float, 2>& a, const std::array<float, 2>& b, float t) {
    return {a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t};
}

// The vertex where an edge a->b is cut, every attribute interpolated (RadClipWindingEpsilon).
BouncePieceVertex splitVertex(const BouncePieceVertex& a, const BouncePieceVertex& b, float t) {
    BouncePieceVertex mid;
    mid.vertex.xyz = lerp(a.vertex.xyz, b.vertex.xyz, t);
    mid.vertex.normal = normalize(lerp(a.vertex.normal, b.vertex.normal, t));
    mid.vertex.st = lerp2(a.vertex.st, b.vertex.st, t);
    mid.vertex.lm = lerp2(a.vertex.lm, b.vertex.lm, t);
    mid.light = lerp(a.light, b.light, t);
    return mid;
}

// Texture colour in 0..255 at st, tinted towards its grey by `colorRatio` (NetRadiant-custom
// -bouncecolorratio). Without a usable image the surface's average colour stands in.
Vec3 textureColorAt(const BounceSurface& surface, const std::array<float, 2>& st, float colorRatio) {
    Vec3 tex = surface.averageColor * 255.0f;
    if (surface.image) {
        if (const uint8_t* texel = surface.image->texel(st[0], st[1]))
            tex = {static_cast<float>(texel[0]), static_cast<float>(texel[1]), static_cast<float>(texel[2])};
    }
    const float grey = (tex.x + tex.y + tex.z) / 3.0f;
    return tex * colorRatio + Vec3::splat(grey * (1.0f - colorRatio));
}

// The luxel under lightmap coordinate `lm` (truncated and clamped to the lightmap), or false when
// it is unlit: marked 0 in `lit`, or negative (q3map2's mark for unused radiosity luxels).
bool luxelAt(const BounceSurface& surface, const std::array<float, 2>& lm, Vec3& out) {
    if (!std::isfinite(lm[0]) || !std::isfinite(lm[1])) return false;
    const int x = static_cast<int>(std::clamp(lm[0], 0.0f, static_cast<float>(surface.width - 1)));
    const int y = static_cast<int>(std::clamp(lm[1], 0.0f, static_cast<float>(surface.height - 1)));
    const size_t index = static_cast<size_t>(y) * static_cast<size_t>(surface.width) + static_cast<size_t>(x);
    if (!surface.lit.empty() && surface.lit[index] == 0) return false;
    const Vec3& luxel = surface.luxels[index];
    if (luxel.x < 0) return false;
    out = luxel;
    return true;
}

// Running average and per-channel range of the sampled colours.
struct ColorStats {
    Vec3 sum;
    Bounds range;
    int count = 0;

    void add(Vec3 color) {
        sum += color;
        range.add(color);
        ++count;
    }
    BounceSample result() const {
        if (count == 0) return {};
        BounceSample s;
        s.samples = count;
        s.color = sum / static_cast<float>(count);
        s.gradient = (range.maxs - range.mins) * range.maxs;
        return s;
    }
};

bool hasLightmap(const BounceSurface& surface) {
    return surface.width > 0 && surface.height > 0 && !surface.luxels.empty();
}

struct PieceContext {
    const BounceSurface& surface;
    const BounceSettings& settings;
    bool twoSided;
    std::vector<Light>& out;
};

void emitPiece(const PieceContext& ctx, const Piece& w, float subdivide) {
    if (w.size() < 3) return;
    const Bounds bounds = windingBounds(w, VertexPosition{});
    for (int axis = 0; axis < 3; ++axis) {
        if (bounds.maxs[axis] - bounds.mins[axis] > subdivide) {
            const float dist = (bounds.maxs[axis] + bounds.mins[axis]) * 0.5f;
            Piece front, back;
            clipWindingAxial(w, axis, dist, kBounceClipEpsilon, front, back, splitVertex, VertexPosition{});
            emitPiece(ctx, front, subdivide);
            emitPiece(ctx, back, subdivide);
            return;
        }
    }
    const float area = windingArea(w, VertexPosition{});
    if (!(area >= kMinPieceArea && area <= kMaxPieceArea)) return;  // also drops NaN geometry

    const BounceSample sample = sampleBouncePiece(ctx.surface, w, ctx.settings.colorRatio);
    // A piece whose light varies strongly is split finer so the emitters follow the light.
    if (subdivide > kBounceMinSubdivide && maxComponent(sample.gradient) > kBounceMaxGradient) {
        emitPiece(ctx, w, subdivide * 0.5f);
        return;
    }

    Vec3 normal;
    for (const BouncePieceVertex& v : w) normal += v.vertex.normal;
    normal = normalize(normal / static_cast<float>(w.size()));
    if (!(length(normal) > 0)) return;
    if (length(sample.color) < kBounceMinColor) return;

    const float value = kBounceValue * ctx.surface.shaderBounceScale * kBounceValueFactor;
    Light light;
    light.type = LightType::Area;
    light.winding.reserve(w.size());
    for (const BouncePieceVertex& v : w) light.winding.push_back(v.vertex.xyz);
    light.emitter = emitterBounds(light.winding);
    light.normal = normal;
    light.origin = windingCentroid(w, VertexPosition{}) + normal;  // nudged off the plane
    light.planeDist = dot(light.origin, normal);
    light.photons = value * area * ctx.settings.bounceScale;
    light.add = value * kFormFactorValueScale * ctx.settings.bounceScale;
    light.color = sample.color;
    // q3map2 turns an invalid style (outside 0..254, 255 being "no style") into style 0.
    const int style = ctx.surface.style;
    light.style = ctx.settings.noStyles || style < 0 || style >= kNoStyle ? 0 : style;
    light.twoSided = ctx.twoSided;
    light.falloffTolerance = ctx.settings.falloffTolerance;
    light.fast = ctx.settings.fast;
    ctx.out.push_back(std::move(light));
}

void checkSurface(const BounceSurface& s) {
    const std::string where = "bounce surface " + std::to_string(s.surfaceNum) + ": ";
    if (s.triangles.size() % 3 != 0)
        throw CompileError(where + std::to_string(s.triangles.size()) + " triangle indexes (not a multiple of 3)");
    for (uint32_t index : s.triangles)
        if (index >= s.verts.size())
            throw CompileError(where + "triangle index " + std::to_string(index) + " out of range (" +
                               std::to_string(s.verts.size()) + " vertices)");
    if (s.width < 0 || s.height < 0) throw CompileError(where + "negative lightmap size");
    const size_t luxelCount = static_cast<size_t>(s.width) * static_cast<size_t>(s.height);
    if (!s.luxels.empty() && s.luxels.size() != luxelCount)
        throw CompileError(where + std::to_string(s.luxels.size()) + " luxels for a " + std::to_string(s.width) +
                           "x" + std::to_string(s.height) + " lightmap");
    if (!s.vertexLight.empty() && s.vertexLight.size() != s.verts.size())
        throw CompileError(where + std::to_string(s.vertexLight.size()) + " vertex lights for " +
                           std::to_string(s.verts.size()) + " vertices");
    if (!s.lit.empty() && s.lit.size() != s.luxels.size())
        throw CompileError(where + std::to_string(s.lit.size()) + " lit flags for " +
                           std::to_string(s.luxels.size()) + " luxels");
}

void emitSurface(const BounceSurface& surface, const BounceSettings& settings, std::vector<Light>& out) {
    if (!surfaceBounces(surface.shader, surface.shaderBounceScale)) return;
    const LightingShader* si = surface.shader;
    const float subdivide = std::max(
        si && si->lightSubdivide > 0 ? si->lightSubdivide : kBounceDefaultSubdivide, kSmallestSubdivide);
    const PieceContext ctx{surface, settings, si && (si->fog || si->twoSided), out};
    for (size_t i = 0; i < surface.triangles.size(); i += 3) {
        Piece triangle(3);
        for (size_t c = 0; c < 3; ++c) {
            const uint32_t index = surface.triangles[i + c];
            triangle[c].vertex = surface.verts[index];
            if (!surface.vertexLight.empty()) triangle[c].light = surface.vertexLight[index];
        }
        if (!(maxComponent(windingBounds(triangle, VertexPosition{}).size()) <= kLargestTriangleExtent)) continue;
        emitPiece(ctx, triangle, subdivide);
    }
}

}  // namespace

bool surfaceBounces(const LightingShader* shader, float shaderBounceScale) {
    if (!(shaderBounceScale > 0)) return false;
    if (!shader) return true;
    return !shader->sky && !shader->autosprite && !shader->nodraw && !shader->translucent;
}

BounceSample sampleBouncePiece(const BounceSurface& surface, std::span<const BouncePieceVertex> w,
                               float colorRatio) {
    ColorStats stats;
    if (w.size() < 3) return {};

    if (!hasLightmap(surface)) {
        // Vertex-lit surface: one sample per winding point, its own vertex light.
        for (const BouncePieceVertex& v : w)
            stats.add(textureColorAt(surface, v.vertex.st, colorRatio) / 255.0f * (v.light / 255.0f));
        return stats.result();
    }

    // Barycentric points of the fan triangles, as many as kBounceMaxSamples lit ones.
    for (size_t v = 1; v + 1 < w.size() && stats.count < kBounceMaxSamples; ++v) {
        const BounceVertex* corner[3] = {&w[0].vertex, &w[v].vertex, &w[v + 1].vertex};
        for (int i = 1; i < kGranularity && stats.count < kBounceMaxSamples; ++i) {
            for (int j = 1; j < kGranularity && stats.count < kBounceMaxSamples; ++j) {
                for (int k = 1; k < kGranularity && stats.count < kBounceMaxSamples; ++k) {
                    const float inv = 1.0f / static_cast<float>(i + j + k);
                    const float blend[3] = {static_cast<float>(i) * inv, static_cast<float>(j) * inv,
                                            static_cast<float>(k) * inv};
                    std::array<float, 2> st{}, lm{};
                    for (int c = 0; c < 3; ++c) {
                        for (int a = 0; a < 2; ++a) {
                            st[a] += corner[c]->st[a] * blend[c];
                            lm[a] += corner[c]->lm[a] * blend[c];
                        }
                    }
                    Vec3 luxel;
                    if (!luxelAt(surface, lm, luxel)) continue;
                    stats.add(textureColorAt(surface, st, colorRatio) / 255.0f * (luxel / 255.0f));
                }
            }
        }
    }
    return stats.result();
}

std::vector<Light> createBounceLights(std::span<const BounceSurface> surfaces, const BounceSettings& settings) {
    for (const BounceSurface& s : surfaces) checkSurface(s);

    // Each surface fills its own slot; the slots are joined in surface order.
    std::vector<std::vector<Light>> perSurface(surfaces.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, surfaces.size()), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i != r.end(); ++i) emitSurface(surfaces[i], settings, perSurface[i]);
    });

    size_t total = 0;
    for (const auto& lights : perSurface) total += lights.size();
    std::vector<Light> out;
    out.reserve(total);
    for (auto& lights : perSurface) std::move(lights.begin(), lights.end(), std::back_inserter(out));
    return out;
}

namespace {
// q3map2 writes int(add); a value outside int (or not a number) is clamped rather than undefined.
int dumpedIntensity(float add) {
    if (!std::isfinite(add)) return 0;
    return static_cast<int>(std::clamp(static_cast<double>(add), -2147483647.0, 2147483647.0));
}
}  // namespace

std::string bounceLightsAsMap(std::span<const Light> lights) {
    std::string text;
    char buffer[1024];
    for (const Light& light : lights) {
        const int written = std::snprintf(
            buffer, sizeof(buffer),
            "{\n\"classname\" \"light\"\n\"light\" \"%d\"\n\"origin\" \"%.0f %.0f %.0f\"\n\"_color\" \"%.3f %.3f %.3f\"\n}\n",
            dumpedIntensity(light.add), static_cast<double>(light.origin.x), static_cast<double>(light.origin.y),
            static_cast<double>(light.origin.z), static_cast<double>(light.color.x),
            static_cast<double>(light.color.y), static_cast<double>(light.color.z));
        if (written > 0) text.append(buffer, std::min(static_cast<size_t>(written), sizeof(buffer) - 1));
    }
    return text;
}

}  // namespace q3::light
