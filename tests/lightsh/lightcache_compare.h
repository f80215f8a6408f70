// A map lit twice by the compiler (SH grid with the world lights in it; SH grid without them plus
// the WORLDLIGHTS lump) and the three ways a moving model can be lit there: brute force (every
// world light with the compiler's own occlusion at the exact position, plus what the grid holds
// besides those lights), the SH grid alone, and the grid without the lights plus the light cache.
// Shared by the accuracy tests and the lightcachepath picture tool.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "image.h"
#include "light_cache.h"
#include "light_context.h"

namespace q3::light::cachetest {

struct MapInputs {
    std::filesystem::path bsp;        // the input BSP
    std::filesystem::path mapSource;  // its .map, where -light finds the light entities
    std::vector<std::string> basePaths;
    std::string fsGame;
};

// `count` unit vectors spread evenly over the sphere (spherical Fibonacci).
std::vector<Vec3> fibonacciNormals(int count);

class LitMap {
public:
    // Lights two copies in `work` (-light -fast -nolm, with -sh -worldlights and with
    // -shnoworldlights) and loads them; error() says what failed.
    LitMap(const MapInputs& in, const std::filesystem::path& work);

    const std::string& error() const { return error_; }
    const std::vector<uint8_t>& cacheBytes() const { return cacheBytes_; }
    const sh::LightCache& cache() const { return cache_; }
    size_t listedLights() const { return listed_.size(); }
    bool open(Vec3 p) const;
    // Distance from `p` to the nearest point or spot light of the lump.
    float nearestLocalLight(Vec3 p) const;

    // Irradiance (RGB, SH grid units) at `p` towards each normal, three ways.
    struct Irradiance {
        std::vector<Vec3> bruteForce, shAlone, withCache;
    };
    Irradiance irradianceAt(Vec3 p, const std::vector<Vec3>& normals) const;

    struct Errors {
        double shAlone = 0;     // mean over the normals of |SH grid alone - brute force|, RGB summed
        double withCache = 0;   // the same for the grid without the lights plus the light cache
        double truthScale = 0;  // mean |brute force|, RGB summed
    };
    Errors errorsAt(Vec3 p, const std::vector<Vec3>& normals) const;

private:
    std::vector<Vec3> bruteForceDirect(Vec3 p, const std::vector<Vec3>& normals) const;

    std::string error_;
    std::vector<uint8_t> cacheBytes_;
    sh::GridRuntime fullGrid_;
    sh::LightCache cache_;
    LightContext ctx_;
    std::vector<const Light*> listed_;
    LightingEnv env_;
};

// One column per position, three rows (brute force, SH grid alone, SH grid + light cache), each
// cell a sphere seen from above (+Z towards the viewer, +X right, +Y up) shaded by that row's
// irradiance; `cell` pixels a side, displayed as 1 - exp(-exposure * irradiance) with gamma 2.2.
Image renderPathPicture(const LitMap& map, const std::vector<Vec3>& positions, int cell, float exposure);

}  // namespace q3::light::cachetest
