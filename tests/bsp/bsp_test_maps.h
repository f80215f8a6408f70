// Small hand-made .map texts and the shader set they use, for the -bsp step tests.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bsp_brushes.h"
#include "file_io.h"
#include "log.h"
#include "map_file.h"
#include "shader_info.h"
#include "shader_loader.h"
#include "world_structure.h"

namespace q3::bspstage::test {

// The common shaders as GtkRadiant's common.shader defines them (the ones these tests use).
inline ShaderTable commonShaders(Log& log) {
    static const char* const kScript = R"(
textures/common/caulk
{
	surfaceparm nodraw
	surfaceparm nolightmap
	surfaceparm nomarks
}
textures/common/hint
{
	surfaceparm nodraw
	surfaceparm nonsolid
	surfaceparm structural
	surfaceparm trans
	surfaceparm noimpact
	surfaceparm hint
}
textures/common/skip
{
	surfaceparm nodraw
	surfaceparm nonsolid
	surfaceparm structural
	surfaceparm trans
	surfaceparm noimpact
	surfaceparm skip
}
textures/common/areaportal
{
	surfaceparm nodraw
	surfaceparm nolightmap
	surfaceparm nonsolid
	surfaceparm structural
	surfaceparm trans
	surfaceparm nomarks
	surfaceparm areaportal
}
textures/common/clip
{
	surfaceparm nodraw
	surfaceparm nolightmap
	surfaceparm nonsolid
	surfaceparm trans
	surfaceparm nomarks
	surfaceparm noimpact
	surfaceparm playerclip
}
textures/common/origin
{
	surfaceparm nodraw
	surfaceparm nolightmap
	surfaceparm nonsolid
	surfaceparm trans
	surfaceparm origin
}
textures/liquids/water
{
	surfaceparm trans
	surfaceparm nonsolid
	surfaceparm water
}
textures/base/detailwall
{
	surfaceparm detail
}
textures/skies/stars
{
	surfaceparm sky
	surfaceparm noimpact
	surfaceparm nolightmap
	skyParms env/stars - -
}
)";
    std::vector<ShaderScriptSource> scripts{{"scripts/common.shader", "common.shader", kScript}};
    return buildShaderTable(scripts, {}, false, log);
}

// An axial box brush in the classic (Quake) format, planes facing out.
// `detail` sets the editor's detail bit (0x8000000) in the face flags.
inline std::string boxBrush(DVec3 mins, DVec3 maxs, const std::string& texture = "base/wall", bool detail = false) {
    auto n = [](double v) {
        std::string s = std::to_string(v);
        s.erase(s.find_last_not_of('0') + 1);
        if (s.back() == '.') s.pop_back();
        return s;
    };
    auto p = [&](double x, double y, double z) { return "( " + n(x) + " " + n(y) + " " + n(z) + " ) "; };
    const std::string tex = texture + (detail ? " 0 0 0 0.5 0.5 134217728 0 0\n" : " 0 0 0 0.5 0.5 0 0 0\n");
    std::string s = "{\n";
    s += p(mins.x, 0, 0) + p(mins.x, 1, 0) + p(mins.x, 0, 1) + tex;
    s += p(maxs.x, 0, 0) + p(maxs.x, 0, 1) + p(maxs.x, 1, 0) + tex;
    s += p(0, mins.y, 0) + p(0, mins.y, 1) + p(1, mins.y, 0) + tex;
    s += p(0, maxs.y, 0) + p(1, maxs.y, 0) + p(0, maxs.y, 1) + tex;
    s += p(0, 0, mins.z) + p(1, 0, mins.z) + p(0, 1, mins.z) + tex;
    s += p(0, 0, maxs.z) + p(0, 1, maxs.z) + p(1, 0, maxs.z) + tex;
    return s + "}\n";
}

// Six wall brushes `thickness` thick around the open box inner (mins, maxs).
inline std::string hollowRoom(DVec3 mins, DVec3 maxs, double thickness = 16, const std::string& texture = "base/wall") {
    const DVec3 t = DVec3::splat(thickness);
    const DVec3 lo = mins - t, hi = maxs + t;
    std::string s;
    s += boxBrush(lo, {mins.x, hi.y, hi.z}, texture);
    s += boxBrush({maxs.x, lo.y, lo.z}, hi, texture);
    s += boxBrush({mins.x, lo.y, lo.z}, {maxs.x, mins.y, hi.z}, texture);
    s += boxBrush({mins.x, maxs.y, lo.z}, {maxs.x, hi.y, hi.z}, texture);
    s += boxBrush({mins.x, mins.y, lo.z}, {maxs.x, maxs.y, mins.z}, texture);
    s += boxBrush({mins.x, mins.y, maxs.z}, {maxs.x, maxs.y, hi.z}, texture);
    return s;
}

inline std::string worldspawn(const std::string& brushes, const std::string& keys = {}) {
    return "{\n\"classname\" \"worldspawn\"\n" + keys + brushes + "}\n";
}

inline std::string pointEntity(const std::string& classname, DVec3 origin) {
    char text[160];
    std::snprintf(text, sizeof text, "{\n\"classname\" \"%s\"\n\"origin\" \"%g %g %g\"\n}\n", classname.c_str(), origin.x,
                  origin.y, origin.z);
    return text;
}

// Parses, loads and runs the world structure steps on a .map text.
struct CompiledMap {
    map::MapFile file;
    LoadedMap map;
    WorldStructure world;
};

inline std::unique_ptr<CompiledMap> compileMapText(const std::string& text, WorldStructureOptions options = {},
                                                   MapLoadOptions load = {}) {
    static Log log(false);
    static const ShaderTable shaders = commonShaders(log);
    auto out = std::make_unique<CompiledMap>();
    // Q3MAP_BSP_DUMP_MAPS=<dir> keeps every map text, to compile it with the reference q3map2.
    if (const char* dump = std::getenv("Q3MAP_BSP_DUMP_MAPS")) {
        static int serial = 0;
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        writeFileAtomic(std::filesystem::path(dump) / (std::string(info->name()) + "_" + std::to_string(serial++) + ".map"),
                        text);
    }
    out->file = map::parseMap(text, "test.map");
    out->map = loadMapForBsp(out->file, shaders, load, log);
    out->world = buildWorldStructure(out->map, options, log);
    return out;
}

}  // namespace q3::bspstage::test
