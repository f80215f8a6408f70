// The SH light grid of `-light -sh` (specs/sh-grid.md): its layout (cell size from -gridsh, or the
// worldspawn "gridsize" divided by -gridscalesh; bounds of model 0; growth past the 256 MiB lump
// limit), its trace (every light the legacy grid sees, projected as L2 irradiance from its true
// directions; close area lights integrated over their surface; ambient and minlight floors on the uniform
// band; points in solid nudged out or filled from their neighbours) and how it is stored in a BSP
// (lump 18 of version 47, or the BSPX lump LIGHTGRID_SH of version 46).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "bspfile.h"
#include "grid_blocks.h"
#include "light_types.h"
#include "sh.h"
#include "sh_grid_lump.h"
#include "vec3.h"

namespace q3 {
class Log;
}

namespace q3::light {

struct LightContext;
struct Light;
struct LightingEnv;

constexpr float kMinShCellSize = 8.0f;                          // smallest SH cell axis, also the growth step
// Largest SH lump: engines read the whole BSP into their hunk (ioquake3 loads oacmpdm9 with a 242 MB
// SH grid and refuses oacmpctf3 with 588 MB), so a larger grid would make the map unplayable.
constexpr uint64_t kMaxShLumpBytes = uint64_t{1} << 28;  // 256 MiB

struct ShGridLayout {
    Vec3 requestedSize;            // from -gridsh or gridsize / -gridscalesh, before the clamp
    Vec3 size;                     // final cell size
    Vec3 mins;                     // world position of point (0,0,0)
    std::array<int, 3> bounds{};   // points per axis, each >= 1
    int growSteps = 0;             // times every axis grew by kMinShCellSize to fit kMaxShLumpBytes
    bool clamped = false;          // an axis was raised to kMinShCellSize

