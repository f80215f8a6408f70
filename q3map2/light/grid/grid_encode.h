// The legacy light grid (BSP lump 15): its layout as q3map2 and the engines compute it from model 0,
// and the encoding of one grid point from the light that reaches it.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "bspfile.h"
#include "color_pipeline.h"
#include "light_types.h"
#include "vec3.h"

namespace q3::light {

constexpr int kMaxGridPoints = 0x100000;  // MAX_MAP_LIGHTGRID
constexpr float kGridGrowStep = 16.0f;     // added to one axis (x, y, z in turn) while too many points
inline constexpr Vec3 kDefaultGridSize{64.0f, 64.0f, 128.0f};

// Parses a worldspawn "gridsize" value ("x y z"). An empty value gives the default 64 64 128.
// Throws CompileError naming `where` when the value is not three numbers.
Vec3 parseGridSize(std::string_view value, const std::string& where);

struct GridLayout {
    Vec3 requestedSize;             // as parsed, before flooring
    Vec3 size;                      // final cell size: floored, >= 8, grown until the count fits
    Vec3 mins;                      // world position of point (0,0,0)
    std::array<int, 3> bounds{};    // points per axis
    int growSteps = 0;              // how many times 16 units were added

    int numPoints() const { return bounds[0] * bounds[1] * bounds[2]; }
    // True when `size` differs from the requested value: q3map2 then writes the adjusted value back
    // to worldspawn "gridsize" (the engine reads the grid size from there).
    bool sizeChanged() const { return !(size == requestedSize); }
    // "%.0f %.0f %.0f" of `size`, the value written back.
    std::string sizeKeyValue() const;

    // Point index = x + y*bx + z*bx*by.
    std::array<int, 3> pointCoords(int index) const;
    Vec3 pointOrigin(int index) const;
};

// q3map2 SetupGrid: floor each axis (min 8), mins = g*ceil(worldMins/g), maxs = g*floor(worldMaxs/g),
// bounds = (maxs-mins)/g + 1 (float arithmetic as the engine does it), growing while the point count
// exceeds kMaxGridPoints. World coordinates are clamped to +-2^20 (no engine goes near that).
GridLayout computeGridLayout(Vec3 requestedSize, Vec3 worldMins, Vec3 worldMaxs);
// Same from BSP model 0 (the world).
GridLayout computeGridLayout(Vec3 requestedSize, const bsp::Bsp& bsp);

// Grid options of the -light command line and worldspawn.
struct GridOptions {
    float scale = 1.0f;                  // -gridscale
    float ambientScale = 1.0f;           // -gridambientscale
    float directionality = 1.0f;         // -griddirectionality (<= 1)
    float ambientDirectionality = 0.0f;  // -gridambientdirectionality (>= -1)
    Vec3 minLight{0, 0, 0};              // worldspawn _mingridlight (or _minlight) x _color
};

// Style-0 light of one grid point in float units, before the byte conversion.
struct GridSample {
    Vec3 ambient;
    Vec3 directed;
    Vec3 direction;  // unit vector towards the dominant light (zero when nothing reached the point)
};

// q3map2 TraceGrid's split: the primary direction is the normalised sum of each contribution's
// direction weighted by |colour| (all styles); each contribution goes to `directed` with weight
// d = max(0, gAD + cos*(gD - gAD)) and to `ambient` with 0.25*(1-d). `baseAmbient` is the worldspawn
// ambient the point starts with. Styles: the first four distinct styles (style 0 first) get slots,
// contributions of further styles fall back to style 0; only style 0 is returned (IBSP stores one).
GridSample accumulateGridSample(std::span<const LightContribution> contributions, Vec3 baseAmbient,
                                const GridOptions& options);

// Bytes of one lump-15 point: ambient = max(ambient, minLight) through ColorToBytes with
// scale*ambientScale, directed with scale, ambient forced to (1,1,1) when it is zero but directed is
// not (the engines skip zero-ambient points), direction as NormalToLatLong.
bsp::GridPoint encodeGridPoint(const GridSample& sample, const GridOptions& options, const ColorOptions& color);

// q3map2 / id NormalToLatLong: byte[0] = acos(z) in 255/360 steps, byte[1] = atan2(y, x) in 255/360
// steps (both truncated and masked to 8 bits); straight up is (0,0), straight down (128,0).
std::array<uint8_t, 2> normalToLatLong(Vec3 normal);
// The engine decode (ioquake3 R_SetupEntityLightingGrid): lng = byte[0], lat = byte[1], 256 steps
// per turn, n = (cos lat sin lng, sin lat sin lng, cos lng).
Vec3 latLongToNormal(std::array<uint8_t, 2> bytes);

}  // namespace q3::light
