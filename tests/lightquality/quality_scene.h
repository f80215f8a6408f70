// Small BSP scenes for the light quality tests: quads with chosen shaders, written under a game
// folder (<tmp>/game/maps/NAME.bsp, shader scripts in <tmp>/game/scripts) and lit by the stage.
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "bspfile.h"
#include "common_options.h"
#include "file_io.h"
#include "light_options.h"
#include "light_stage.h"
#include "lightmap_layout.h"
#include "log.h"
#include "option_parser.h"
#include "bsp_scene.h"
#include "test_data.h"

namespace q3::light::quality {

using q3::test::addQuad;

// An empty BSP with the given shader names and worldspawn keys; add quads, then finish().
inline bsp::Bsp emptyBsp(const std::vector<std::string>& shaders) {
    bsp::Bsp b;
    b.version = bsp::kVersionQ3;
    b.headerLumps = 18;
    for (const std::string& name : shaders) {
        bsp::Shader sh{};
        std::strncpy(sh.name, name.c_str(), sizeof(sh.name) - 1);
        sh.contentFlags = 1;
        b.shaders.push_back(sh);
    }
    return b;
}

inline void finish(bsp::Bsp& b, std::vector<std::pair<std::string, std::string>> worldspawn) {
    bsp::Model world{};
    Bounds bounds;
    for (const bsp::DrawVert& v : b.drawVerts) bounds.add(Vec3::fromArray(v.xyz));
    bounds.mins.toArray(world.mins);
    bounds.maxs.toArray(world.maxs);
    world.firstSurface = 0;
    world.numSurfaces = static_cast<int32_t>(b.surfaces.size());
    b.models.push_back(world);
    std::vector<bsp::Entity> ents(1);
    ents[0].pairs = {{"classname", "worldspawn"}};
    for (auto& kv : worldspawn) ents[0].pairs.push_back(kv);
    b.entities = bsp::unparseEntities(ents);
}

// Writes the BSP as <tmp>/game/maps/<name>.bsp and `shaderScript` as <tmp>/game/scripts/test.shader.
inline std::filesystem::path writeScene(const bsp::Bsp& b, const std::string& name,
                                        const std::string& shaderScript = "") {
    const std::filesystem::path game = q3::test::tempDir() / "game";
    std::filesystem::create_directories(game / "maps");
    if (!shaderScript.empty()) {
        std::filesystem::create_directories(game / "scripts");
        writeFileAtomic(game / "scripts" / "test.shader", shaderScript);
    }
    const std::filesystem::path path = game / "maps" / (name + ".bsp");
    writeFileAtomic(path, bsp::serializeBsp(b));
    return path;
}

// Options parsed as the command line would give them.
inline LightOptions lightOptions(const std::vector<std::string>& args) {
    LightOptions options;
    cli::parseOptions(lightOptionTable(), args, cli::ParseContext{"-light", {}, {}}, options);
    return options;
}

inline int runLight(const std::filesystem::path& bspPath, const std::vector<std::string>& args, int threads = 2) {
    CommonOptions common;
    common.mapPath = bspPath;
    common.threads = threads;
    common.commandLine = "-light";
    Log log(false);
    return runLightStage(lightOptions(args), common, log);
}

// Lightmap texel of surface `s` at its luxel (x, y) (clamped into the stored block, which may be a
// single texel for a solid lightmap).
inline std::array<int, 3> texel(const bsp::Bsp& b, int s, int x, int y) {
    const bsp::Surface& surface = b.surfaces[static_cast<size_t>(s)];
    EXPECT_GE(surface.lightmapNum, 0);
    x = std::clamp(x, 0, std::max(0, surface.lightmapWidth - 1));
    y = std::clamp(y, 0, std::max(0, surface.lightmapHeight - 1));
    const size_t page = static_cast<size_t>(std::max(0, surface.lightmapNum)) * 128 * 128 * 3;
    const size_t at = page + (static_cast<size_t>(surface.lightmapY + y) * 128 + surface.lightmapX + x) * 3;
    if (at + 2 >= b.lightmaps.size()) return {-1, -1, -1};
    return {b.lightmaps[at], b.lightmaps[at + 1], b.lightmaps[at + 2]};
}

// The mapped luxel of surface `s` whose origin is nearest `where`.
inline std::array<int, 2> luxelNear(const bsp::Bsp& b, int s, Vec3 where) {
    SurfaceGeometry g = surfaceGeometry(b, s);
    std::optional<RawLightmap> raw = layoutSurfaceLightmap(g, SurfaceLightmapParams{}, LayoutOptions{});
    EXPECT_TRUE(raw.has_value());
    std::array<int, 2> best{0, 0};
    float bestDistance = 1e30f;
    if (!raw) return best;
    for (int y = 0; y < raw->height; ++y)
        for (int x = 0; x < raw->width; ++x) {
            const Luxel& lx = raw->luxel(x, y);
            if (!lx.mapped) continue;
            const float d = distance(lx.origin, where);
            if (d < bestDistance) {
                bestDistance = d;
                best = {x, y};
            }
        }
    return best;
}

}  // namespace q3::light::quality
