// Writes the seed corpora of every fuzz target: small real inputs from the OpenArena cache, and our
// own outputs (v46, v47 + SH grid and BSPX BSPs made with the bspfile library, and the JSON folder
// -json -unpack writes for them). Deterministic: the same cache gives the same seeds.
//
// Usage: fuzz_seed_corpus DATA_CACHE OUT_DIR     (OUT_DIR/<target>/ per target)
#include "fuzz_entries.h"

#include "bspfile.h"
#include "file_io.h"
#include "json_stage.h"
#include "log.h"
#include "sh_grid_lump.h"
#include "synthetic_bsp.h"
#include "../sh/world_lights_samples.h"
#include "light_cache_test_bsp.h"

#include <zip.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>
#include <utility>
#include <vector>

namespace {
namespace fs = std::filesystem;

constexpr size_t kMaxTextSeed = 24 * 1024;  // .map and .shader seeds are cut below this size
constexpr size_t kRealBspSeeds = 1;           // the smallest real map is about 680 KB
constexpr size_t kShaderSeeds = 40;

struct SizedFile {
    uintmax_t size;
    fs::path path;
    bool operator<(const SizedFile& o) const { return size != o.size ? size < o.size : path < o.path; }
};

// Files under `root` with `extension` whose parent folder is `folder`, smallest first.
std::vector<SizedFile> filesBySize(const fs::path& root, const std::string& extension, const std::string& folder) {
    std::vector<SizedFile> out;
    for (const auto& item : fs::recursive_directory_iterator(root)) {
        if (!item.is_regular_file()) continue;
        const fs::path& p = item.path();
        if (p.extension() == extension && p.parent_path().filename() == folder) out.push_back({item.file_size(), p});
    }
    std::sort(out.begin(), out.end());
    return out;
}

// Seed file name from the source path, unique within the cache ("pak0_scripts_sfx.shader").
std::string seedName(const fs::path& root, const fs::path& file) {
    std::string name = fs::relative(file, root).string();
    std::replace(name.begin(), name.end(), '/', '_');
    return name;
}

void writeSeed(const fs::path& dir, const std::string& name, std::span<const uint8_t> bytes) {
    fs::create_directories(dir);
    q3::writeFileAtomic(dir / name, bytes);
}
void writeSeed(const fs::path& dir, const std::string& name, const std::string& text) {
    writeSeed(dir, name, std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(text.data()), text.size()));
}

// A prefix of a .map source that is still a complete file: cut after the last brush or patch of the
// first entity that ends below `limit`, then close that entity.
std::string completeMapPrefix(const std::string& text, size_t limit) {
    if (text.size() <= limit) return text;
    int depth = 0;
    size_t lastCut = std::string::npos;
    size_t lineStart = 0;
    while (lineStart < text.size() && lineStart < limit) {
        size_t lineEnd = text.find('\n', lineStart);
        if (lineEnd == std::string::npos) lineEnd = text.size();
        std::string_view line(text.data() + lineStart, lineEnd - lineStart);
        while (!line.empty() && (line.back() == '\r' || line.back() == ' ' || line.back() == '\t')) line.remove_suffix(1);
        while (!line.empty() && (line.front() == ' ' || line.front() == '\t')) line.remove_prefix(1);
        if (line == "{") ++depth;
        if (line == "}") {
            --depth;
            if (depth == 1 && lineEnd + 1 <= limit) lastCut = lineEnd + 1;
        }
        lineStart = lineEnd + 1;
    }
    if (lastCut == std::string::npos) return text.substr(0, limit);
    return text.substr(0, lastCut) + "}\n";
}

// A prefix of a shader script that ends after a complete top-level shader.
std::string completeShaderPrefix(const std::string& text, size_t limit) {
    if (text.size() <= limit) return text;
    int depth = 0;
    size_t lastCut = 0;
    for (size_t i = 0; i < limit; ++i) {
        if (text[i] == '{') ++depth;
        if (text[i] == '}' && --depth == 0) lastCut = i + 1;
    }
    return text.substr(0, lastCut ? lastCut : limit);
}

