// Deluxe maps: direction texels, tangent frames and interleaved pages (deluxe.h).
#include "deluxe.h"

#include <algorithm>
#include <cmath>

#include "light_context.h"
#include "lightmap_pack.h"
#include "surface_lighting.h"

namespace q3::light {

std::optional<DeluxeSettings> deluxeSettings(const LightContext& ctx) {
    if (!ctx.options.deluxe) return std::nullopt;
    return DeluxeSettings{ctx.options.deluxeMode == 1};
}

TangentFrame surfaceTangentFrame(const bsp::Bsp& bsp, int surfaceNum) {
    const bsp::Surface& s = bsp.surfaces.at(size_t(surfaceNum));
    Vec3 sDir, tDir;
    auto vert = [&](int i) -> const bsp::DrawVert& { return bsp.drawVerts.at(size_t(s.firstVert + i)); };
    auto addTriangle = [&](int a, int b, int c) {
        const Vec3 p0 = Vec3::fromArray(vert(a).xyz), p1 = Vec3::fromArray(vert(b).xyz), p2 = Vec3::fromArray(vert(c).xyz);
        const float s1 = vert(b).st[0] - vert(a).st[0], t1 = vert(b).st[1] - vert(a).st[1];
        const float s2 = vert(c).st[0] - vert(a).st[0], t2 = vert(c).st[1] - vert(a).st[1];
        const float det = s1 * t2 - s2 * t1;
        if (std::fabs(det) < 1e-12f) return;
        const Vec3 e1 = p1 - p0, e2 = p2 - p0;
        sDir += (e1 * t2 - e2 * t1) / det;
        tDir += (e2 * s1 - e1 * s2) / det;
    };
    if (s.surfaceType == bsp::MST_PATCH) {
        for (int y = 0; y + 1 < s.patchHeight; ++y)
            for (int x = 0; x + 1 < s.patchWidth; ++x) {
                const int i = y * s.patchWidth + x;
                addTriangle(i, i + 1, i + s.patchWidth);
            }
    } else {
        for (int i = 0; i + 2 < s.numIndexes; i += 3) {
            const int a = bsp.drawIndexes.at(size_t(s.firstIndex + i)), b = bsp.drawIndexes.at(size_t(s.firstIndex + i + 1)),
                      c = bsp.drawIndexes.at(size_t(s.firstIndex + i + 2));
            if (a < 0 || b < 0 || c < 0 || a >= s.numVerts || b >= s.numVerts || c >= s.numVerts) continue;
            addTriangle(a, b, c);
        }
    }
    auto unit = [](Vec3 v) { return length(v) > 0 ? normalize(v) : Vec3{}; };
    return {unit(sDir), unit(tDir)};
}

Vec3 toTangentSpace(Vec3 dir, Vec3 n, const TangentFrame& frame) {
    // Gram-Schmidt against the luxel normal, so that curved surfaces keep an orthonormal frame.
    Vec3 t = frame.tangent - n * dot(n, frame.tangent);
    if (length(t) < 1e-6f) t = std::fabs(n.x) < 0.9f ? cross(n, Vec3{1, 0, 0}) : cross(n, Vec3{0, 1, 0});
    t = normalize(t);
    Vec3 b = cross(n, t);
    if (dot(b, frame.bitangent) < 0) b = -b;  // keep the texture's handedness
    return {dot(dir, t), dot(dir, b), dot(dir, n)};
}

Rgb8 encodeDirection(Vec3 dir, Vec3 fallback) {
    const Vec3 d = length(dir) > 0 ? normalize(dir) : fallback;
    Rgb8 out;
    for (int c = 0; c < 3; ++c) out[size_t(c)] = uint8_t(std::clamp(d[c] * 127.5f + 127.5f, 0.0f, 255.0f));
    return out;
}

std::vector<Rgb8> encodeDeluxels(const bsp::Bsp& bsp, const SurfaceLight& lit, const DeluxeSettings& settings) {
    const size_t count = size_t(lit.width) * size_t(lit.height);
    std::vector<Rgb8> out(count);
    const TangentFrame frame = settings.tangentSpace ? surfaceTangentFrame(bsp, lit.surfaceNum) : TangentFrame{};
    for (size_t i = 0; i < count; ++i) {
        const Vec3 dir = i < lit.directions.size() ? lit.directions[i] : Vec3{};
        Vec3 n = i < lit.normals.size() ? lit.normals[i] : Vec3{};
        n = length(n) > 0 ? normalize(n) : Vec3{0, 0, 1};
        if (!settings.tangentSpace) {
            out[i] = encodeDirection(dir, n);
            continue;
        }
        const Vec3 local = length(dir) > 0 ? toTangentSpace(normalize(dir), n, frame) : Vec3{};
        out[i] = encodeDirection(local, Vec3{0, 0, 1});
    }
    return out;
}

void interleaveDirectionPages(PackedLightmaps& packed, std::span<const LightmapBlock> blocks) {
    const int n = packed.pageSize;
    std::vector<std::vector<uint8_t>> directions(packed.pages.size(), std::vector<uint8_t>(size_t(n) * n * 3, 127));
    for (size_t b = 0; b < blocks.size() && b < packed.placements.size(); ++b) {
        const BlockPlacement& p = packed.placements[b];
        const LightmapBlock& block = blocks[b];
        if (p.page < 0 || block.directionTexels.size() != size_t(block.width) * block.height) continue;
        for (int y = 0; y < p.height; ++y)
            for (int x = 0; x < p.width; ++x) {
                const Rgb8& d = block.directionTexels[size_t(y) * size_t(block.width) + size_t(x)];
                const size_t o = (size_t(p.y + y) * size_t(n) + size_t(p.x + x)) * 3;
                std::copy(d.begin(), d.end(), directions[size_t(p.page)].begin() + long(o));
            }
    }
    std::vector<std::vector<uint8_t>> pages, used;
    for (size_t p = 0; p < packed.pages.size(); ++p) {
        pages.push_back(std::move(packed.pages[p]));
        pages.push_back(std::move(directions[p]));
        used.push_back(packed.pageUsed[p]);
        used.push_back(std::move(packed.pageUsed[p]));
    }
    packed.pages = std::move(pages);
    packed.pageUsed = std::move(used);
    for (BlockPlacement& p : packed.placements)
        if (p.page >= 0) p.page *= 2;
}

void markDeluxeWorldspawn(bsp::Entity& worldspawn, const DeluxeSettings& settings) {
    worldspawn.set("deluxeMaps", settings.tangentSpace ? "2" : "1");
}

}  // namespace q3::light
