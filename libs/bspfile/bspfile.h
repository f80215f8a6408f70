// Quake 3 IBSP files: typed lumps, reading with validation, and writing.
//
// Supported headers: version 46 with 17 lump entries (id's layout), version 46 with 18 entries (what
// q3map2 writes), version 47 with 18 entries (Quake Live) and 19 entries (lump 18 = SH light grid),
// and version 47 with 17 entries (RTCW/ET maps). The entry count is not stored in the file: it is
// the largest count for which no lump data starts inside the header and every extra entry is a
// range inside the file. Other versions are read with ReadOptions::force.
// A BSPX trailer after the last lump carries extra named lumps.
// All records are little-endian and stored with their on-disk layout, so a lump is a plain array.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace q3::bsp {

constexpr char kIdent[4] = {'I', 'B', 'S', 'P'};
constexpr int32_t kVersionQ3 = 46;
constexpr int32_t kVersionQL = 47;

enum Lump : int {
    LUMP_ENTITIES = 0,
    LUMP_SHADERS = 1,
    LUMP_PLANES = 2,
    LUMP_NODES = 3,
    LUMP_LEAFS = 4,
    LUMP_LEAFSURFACES = 5,
    LUMP_LEAFBRUSHES = 6,
    LUMP_MODELS = 7,
    LUMP_BRUSHES = 8,
    LUMP_BRUSHSIDES = 9,
    LUMP_DRAWVERTS = 10,
    LUMP_DRAWINDEXES = 11,
    LUMP_FOGS = 12,
    LUMP_SURFACES = 13,
    LUMP_LIGHTMAPS = 14,
    LUMP_LIGHTGRID = 15,
    LUMP_VISIBILITY = 16,
    LUMP_ADVERTISEMENTS = 17,  // Quake Live; q3map2 writes this slot (empty) into v46 files too
    LUMP_LIGHTGRID_SH = 18,    // our spherical-harmonics light grid, v47 with 19 entries only
    kMaxLumps = 19
};

// Name of a lump as used in messages ("drawverts", "lightgrid", ...).
std::string_view lumpName(int lump);

struct Shader {
    char name[64];
    int32_t surfaceFlags;
    int32_t contentFlags;
};
struct Plane {
    float normal[3];
    float dist;
};
struct Node {
    int32_t planeNum;
    int32_t children[2];  // negative: -(leaf + 1)
    int32_t mins[3];
    int32_t maxs[3];
};
struct Leaf {
    int32_t cluster;
    int32_t area;
    int32_t mins[3];
    int32_t maxs[3];
    int32_t firstLeafSurface, numLeafSurfaces;
    int32_t firstLeafBrush, numLeafBrushes;
};
struct Model {
    float mins[3];
    float maxs[3];
    int32_t firstSurface, numSurfaces;
    int32_t firstBrush, numBrushes;
};
struct Brush {
    int32_t firstSide, numSides;
    int32_t shaderNum;
};
struct BrushSide {
    int32_t planeNum;
    int32_t shaderNum;
};
struct DrawVert {
    float xyz[3];
    float st[2];
    float lightmap[2];
    float normal[3];
    uint8_t color[4];
};
struct Fog {
    char shader[64];
    int32_t brushNum;
    int32_t visibleSide;
};
enum SurfaceType : int32_t { MST_BAD = 0, MST_PLANAR = 1, MST_PATCH = 2, MST_TRIANGLE_SOUP = 3, MST_FLARE = 4,
                             MST_FOLIAGE = 5 };
constexpr int32_t kLightmapByVertex = -3;  // lightmapNum of a vertex-lit surface
constexpr int32_t kLightmapNone = -1;
struct Surface {
    int32_t shaderNum;
    int32_t fogNum;
    int32_t surfaceType;
    int32_t firstVert, numVerts;
    int32_t firstIndex, numIndexes;
    int32_t lightmapNum;
    int32_t lightmapX, lightmapY;
    int32_t lightmapWidth, lightmapHeight;
    float lightmapOrigin[3];
    float lightmapVecs[3][3];  // s axis, t axis, and the normal of planar surfaces
    int32_t patchWidth, patchHeight;
};
struct GridPoint {
    uint8_t ambient[3];
    uint8_t directed[3];
    uint8_t latLong[2];
};
struct Advertisement {
    int32_t cellId;
    float normal[3];
    float rect[4][3];
    char model[64];
};

static_assert(sizeof(Shader) == 72 && sizeof(Plane) == 16 && sizeof(Node) == 36 && sizeof(Leaf) == 48);
static_assert(sizeof(Model) == 40 && sizeof(Brush) == 12 && sizeof(BrushSide) == 8 && sizeof(DrawVert) == 44);
static_assert(sizeof(Fog) == 72 && sizeof(Surface) == 104 && sizeof(GridPoint) == 8 && sizeof(Advertisement) == 128);

constexpr int kLightmapPageBytes = 128 * 128 * 3;

// An extra lump stored in the BSPX trailer.
struct BspxLump {
    std::string name;  // at most 23 characters
    std::vector<uint8_t> data;
};

// The whole file. Lumps the compiler does not interpret (visibility, lightmaps, lump 17, lump 18)
// are kept as raw bytes so that a read-then-write round trip is byte-exact.
struct Bsp {
    int32_t version = kVersionQ3;
    int headerLumps = 17;  // 17, 18 or 19 entries in the header