// A .pk3 made with minizip, entries deflated or stored, with fixed (zero) timestamps.
std::vector<uint8_t> makePk3(const fs::path& scratchFile, const std::vector<std::pair<std::string, std::string>>& files,
                             bool deflate) {
    zipFile zip = zipOpen64(scratchFile.c_str(), APPEND_STATUS_CREATE);
    if (!zip) throw std::runtime_error(scratchFile.string() + ": cannot create zip");
    for (const auto& [name, data] : files) {
        zip_fileinfo info{};
        if (zipOpenNewFileInZip64(zip, name.c_str(), &info, nullptr, 0, nullptr, 0, nullptr, deflate ? Z_DEFLATED : 0,
                                  deflate ? 6 : 0, 0) != ZIP_OK ||
            zipWriteInFileInZip(zip, data.data(), unsigned(data.size())) != ZIP_OK || zipCloseFileInZip(zip) != ZIP_OK)
            throw std::runtime_error(scratchFile.string() + ": cannot add " + name);
    }
    if (zipClose(zip, nullptr) != ZIP_OK) throw std::runtime_error(scratchFile.string() + ": cannot finish zip");
    std::vector<uint8_t> bytes = q3::readFileBytes(scratchFile);
    fs::remove(scratchFile);
    return bytes;
}

// Hand-written .map text using every primitive form the parser accepts.
std::string syntheticMap() {
    return "Version 2\n"
           "// entity 0\n{\n\"classname\" \"worldspawn\"\n\"_color\" \"1 0.9 0.8\"\n"
           "// brush 0\n{\n"
           "( 0 0 0 ) ( 0 64 0 ) ( 64 0 0 ) base_wall/concrete 0 0 0 0.5 0.5 0 0 0\n"
           "( 0 0 64 ) ( 64 0 64 ) ( 0 64 64 ) base_wall/concrete 0 0 0 0.5 0.5 0 0 0\n"
           "( 0 0 0 ) ( 64 0 0 ) ( 0 0 64 ) base_wall/concrete 0 0 0 0.5 0.5 0 0 0\n"
           "( 0 64 0 ) ( 0 64 64 ) ( 64 64 0 ) base_wall/concrete 0 0 0 0.5 0.5 0 0 0\n"
           "( 0 0 0 ) ( 0 0 64 ) ( 0 64 0 ) base_wall/concrete 0 0 0 0.5 0.5 0 0 0\n"
           "( 64 0 0 ) ( 64 64 0 ) ( 64 0 64 ) base_wall/concrete 0 0 0 0.5 0.5 0 0 0\n"
           "}\n"
           "// brush 1\n{\nbrushDef\n{\n"
           "( 0 0 128 ) ( 0 64 128 ) ( 64 0 128 ) ( ( 0.0078125 0 0 ) ( 0 0.0078125 0 ) ) common/caulk 0 0 0\n"
           "( 0 0 192 ) ( 64 0 192 ) ( 0 64 192 ) ( ( 0.0078125 0 0 ) ( 0 0.0078125 0 ) ) common/caulk 0 0 0\n"
           "( 0 0 128 ) ( 64 0 128 ) ( 0 0 192 ) ( ( 0.0078125 0 0 ) ( 0 0.0078125 0 ) ) common/caulk 0 0 0\n"
           "( 0 64 128 ) ( 0 64 192 ) ( 64 64 128 ) ( ( 0.0078125 0 0 ) ( 0 0.0078125 0 ) ) common/caulk 0 0 0\n"
           "( 0 0 128 ) ( 0 0 192 ) ( 0 64 128 ) ( ( 0.0078125 0 0 ) ( 0 0.0078125 0 ) ) common/caulk 0 0 0\n"
           "( 64 0 128 ) ( 64 64 128 ) ( 64 0 192 ) ( ( 0.0078125 0 0 ) ( 0 0.0078125 0 ) ) common/caulk 0 0 0\n"
           "}\n}\n"
           "// brush 2\n{\n"
           "( 0 0 256 ) ( 0 64 256 ) ( 64 0 256 ) sky [ 1 0 0 0 ] [ 0 -1 0 0 ] 0 0.25 0.25 0 0 0\n"
           "( 0 0 320 ) ( 64 0 320 ) ( 0 64 320 ) sky [ 1 0 0 0 ] [ 0 -1 0 0 ] 0 0.25 0.25 0 0 0\n"
           "( 0 0 256 ) ( 64 0 256 ) ( 0 0 320 ) sky [ 1 0 0 0 ] [ 0 0 -1 0 ] 0 0.25 0.25 0 0 0\n"
           "( 0 64 256 ) ( 0 64 320 ) ( 64 64 256 ) sky [ 1 0 0 0 ] [ 0 0 -1 0 ] 0 0.25 0.25 0 0 0\n"
           "( 0 0 256 ) ( 0 0 320 ) ( 0 64 256 ) sky [ 0 1 0 0 ] [ 0 0 -1 0 ] 0 0.25 0.25 0 0 0\n"
           "( 64 0 256 ) ( 64 64 256 ) ( 64 0 320 ) sky [ 0 1 0 0 ] [ 0 0 -1 0 ] 0 0.25 0.25 0 0 0\n"
           "}\n"
           "// brush 3\n{\npatchDef2\n{\nbase_floor/tile\n( 3 3 0 0 0 )\n(\n"
           "( ( 0 0 0 0 0 ) ( 0 32 16 0 0.5 ) ( 0 64 0 0 1 ) )\n"
           "( ( 32 0 0 0.5 0 ) ( 32 32 16 0.5 0.5 ) ( 32 64 0 0.5 1 ) )\n"
           "( ( 64 0 0 1 0 ) ( 64 32 16 1 0.5 ) ( 64 64 0 1 1 ) )\n"
           ")\n}\n}\n"
           "// brush 4\n{\npatchDef3\n{\nbase_floor/tile\n( 3 3 4 4 0 0 0 )\n(\n"
           "( ( 0 0 0 0 0 ) ( 0 32 16 0 0.5 ) ( 0 64 0 0 1 ) )\n"
           "( ( 32 0 0 0.5 0 ) ( 32 32 16 0.5 0.5 ) ( 32 64 0 0.5 1 ) )\n"
           "( ( 64 0 0 1 0 ) ( 64 32 16 1 0.5 ) ( 64 64 0 1 1 ) )\n"
           ")\n}\n}\n"
           "}\n"
           "// entity 1\n{\n\"classname\" \"light\"\n\"origin\" \"32 32 32\"\n\"light\" \"300\"\n}\n"
           "// entity 2\n{\n\"classname\" \"func_group\"\n{\n"
           "( 0 0 0 ) ( 0 8 0 ) ( 8 0 0 ) common/clip 0 0 0 1 1\n"
           "( 0 0 8 ) ( 8 0 8 ) ( 0 8 8 ) common/clip 0 0 0 1 1\n"
           "( 0 0 0 ) ( 8 0 0 ) ( 0 0 8 ) common/clip 0 0 0 1 1\n"
           "( 0 8 0 ) ( 0 8 8 ) ( 8 8 0 ) common/clip 0 0 0 1 1\n"
           "( 0 0 0 ) ( 0 0 8 ) ( 0 8 0 ) common/clip 0 0 0 1 1\n"
           "( 8 0 0 ) ( 8 8 0 ) ( 8 0 8 ) common/clip 0 0 0 1 1\n"
           "}\n}\n";
}

