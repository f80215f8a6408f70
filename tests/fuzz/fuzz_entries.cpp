#include "fuzz_entries.h"

#include <array>

namespace q3::fuzz {

namespace {

constexpr std::array kEntries = {
    FuzzEntry{"bsp", fuzzBsp, "IBSP reader: parseBsp (default and -force), validateBsp, write/read round trip, entities"},
    FuzzEntry{"sh_runtime", fuzzShRuntime, "SH grid runtime: GridRuntime::loadFromBsp, sampling, irradiance, lump re-encode"},
    FuzzEntry{"map", fuzzMap, ".map parser: parseMap, entity helpers, texture projections of every face"},
    FuzzEntry{"map_bsp", fuzzMapBsp, "-bsp on a .map: loadMapForBsp and compileBsp (tree, portals, surfaces, lumps), output read back"},
    FuzzEntry{"shader", fuzzShader, "shader script parser: parseShaderScript"},
    FuzzEntry{"json", fuzzJson, "JSON reader: parseDocument with every value conversion, streaming readNumFile"},
    FuzzEntry{"json_pack", fuzzJsonPack, "-json -pack: packFolder on an unpacked folder with one file replaced"},
    FuzzEntry{"pk3", fuzzPk3, "pk3 archives: Pk3Archive table of contents and entries, Vfs look-ups and listings"},
    FuzzEntry{"prt", fuzzPrt, ".prt reader: parsePortalFile; on small files the merges, base vis, passages and every flow mode"},
    FuzzEntry{"world_lights", fuzzWorldLights, "WORLDLIGHTS lump: decodeWorldLights, re-encode, evaluateWorldLight of every record"},
    FuzzEntry{"lightcache", fuzzLightCache, "light cache: LightCache::loadFromBsp (tree, brushes, visibility, WORLDLIGHTS, grid), queries at the origin, far away and by each light"},
};

}  // namespace

std::span<const FuzzEntry> fuzzEntries() { return kEntries; }

const FuzzEntry* findFuzzEntry(std::string_view name) {
    for (const FuzzEntry& entry : kEntries)
        if (entry.name == name) return &entry;
    return nullptr;
}

}  // namespace q3::fuzz
