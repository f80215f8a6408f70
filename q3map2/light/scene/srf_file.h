// The .srf file written by -bsp beside the map: per-surface compile attributes that the BSP has no
// room for (sample size, lightmap axis, shadow groups, cloned parents...). -light reads it first.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "vec3.h"

namespace q3::light {

struct SurfaceExtra {
    std::string shader;          // compile-time shader; empty = use the BSP shader
    int parent = -1;             // surface this one was cloned from (shares its lighting), -1 = none
    int entity = 0;              // originating .map entity
    int castShadows = 1;         // shadow groups
    int receiveShadows = 1;
    int sampleSize = 16;         // final luxel size decided by -bsp
    Vec3 ambientColor{0, 0, 0};  // per-entity _ambient; zero = use the global one
    float longestCurve = 0.0f;   // patch subdivision hint for tracing
    Vec3 lightmapAxis{0, 0, 0};  // projection axis; zero = choose from the plane
};

struct SurfaceExtras {
    bool loaded = false;                 // false: no file, every surface uses the defaults
    SurfaceExtra defaults;               // the "default" block
    std::vector<SurfaceExtra> surfaces;  // indexed by surface number; blocks start from `defaults`
    std::vector<bool> present;           // which surface numbers had a block

    // The extra of a surface; the defaults for surfaces the file does not mention.
    const SurfaceExtra& forSurface(int surface) const;
};

// Parses .srf text. `name` is used in errors ("<name>:<line>: <what is wrong>", ScriptError).
// Unknown keys are skipped with the rest of their line, as q3map2 does. `defaultSampleSize` (-samplesize)
// is the sample size before the file's "default" block overrides it.
SurfaceExtras parseSurfaceExtras(std::string_view text, const std::string& name, int defaultSampleSize = 16);

// Reads a .srf file. A missing file gives {loaded = false} with `defaultSampleSize` in the defaults
// (the caller notes it); unreadable or malformed files throw.
SurfaceExtras loadSurfaceExtras(const std::filesystem::path& path, int defaultSampleSize = 16);

}  // namespace q3::light