// Our own BSP outputs: v46 (17 and 18 entries), v47 with lump 18, v46 with a BSPX SH grid; each
// with its 48 KB lightmap page and, smaller and faster to mutate, without it.
std::vector<std::pair<std::string, q3::bsp::Bsp>> ownBsps() {
    using namespace q3::bsp;
    std::vector<std::pair<std::string, Bsp>> out;
    Bsp lit = test::makeSyntheticBsp();
    Bsp unlit = lit;
    unlit.lightmaps.clear();
    for (Surface& surface : unlit.surfaces)
        if (surface.lightmapNum >= 0) surface.lightmapNum = kLightmapByVertex;

    for (const auto& [suffix, plain] : {std::pair<std::string, Bsp>{"", lit}, {"-nolightmap", unlit}}) {
        out.emplace_back("own-v46" + suffix + ".bsp", plain);

        Bsp withLump17 = plain;
        withLump17.headerLumps = 18;
        out.emplace_back("own-v46-18" + suffix + ".bsp", withLump17);

        Bsp sh = plain;
        attachShGrid(sh, test::makeShGridLump(2, 3, 2));
        out.emplace_back("own-v47-sh" + suffix + ".bsp", sh);

        Bsp bspx = plain;
        bspx.setBspx(q3::sh::kBspxLumpName, test::makeShGridLump(3, 2, 2));
        bspx.setBspx("FUZZ_EXTRA", {1, 2, 3, 4, 5, 6, 7});
        out.emplace_back("own-bspx-sh" + suffix + ".bsp", bspx);
    }
    return out;
}