    uint64_t numPoints() const {
        return uint64_t(bounds[0]) * uint64_t(bounds[1]) * uint64_t(bounds[2]);
    }
    uint64_t lumpBytes() const { return sh::kGridHeaderBytes + sh::kGridPointBytes * numPoints(); }
    Vec3 pointOrigin(int x, int y, int z) const {
        return {mins.x + float(x) * size.x, mins.y + float(y) * size.y, mins.z + float(z) * size.z};
    }
};

// Pure layout rule: requested cell size (each axis clamped to >= 8), bounds of the world
// (mins = s*ceil(worldMins/s), maxs = s*floor(worldMaxs/s), bounds = (maxs-mins)/s + 1, at least 1),
// growth of every axis by 8 while the lump would exceed `maxLumpBytes`.
ShGridLayout computeShGridLayout(Vec3 requestedSize, Vec3 worldMins, Vec3 worldMaxs,
                                 uint64_t maxLumpBytes = kMaxShLumpBytes);

// The requested SH cell size of a run: -gridsh when given, else worldspawn "gridsize" (default
// 64 64 128) divided by -gridscalesh per axis. Throws CompileError for a malformed "gridsize".
Vec3 requestedShCellSize(const LightContext& ctx);

// SetupGridSH: layout from the options, worldspawn and model 0; warns when an axis is clamped to 8
// and when the cell grows to fit kMaxShLumpBytes (naming the final size).
ShGridLayout setupGridSH(const LightContext& ctx, Log& log);

struct ShTraceStats {
    uint64_t points = 0;
    std::array<int, 3> bounds{};  // points per axis
    uint64_t nudged = 0;          // started in solid, moved out within half a cell
    uint64_t inSolid = 0;         // stayed in solid (filled from neighbours)
    uint64_t filled = 0;          // in-solid points that received a neighbour average
    uint64_t blackBeforeFill = 0; // all-zero points after the trace
    uint64_t blackAfterFill = 0;  // all-zero points at the end
    std::vector<uint8_t> solid;   // per point: 1 = stayed in solid
    std::vector<Vec3> origins;    // per point, with -shgather only: where it was lit (lattice or nudged position)
    uint64_t sharedPairs = 0;     // (light, probe) pairs taken from their block's corners or left out (none with -shexact)
};

// The SH projection of one light at one (free) grid point, in SH units (1.0 = legacy byte 255,
// before -gridscale). Returns the legacy grid's contribution of the light (nullopt when it does not
// reach the point, and then nothing is added). Area lights close to the point (within 4 times their
// radius) are integrated exactly over the directions they cover, unless `areaAsOneSample`; far or
// faint ones are one directional sample.
std::optional<LightContribution> addLightToGridPointSH(sh::SH9Color& acc, const Light& light, Vec3 origin,
                                                       int cluster, const LightingEnv& env,
                                                       bool areaAsOneSample = false);

// Projects a contribution of `light` at `origin` whose shadow ray let `transmission` through
// (c.color already multiplied by it): close area lights integrated over their emitter unless
// `areaAsOneSample`, every other light one directional sample. Returns whether it integrated an
// emitter (the costly form; the others are cheap to project again).
bool projectContribution(sh::SH9Color& acc, const Light& light, Vec3 origin, const LightContribution& c,
                         Vec3 transmission, const ContributionSettings& settings, bool areaAsOneSample);

// Whether `light` is far enough from `box` (the box of a block's corners) that its light varies
// smoothly over the block: the gap between the box and the light (an area light's emitter sphere)
// is at least the box's largest extent. Suns are parallel light.
bool farFromBlock(const Light& light, const Bounds& box);

// The same for every style-0 light of `candidates` (indices into `lights`, in order), their shadow
// rays traced as one batch.
void addLightsToGridPointSH(sh::SH9Color& acc, std::span<const Light> lights, std::span<const uint32_t> candidates,
                            Vec3 origin, int cluster, const LightingEnv& env);
// The same for several free points (`origins`, `clusters`, one accumulator each), the shadow rays
// of all of them traced as one batch; each point still adds its lights in light order.
// `clearOfSolid[k]`, when given, says that candidate k's rays from every point meet no structural
// solid; `envelopes`, when given, holds lightEnvelope of every light.
void addLightsToGridPointsSH(std::span<sh::SH9Color> accs, std::span<const Light> lights,
                             std::span<const uint32_t> candidates, std::span<const uint8_t> clearOfSolid,
                             std::span<const float> envelopes, std::span<const Vec3> origins,
                             std::span<const int> clusters, const LightingEnv& env);

// Ambient and the minlight floor on coefficient 0 (inputs in legacy units, 0..255): the ambient
// adds ambient/255 * 2*sqrt(pi); then, per channel, coefficient 0 is raised so that the uniform
// part's irradiance c0 * Y_0 reaches minLight/255.
void applyAmbientAndFloor(sh::SH9Color& acc, Vec3 ambient, Vec3 minLight);

// Neighbour fill of the points marked in `unset`: each pass gives every unset point next to a set
// one (6-neighbourhood) the average of its set neighbours, then marks it set; repeated until no
// point changes. Works in the lump image itself. Returns how many points received a value.
uint64_t fillFromNeighbours(sh::GridLumpImage& grid, std::vector<uint8_t>& unset);

// TraceGridSH: one SH point per layout point, in parallel (each point writes its own slot, so
// the result does not depend on the thread count). Each point is encoded straight into the lump
// image as it is lit: the grid exists once, already in the form the BSP stores.
sh::GridLumpImage traceGridSH(const LightContext& ctx, const ShGridLayout& layout, Log& log, ShTraceStats* stats = nullptr);

// With bspx false: lump 18, version 47, 19 header entries (lump 17 left as it is: empty for
// q3map2 output). With bspx true: version 46 and the BSPX lump LIGHTGRID_SH (lump 18 dropped).
// The image's bytes move into the BSP (no copy); `grid` is left empty.
void attachGridSH(bsp::Bsp& bsp, sh::GridLumpImage&& grid, bool bspx);
// Removes an SH grid an earlier -sh run left (lump 18, then version 46 again, or the BSPX lump): a
// run that lights without -sh must not keep a grid that no longer matches its light.
void removeGridSH(bsp::Bsp& bsp);

// The whole SH step of the stage, for the pipeline after lightGrid: nothing without -sh; else
// setupGridSH, traceGridSH and attachGridSH(ctx.bsp, std::move(grid), ctx.options.shBspx). Returns the stats.
ShTraceStats lightGridSH(LightContext& ctx, Log& log);

}  // namespace q3::light
