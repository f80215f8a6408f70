// The -bsp stage on a .map text: load (brushes, patches, entities, func_group, origin brushes),
// world tree, portals, flood, areas, faces, patches, fog, T-junctions, lumps, .srf and .prt, with a
// fixed shader set and no game files (misc_model entities are skipped with a warning).
#include "fuzz_entries.h"

#include "bsp_brushes.h"
#include "bsp_compile.h"
#include "log.h"
#include "map_file.h"
#include "script.h"
#include "shader_info.h"
#include "shader_loader.h"
#include "texture_sizes.h"

#include <string>
#include <string_view>

namespace q3::fuzz {
namespace {

// Every compile flag the stage tells apart: caulk, hint, skip, areaportal, origin, clip, detail,
// water, lava (tessSize), fog, sky, and the texture names the -bsp samples use.
constexpr std::string_view kShaders = R"(
textures/common/caulk { surfaceparm nodraw surfaceparm nolightmap surfaceparm nomarks }
textures/common/hint { surfaceparm nodraw surfaceparm nonsolid surfaceparm structural surfaceparm trans surfaceparm hint }
textures/common/skip { surfaceparm nodraw surfaceparm nonsolid surfaceparm structural surfaceparm trans surfaceparm skip }
textures/common/areaportal { surfaceparm nodraw surfaceparm nonsolid surfaceparm structural surfaceparm trans surfaceparm areaportal }
textures/common/origin { surfaceparm nodraw surfaceparm nonsolid surfaceparm trans surfaceparm origin }
textures/common/clip { surfaceparm nodraw surfaceparm nonsolid surfaceparm trans surfaceparm playerclip }
textures/base/detailwall { surfaceparm detail }
textures/samples/wall { q3map_textureSize 128 128 }
textures/samples/trim { q3map_textureSize 256 32 }
textures/samples/water { surfaceparm trans surfaceparm nonsolid surfaceparm water }
textures/samples/lava { tessSize 64 surfaceparm trans surfaceparm nonsolid surfaceparm lava }
textures/samples/fog { surfaceparm trans surfaceparm nonsolid surfaceparm fog fogparms ( 0.5 0.5 0.6 ) 512 }
textures/samples/sky { surfaceparm sky surfaceparm noimpact surfaceparm nolightmap skyParms - 512 - }
)";

const ShaderTable& fuzzShaders() {
    static Log log(false);
    static const ShaderTable table = buildShaderTable({{"scripts/fuzz.shader", "fuzz.shader", std::string(kShaders)}}, {},
                                                      false, log);
    return table;
}

}  // namespace

void fuzzMapBsp(std::span<const uint8_t> input, const FuzzContext&) {
    map::MapFile file;
    try {
        file = map::parseMap({reinterpret_cast<const char*>(input.data()), input.size()}, "fuzz.map");
    } catch (const ScriptError&) {
        return;
    }
    Log log(false);
    const ShaderTable& shaders = fuzzShaders();
    bspstage::CompiledBsp compiled;
    try {
        bspstage::LoadedMap loaded = bspstage::loadMapForBsp(file, shaders, {}, log);
        const bspstage::TextureSizes textures;
        compiled = bspstage::compileBsp({loaded, file, shaders, textures}, bspstage::BspCompileOptions{}, log);
    } catch (const CompileError&) {
        return;
    }
    // What the stage writes must read back: the BSP through the validating reader, the portal file
    // through -vis's parser.
    const std::vector<uint8_t> bytes = bsp::serializeBsp(compiled.bsp, "fuzz.bsp");
    try {
        bsp::parseBsp(bytes, "fuzz.bsp");
    } catch (const bsp::BspError& e) {
        throw PropertyViolation(std::string("-bsp wrote a BSP its reader refuses: ") + e.what());
    }
    if (compiled.world.leaked != compiled.world.portalFile.empty())
        throw PropertyViolation("-bsp wrote a portal file for a leaking map, or none for a sealed one");
    if (!compiled.world.portalFile.empty()) checkPortalFileReads(compiled.world.portalFile);
}

}  // namespace q3::fuzz