void bspSeeds(const fs::path& cache, const fs::path& out) {
    for (const auto& [name, bsp] : ownBsps()) {
        const std::vector<uint8_t> bytes = q3::bsp::serializeBsp(bsp, name);
        writeSeed(out / "bsp", name, bytes);
        writeSeed(out / "sh_runtime", name, bytes);
    }
    // The smallest real map as shipped, for the quirks of real files (fogNum 0 without fogs, NaN
    // texture coordinates, q3map2's header layout). Real maps are all 700 KB or more and mutate
    // about ten times slower than the synthetic seeds, so one is enough.
    const fs::path loose = cache / "loose";
    std::vector<SizedFile> real = filesBySize(loose, ".bsp", "maps");
    for (size_t i = 0; i < std::min(kRealBspSeeds, real.size()); ++i) {
        const std::vector<uint8_t> bytes = q3::readFileBytes(real[i].path);
        writeSeed(out / "bsp", seedName(loose, real[i].path), bytes);
        writeSeed(out / "sh_runtime", seedName(loose, real[i].path), bytes);
        writeSeed(out / "lightcache", seedName(loose, real[i].path), bytes);
    }
}

void textSeeds(const fs::path& cache, const fs::path& out) {
    const fs::path loose = cache / "loose";
    for (const char* target : {"map", "map_bsp"}) {
        writeSeed(out / target, "own-all-primitives.map", syntheticMap());
        std::vector<SizedFile> maps = filesBySize(loose, ".map", "maps");
        for (size_t i = 0; i < std::min<size_t>(3, maps.size()); ++i)
            writeSeed(out / target, seedName(loose, maps[i].path),
                      completeMapPrefix(q3::readFileText(maps[i].path), kMaxTextSeed));
    }
    // The -bsp samples: small sealed maps, one feature each (areaportal, door, detail and hint,
    // func_group, water and fog, patches, models, _skybox, a leak).
    for (const SizedFile& sample : filesBySize(fs::path(Q3MAP_SOURCE_DIR) / "bsp-samples" / "samples", ".map", "maps"))
        writeSeed(out / "map_bsp", "sample-" + sample.path.filename().string(), q3::readFileText(sample.path));

    std::vector<SizedFile> shaders = filesBySize(loose, ".shader", "scripts");
    // Spread the picks over the size range: small scripts and prefixes of big ones.
    const size_t step = std::max<size_t>(1, shaders.size() / kShaderSeeds);
    for (size_t i = 0; i < shaders.size(); i += step)
        writeSeed(out / "shader", seedName(loose, shaders[i].path),
                  completeShaderPrefix(q3::readFileText(shaders[i].path), kMaxTextSeed));
}

void jsonSeeds(const fs::path& out, const fs::path& scratch) {
    q3::Log log(false);
    const std::pair<std::string, q3::bsp::Bsp> sources[] = {{"own-json.bsp", q3::fuzz::jsonPackSourceBsp()}};
    for (const auto& [name, bsp] : sources) {
        const fs::path folder = scratch / name;
        fs::remove_all(folder);
        q3::json::unpackBsp(bsp, folder, q3::json::JsonOptions{}, log);
        for (const auto& item : fs::directory_iterator(folder)) {
            if (!item.is_regular_file()) continue;
            const std::string file = item.path().filename().string();
            const std::string text = q3::readFileText(item.path());
            const std::string stem = fs::path(name).stem().string();
            writeSeed(out / "json", stem + "-" + file, text);
            writeSeed(out / "json_pack", stem + "-" + file, file + q3::fuzz::kJsonPackSeparator + text);
        }
        fs::remove_all(folder);
    }
}

void pk3Seeds(const fs::path& cache, const fs::path& out, const fs::path& scratch) {
    const fs::path loose = cache / "loose";
    std::vector<std::pair<std::string, std::string>> files;
    std::vector<SizedFile> shaders = filesBySize(loose, ".shader", "scripts");
    std::string shaderList;
    for (size_t i = 0; i < std::min<size_t>(3, shaders.size()); ++i) {
        files.emplace_back("scripts/" + shaders[i].path.filename().string(), q3::readFileText(shaders[i].path));
        shaderList += shaders[i].path.stem().string() + "\n";
    }
    files.emplace_back("scripts/shaderlist.txt", shaderList);
    std::vector<SizedFile> textures = filesBySize(loose, ".tga", "sfx");
    if (!textures.empty())
        files.emplace_back("textures/sfx/" + textures[0].path.filename().string(), q3::readFileText(textures[0].path));
    files.emplace_back("Maps/Upper.TXT", "case-insensitive look-ups\n");

    writeSeed(out / "pk3", "real-deflated.pk3", makePk3(scratch / "deflated.pk3", files, true));
    writeSeed(out / "pk3", "real-stored.pk3", makePk3(scratch / "stored.pk3", files, false));
    writeSeed(out / "pk3", "one-entry.pk3", makePk3(scratch / "one.pk3", {{"scripts/a.shader", "a\n{\n}\n"}}, true));
    writeSeed(out / "pk3", "empty.pk3", makePk3(scratch / "empty.pk3", {}, true));
}