    std::string entities;  // lump 0 exactly as stored (normally ends with a NUL)
    std::vector<Shader> shaders;
    std::vector<Plane> planes;
    std::vector<Node> nodes;
    std::vector<Leaf> leafs;
    std::vector<int32_t> leafSurfaces;
    std::vector<int32_t> leafBrushes;
    std::vector<Model> models;
    std::vector<Brush> brushes;
    std::vector<BrushSide> brushSides;
    std::vector<DrawVert> drawVerts;
    std::vector<int32_t> drawIndexes;
    std::vector<Fog> fogs;
    std::vector<Surface> surfaces;
    std::vector<uint8_t> lightmaps;       // lump 14, pages of 128*128 RGB (or external size)
    std::vector<GridPoint> lightGrid;     // lump 15
    std::vector<uint8_t> visibility;      // lump 16: int numClusters, int bytesPerCluster, bits
    std::vector<uint8_t> lump17;          // advertisements (Quake Live) or q3map2's empty slot
    std::vector<uint8_t> shGrid;          // lump 18, see libs/sh/sh_grid_lump.h; empty = none
    std::vector<BspxLump> bspx;           // BSPX trailer lumps, in file order

    const BspxLump* findBspx(std::string_view name) const;
    void setBspx(std::string name, std::vector<uint8_t> data);  // replaces or appends
    bool removeBspx(std::string_view name);
};

// Thrown for every malformed input; the message is one line: "<file>: <lump>: <what is wrong>".
struct BspError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct ReadOptions {
    bool force = false;          // accept unknown versions (q3map2's -force)
    bool validate = true;        // cross-reference and NaN checks after parsing
};

// Parses a whole file image. `name` is used in error messages.
Bsp parseBsp(std::span<const uint8_t> bytes, const std::string& name, const ReadOptions& options = {});
Bsp readBsp(const std::filesystem::path& path, const ReadOptions& options = {});

// Checks cross-references (indices in range) and coordinates (finite). Throws BspError.
// Covered: shader/fog names terminated; planes, vertex positions and normals, model bounds finite;
// node planes and children, leaf surface/brush ranges and their values, model surface/brush
// ranges, brush sides and shaders, fog brushes and visible sides, surface shaders, fogs, types,
// vertex and index ranges, index values within the surface's vertices, whole triangles, patch
// sizes; visibility header against its size and leaf clusters; lump 18 and the BSPX
// "LIGHTGRID_SH" lump through q3::sh::checkGridLump. Tolerated because shipped maps have them:
// NaN texture/lightmap coordinates, and fogNum 0 in maps without fogs.
void validateBsp(const Bsp& bsp, const std::string& name);

// Serialises to the file image: header with bsp.version / bsp.headerLumps entries, lumps 4-byte
// aligned and zero-padded, then the BSPX trailer when bsp.bspx is not empty. Deterministic.
// Throws BspError (naming `name`) when a non-empty lump has no header entry (lump 17 with a
// 17-entry header, lump 18 without 19 entries), a BSPX name is empty or too long, or the file
// would not fit 32-bit offsets.
std::vector<uint8_t> serializeBsp(const Bsp& bsp, const std::string& name = "bsp");
// The bytes of serializeBsp streamed to a temporary file in the same folder, then renamed over
// the target: the file image is never built in memory (maps with a large SH grid stay small).
void writeBsp(const std::filesystem::path& path, const Bsp& bsp);

// Raw byte view of one lump as it would be written (used by -info and by tests comparing payloads).
// Throws BspError for a lump number outside [0, kMaxLumps).
std::vector<uint8_t> lumpBytes(const Bsp& bsp, int lump);
// The same bytes without a copy (valid while `bsp` is unchanged).
std::span<const uint8_t> lumpView(const Bsp& bsp, int lump);

// Size in bytes of one record of a lump, or 0 for lumps kept as raw bytes (entities, lightmaps,
// visibility, lump 17, lump 18).
size_t lumpRecordSize(int lump);

// Puts an SH grid lump image into lump 18 and switches the header to version 47 with 19 entries.
void attachShGrid(Bsp& bsp, std::vector<uint8_t> lumpImage);
// Drops lump 18 (releasing its memory) and returns to a plain version 46 header (17 entries, or
// 18 when lump 17 holds data).
void detachShGrid(Bsp& bsp);

// Entity lump -------------------------------------------------------------------------------------
struct Entity {
    std::vector<std::pair<std::string, std::string>> pairs;  // in file order, duplicates kept

    // First value of a key (case-insensitive, as the engines compare keys), or nullptr.
    const std::string* find(std::string_view key) const;
    std::string value(std::string_view key, std::string_view fallback = {}) const;
    // Replaces the first pair with this key, or appends one.
    void set(std::string_view key, std::string_view value);
    bool erase(std::string_view key);
    std::string_view classname() const;
};

// Parses the entity text ("{ "key" "value" ... }" blocks). Throws BspError naming `name`.
std::vector<Entity> parseEntities(std::string_view text, const std::string& name);
// Writes entities the way q3map2 does ("{\n\"key\" \"value\"\n}\n" per entity) with a final NUL.
// An entity without pairs is written as "{\n}\n", so parse + unparse keeps the entity count.
std::string unparseEntities(const std::vector<Entity>& entities);

// The compiler's name and version, recorded in worldspawn's _q3map2_version.
inline constexpr const char* kCompilerVersion = "q3map2-cpp 0.1.0 (q3map2 2.5.17n compatible)";
// Records a stage run in worldspawn as q3map2's InjectCommandLine does: the stage switch and its
// options appended to earlier stages' with "; " ("-bsp -meta; -vis -fast; -light -fast") in
// _q3map2_cmdline, and _q3map2_version set.
void injectCommandLine(Entity& worldspawn, const std::string& commandLine);

}  // namespace q3::bsp