// Hand-written portal files: two rooms with a solid face, four rooms whose openings zig-zag
// (hint and sky flags set), and a map without portals.
void prtSeeds(const fs::path& out) {
    auto opening = [](const char* clusters, int x, int y0) {
        const std::string xs = std::to_string(x), y = std::to_string(y0), y1 = std::to_string(y0 + 10);
        return std::string("4 ") + clusters + " (" + xs + " " + y + " 0 ) (" + xs + " " + y1 + " 0 ) (" + xs + " " + y1 +
               " 10 ) (" + xs + " " + y + " 10 ) \n";
    };
    writeSeed(out / "prt", "two-rooms.prt",
              "PRT1\n2\n1\n1\n" + opening("0 1 0", 0, 0) + "3 1 (5 0 0 ) (5 10 0 ) (5 10 10 ) \n");
    const std::string zigZag =
        "PRT1\n4\n3\n0\n" + opening("0 1 1", 0, 0) + opening("1 2 0", 10, 30) + opening("2 3 2", 20, 0);
    const std::string sideBySide = "PRT1\n2\n2\n0\n" + opening("0 1 0", 0, 0) + opening("0 1 0", 0, 10);
    writeSeed(out / "prt", "zigzag.prt", zigZag);
    writeSeed(out / "prt", "side-by-side.prt", sideBySide);
    // A leading "\v" or "\r" turns on -merge / -mergeportals with -hint (see fuzzPrt).
    writeSeed(out / "prt", "zigzag-merge-hint.prt", "\v" + zigZag);
    writeSeed(out / "prt", "side-by-side-mergeportals.prt", "\r" + sideBySide);
    writeSeed(out / "prt", "no-portals.prt", "PRT1\n1\n0\n0\n");
}

// The light cache tests' pillar room: as written there, and with two clusters, a visibility lump,
// a sun and a small SH grid.
void lightCacheSeeds(const fs::path& out) {
    namespace t = q3::sh::test;
    t::TestMap room = t::roomWithPillar();
    writeSeed(out / "lightcache", "own-pillar-room.bsp", t::buildTestBsp(room));
    room.numClusters = 2;
    room.cluster = [](const float*, const float maxs[3]) { return maxs[0] <= 0 ? 0 : 1; };
    room.visible = [](int32_t from, int32_t to) { return from == to; };
    q3::sh::WorldLight sun;
    sun.type = q3::sh::WorldLightType::Sun;
    sun.falloff = q3::sh::WorldLightFalloff::Parallel;
    sun.direction = {0, 0.6f, 0.8f};
    sun.intensity = {1, 1, 1};
    room.lights.push_back(sun);
    room.boxes[1].shader = t::kShaderSky;
    const std::vector<uint8_t> gridLump = q3::bsp::test::makeShGridLump(2, 2, 2);
    q3::sh::GridSH grid;
    std::string error;
    if (!q3::sh::decodeGridLump(gridLump.data(), gridLump.size(), grid, error)) throw std::runtime_error(error);
    room.grid = grid;
    writeSeed(out / "lightcache", "own-pillar-room-vis-sun-grid.bsp", t::buildTestBsp(room));
}

void worldLightSeeds(const fs::path& out) {
    writeSeed(out / "world_lights", "every-model.lump", q3::sh::encodeWorldLights(q3::sh::test::sampleWorldLights()));
    writeSeed(out / "world_lights", "empty.lump", q3::sh::encodeWorldLights({}));
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: %s DATA_CACHE OUT_DIR\n", argv[0]);
        return 2;
    }
    const fs::path cache = argv[1];
    const fs::path out = argv[2];
    try {
        if (!fs::is_directory(cache / "loose")) throw std::runtime_error(cache.string() + ": no loose/ folder (run tools/fetch-openarena.sh)");
        const fs::path scratch = out / ".scratch";
        fs::create_directories(scratch);
        bspSeeds(cache, out);
        textSeeds(cache, out);
        jsonSeeds(out, scratch);
        pk3Seeds(cache, out, scratch);
        prtSeeds(out);
        worldLightSeeds(out);
        lightCacheSeeds(out);
        fs::remove_all(scratch);
        for (const q3::fuzz::FuzzEntry& entry : q3::fuzz::fuzzEntries()) {
            size_t count = 0;
            for (const auto& item : fs::directory_iterator(out / std::string(entry.name))) count += item.is_regular_file();
            std::printf("%-12s %zu seeds\n", std::string(entry.name).c_str(), count);
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "fuzz_seed_corpus: %s\n", e.what());
        return 1;
    }
    return 0;
}
