// Malformed files: each is built by mutating a valid synthetic BSP (as a struct before writing, or
// as bytes after) and must fail with one BspError naming the file, the lump and the problem.
#include "synthetic_bsp.h"

#include "sh_grid_lump.h"
#include "../sh/world_lights_samples.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <random>

namespace q3::bsp::test {
namespace {

constexpr const char* kName = "maps/broken.bsp";
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

void expectError(const std::vector<uint8_t>& image, const std::string& fragment, const ReadOptions& options = {}) {
    try {
        (void)parseBsp(image, kName, options);
        ADD_FAILURE() << "no error; expected one containing \"" << fragment << "\"";
    } catch (const BspError& e) {
        const std::string message = e.what();
        EXPECT_EQ(message.rfind(std::string(kName) + ": ", 0), 0u) << message;
        EXPECT_NE(message.find(fragment), std::string::npos) << "message: " << message << "\nexpected: " << fragment;
        EXPECT_EQ(message.find('\n'), std::string::npos) << "message must be one line: " << message;
    }
}

// Mutates the struct, writes it (the writer does not validate) and expects the reader to refuse it.
void expectStructError(const std::function<void(Bsp&)>& mutate, const std::string& fragment) {
    Bsp bsp = makeSyntheticBsp();
    mutate(bsp);
    expectError(serializeBsp(bsp), fragment);
}

std::vector<uint8_t> validImage() { return serializeBsp(makeSyntheticBsp()); }

TEST(BspBadInput, ValidSyntheticBspIsAccepted) {
    Bsp bsp = parseBsp(validImage(), kName);
    EXPECT_NO_THROW(validateBsp(bsp, kName));
}

// Header ---------------------------------------------------------------------------------------------

TEST(BspBadInput, TinyFile) { expectError({'I', 'B', 'S'}, "header: truncated: file is 3 bytes"); }

TEST(BspBadInput, TruncatedHeader) {
    std::vector<uint8_t> image = validImage();
    image.resize(100);
    expectError(image, "header: truncated: file is 100 bytes, a version 46 header needs 144");
}

TEST(BspBadInput, TruncatedVersion47Header) {
    Bsp bsp = makeSyntheticBsp();
    bsp.version = kVersionQL;
    bsp.headerLumps = 18;
    std::vector<uint8_t> image = serializeBsp(bsp);
    image.resize(140);
    expectError(image, "header: truncated: file is 140 bytes, a version 47 header needs 144");
}

TEST(BspBadInput, WrongIdent) {
    std::vector<uint8_t> image = validImage();
    std::memcpy(image.data(), "VBSP", 4);
    expectError(image, "header: not an IBSP file (ident \"VBSP\")");
}

TEST(BspBadInput, BinaryIdentIsPrintable) {
    std::vector<uint8_t> image = validImage();
    image[0] = 0x00;
    image[1] = 0xff;
    expectError(image, "ident \"\\x00\\xffSP\"");
}

TEST(BspBadInput, WrongVersion) {
    std::vector<uint8_t> image = validImage();
    storeI32(image, 4, 38);
    expectError(image, "header: unsupported version 38 (expected 46 or 47");
    ReadOptions force;
    force.force = true;
    EXPECT_NO_THROW(parseBsp(image, kName, force));
}

TEST(BspBadInput, LumpOffsetPastTheEnd) {
    std::vector<uint8_t> image = validImage();
    setRawEntry(image, LUMP_PLANES, static_cast<int32_t>(image.size()) + 64, 16);
    expectError(image, "planes: offset " + std::to_string(image.size() + 64) + " + length 16 extends past the end");
}

TEST(BspBadInput, TruncatedLump) {
    std::vector<uint8_t> image = validImage();
    const std::vector<RawEntry> entries = rawEntries(image, 17);
    // Cut the file in the middle of the lump that ends last.
    int last = 0;
    for (int i = 0; i < 17; ++i)
        if (entries[i].offset + entries[i].length > entries[last].offset + entries[last].length) last = i;
    image.resize(static_cast<size_t>(entries[last].offset + entries[last].length / 2));
    expectError(image, std::string(lumpName(last)) + ": offset");
}

TEST(BspBadInput, HugeLengthDoesNotOverflow) {
    std::vector<uint8_t> image = validImage();
    setRawEntry(image, LUMP_DRAWVERTS, 0x7ffffff0, 0x7ffffff0);
    expectError(image, "drawverts: offset 2147483632 + length 2147483632 extends past the end");
}

TEST(BspBadInput, NegativeLength) {
    std::vector<uint8_t> image = validImage();
    setRawEntry(image, LUMP_SURFACES, 144, -104);
    expectError(image, "surfaces: negative length -104");
}

TEST(BspBadInput, NegativeOffset) {
    std::vector<uint8_t> image = validImage();
    setRawEntry(image, LUMP_NODES, -36, 36);
    expectError(image, "nodes: negative offset -36");
}

TEST(BspBadInput, LumpInsideTheHeader) {
    std::vector<uint8_t> image = validImage();
    setRawEntry(image, LUMP_SHADERS, 8, 72);
    expectError(image, "shaders: data at offset 8 overlaps the 144-byte header");
}

TEST(BspBadInput, LengthNotAMultipleOfTheRecordSize) {
    std::vector<uint8_t> image = validImage();
    const RawEntry planes = rawEntries(image, 17)[LUMP_PLANES];
    setRawEntry(image, LUMP_PLANES, planes.offset, planes.length - 4);
    expectError(image, "planes: length 92 is not a multiple of the record size 16");
}

TEST(BspBadInput, SurfaceLumpNotAMultiple) {
    std::vector<uint8_t> image = validImage();
    const RawEntry surfaces = rawEntries(image, 17)[LUMP_SURFACES];
    setRawEntry(image, LUMP_SURFACES, surfaces.offset, 100);
    expectError(image, "surfaces: length 100 is not a multiple of the record size 104");
}

// Cross-references -------------------------------------------------------------------------------------

TEST(BspBadInput, SurfaceVertsOutOfRange) {
    expectStructError([](Bsp& b) { b.surfaces[1].numVerts = 10; },
                      "surfaces: record 1: vertex range [4, +10) is outside the 13 drawverts");
}

TEST(BspBadInput, SurfaceNegativeFirstVert) {
    expectStructError([](Bsp& b) { b.surfaces[0].firstVert = -1; }, "surfaces: record 0: vertex range [-1, +4)");
}

TEST(BspBadInput, SurfaceIndexesOutOfRange) {
    expectStructError([](Bsp& b) { b.surfaces[0].firstIndex = 3; },
                      "surfaces: record 0: index range [3, +6) is outside the 6 drawindexes");
}

TEST(BspBadInput, IndexValueOutsideTheSurfaceVerts) {
    expectStructError([](Bsp& b) { b.drawIndexes[4] = 4; },
                      "surfaces: record 0: index 4 = 4 is outside the surface's 4 vertices");
}

TEST(BspBadInput, RangeSumOverflowIsCaught) {
    expectStructError([](Bsp& b) { b.surfaces[0].numIndexes = std::numeric_limits<int32_t>::max(); },
                      "surfaces: record 0: index range [0, +2147483647)");
}

TEST(BspBadInput, IncompleteTriangles) {
    expectStructError([](Bsp& b) { b.surfaces[0].numIndexes = 5; }, "surfaces: record 0: 5 indexes do not make whole");
}

TEST(BspBadInput, PatchSizeMismatch) {
    expectStructError([](Bsp& b) { b.surfaces[1].patchWidth = 5; },
                      "surfaces: record 1: patch size 5x3 does not match its 9 vertices");
}

TEST(BspBadInput, UnknownSurfaceType) {
    expectStructError([](Bsp& b) { b.surfaces[0].surfaceType = 9; }, "surfaces: record 0: unknown surfaceType 9");
}

TEST(BspBadInput, SurfaceShaderIndex) {
    expectStructError([](Bsp& b) { b.surfaces[1].shaderNum = 2; },
                      "surfaces: record 1: shaderNum 2 is out of range (2 shaders)");
}

TEST(BspBadInput, SurfaceFogIndex) {
    expectStructError([](Bsp& b) { b.surfaces[0].fogNum = 1; },
                      "surfaces: record 0: fogNum 1 is out of range (1 fogs)");
    expectStructError([](Bsp& b) { b.surfaces[0].fogNum = -2; }, "surfaces: record 0: fogNum -2 is out of range");
}

TEST(BspBadInput, LeafSurfacesRange) {
    expectStructError([](Bsp& b) { b.leafs[0].numLeafSurfaces = 3; },
                      "leafs: record 0: leaf surface range [0, +3) is outside the 2 leafsurfaces");
}

TEST(BspBadInput, LeafBrushesRange) {
    expectStructError([](Bsp& b) { b.leafs[1].firstLeafBrush = 2; },
                      "leafs: record 1: leaf brush range [2, +0) is outside the 1 leafbrushes");
}

TEST(BspBadInput, LeafSurfaceValue) {
    expectStructError([](Bsp& b) { b.leafSurfaces[1] = 7; },
                      "leafsurfaces: record 1: surface 7 is out of range (2 surfaces)");
}

TEST(BspBadInput, LeafBrushValue) {
    expectStructError([](Bsp& b) { b.leafBrushes[0] = -1; }, "leafbrushes: record 0: brush -1 is out of range");
}

TEST(BspBadInput, NodeChildNode) {
    expectStructError([](Bsp& b) { b.nodes[0].children[0] = 1; },
                      "nodes: record 0: child node 1 is out of range (1 nodes)");
}

TEST(BspBadInput, NodeChildLeaf) {
    expectStructError([](Bsp& b) { b.nodes[0].children[1] = -3; },
                      "nodes: record 0: child leaf 2 is out of range (2 leafs)");
}

TEST(BspBadInput, NodePlane) {
    expectStructError([](Bsp& b) { b.nodes[0].planeNum = 6; }, "nodes: record 0: planeNum 6 is out of range (6 planes)");
}

TEST(BspBadInput, ModelSurfaceRange) {
    expectStructError([](Bsp& b) { b.models[0].firstSurface = 1; },
                      "models: record 0: surface range [1, +2) is outside the 2 surfaces");
}

TEST(BspBadInput, ModelBrushRange) {
    expectStructError([](Bsp& b) { b.models[0].numBrushes = -1; }, "models: record 0: brush range [0, +-1)");
}

TEST(BspBadInput, BrushSidesRange) {
    expectStructError([](Bsp& b) { b.brushes[0].numSides = 7; },
                      "brushes: record 0: side range [0, +7) is outside the 6 brushsides");
}

TEST(BspBadInput, BrushShader) {
    expectStructError([](Bsp& b) { b.brushes[0].shaderNum = 5; }, "brushes: record 0: shaderNum 5 is out of range");
}

TEST(BspBadInput, BrushSidePlaneAndShader) {
    expectStructError([](Bsp& b) { b.brushSides[3].planeNum = 60; },
                      "brushsides: record 3: planeNum 60 is out of range (6 planes)");
    expectStructError([](Bsp& b) { b.brushSides[5].shaderNum = -1; },
                      "brushsides: record 5: shaderNum -1 is out of range");
}

TEST(BspBadInput, FogBrushAndSide) {
    expectStructError([](Bsp& b) { b.fogs[0].brushNum = 1; }, "fogs: record 0: brushNum 1 is out of range (1 brushes)");
    expectStructError([](Bsp& b) { b.fogs[0].visibleSide = 6; },
                      "fogs: record 0: visibleSide 6 is not -1 or one of the 6 sides");
}

TEST(BspBadInput, UnterminatedNames) {
    expectStructError([](Bsp& b) { std::memset(b.shaders[1].name, 'a', sizeof b.shaders[1].name); },
                      "shaders: record 1: name is not NUL-terminated within 64 bytes");
    expectStructError([](Bsp& b) { std::memset(b.fogs[0].shader, 'f', sizeof b.fogs[0].shader); },
                      "fogs: record 0: shader name is not NUL-terminated");
}

// Coordinates ----------------------------------------------------------------------------------------

TEST(BspBadInput, NaNPlane) {
    expectStructError([](Bsp& b) { b.planes[2].normal[1] = kNaN; }, "planes: record 2: normal is not finite (nan)");
    expectStructError([](Bsp& b) { b.planes[3].dist = -kInf; }, "planes: record 3: dist is not finite (-inf)");
}

TEST(BspBadInput, InfiniteVertex) {
    expectStructError([](Bsp& b) { b.drawVerts[1].xyz[2] = kInf; }, "drawverts: record 1: xyz is not finite (inf)");
    expectStructError([](Bsp& b) { b.drawVerts[7].normal[0] = kNaN; }, "drawverts: record 7: normal is not finite");
}

TEST(BspBadInput, NaNLightmapCoordinatesAreTolerated) {
    Bsp bsp = makeSyntheticBsp();
    bsp.drawVerts[5].lightmap[0] = kNaN;  // shipped maps have these on vertex-lit patches
    EXPECT_NO_THROW(parseBsp(serializeBsp(bsp), kName));
}

TEST(BspBadInput, NaNModelBounds) {
    expectStructError([](Bsp& b) { b.models[0].mins[0] = kNaN; }, "models: record 0: mins is not finite");
    expectStructError([](Bsp& b) { b.models[0].maxs[2] = kInf; }, "models: record 0: maxs is not finite");
}

// Visibility -----------------------------------------------------------------------------------------

TEST(BspBadInput, VisibilityHeaderLargerThanLump) {
    expectStructError([](Bsp& b) { b.visibility[4] = 2; }, "visibility: header claims 1 x 2 bytes but the lump holds 1");
}

TEST(BspBadInput, VisibilityShorterThanItsHeader) {
    expectStructError([](Bsp& b) { b.visibility.resize(5); }, "visibility: 5 bytes is shorter than the 8-byte header");
}

TEST(BspBadInput, VisibilityNegativeHeader) {
    expectStructError([](Bsp& b) { b.visibility[7] = 0x80; }, "visibility: negative header");
}

TEST(BspBadInput, VisibilityRowTooNarrow) {
    expectStructError(
        [](Bsp& b) {
            b.visibility = {9, 0, 0, 0, 1, 0, 0, 0};
            b.visibility.resize(8 + 9, 0);
        },
        "visibility: bytesPerCluster 1 cannot hold 9 clusters");
}

TEST(BspBadInput, VisibilityHugeClaimsDoNotOverflow) {
    expectStructError([](Bsp& b) { b.visibility = {0xff, 0xff, 0xff, 0x7f, 0xff, 0xff, 0xff, 0x7f, 0}; },
                      "visibility: header claims 2147483647 x 2147483647 bytes");
}

TEST(BspBadInput, LeafClusterOutOfRange) {
    expectStructError([](Bsp& b) { b.leafs[1].cluster = 1; }, "leafs: record 1: cluster 1 is out of range (1 clusters)");
}

// BSPX -----------------------------------------------------------------------------------------------

std::vector<uint8_t> imageWithBspx(size_t* trailerAt) {
    Bsp bsp = makeSyntheticBsp();
    bsp.setBspx("FIRST", {1, 2, 3, 4});
    bsp.setBspx("SECOND", {5, 6, 7, 8, 9, 10, 11, 12});
    std::vector<uint8_t> image = serializeBsp(bsp);
    size_t end = 0;
    for (const RawEntry& e : rawEntries(image, 17)) end = std::max(end, static_cast<size_t>(e.offset + e.length));
    *trailerAt = (end + 3) & ~size_t(3);
    return image;
}

TEST(BspBadInput, BspxEntryPastTheEnd) {
    size_t at = 0;
    std::vector<uint8_t> image = imageWithBspx(&at);
    storeU32(image, at + 8 + 32 + 24, static_cast<uint32_t>(image.size()) - 4);  // SECOND's offset
    expectError(image, "bspx: lump \"SECOND\" (offset " + std::to_string(image.size() - 4) +
                           ", length 8) extends past the end of the file");
}

TEST(BspBadInput, BspxLengthWrapsAround) {
    size_t at = 0;
    std::vector<uint8_t> image = imageWithBspx(&at);
    storeU32(image, at + 8 + 28, 0xfffffff0u);  // FIRST's length: offset + length would wrap in 32 bits
    expectError(image, "bspx: lump \"FIRST\"");
}

TEST(BspBadInput, BspxCountAbsurd) {
    size_t at = 0;
    std::vector<uint8_t> image = imageWithBspx(&at);
    storeU32(image, at + 4, 0xffffffffu);
    expectError(image, "bspx: directory claims 4294967295 entries but only");
}

TEST(BspBadInput, BspxTruncatedTrailer) {
    size_t at = 0;
    std::vector<uint8_t> image = imageWithBspx(&at);
    image.resize(at + 6);
    expectError(image, "bspx: trailer header truncated");
}

TEST(BspBadInput, BspxNameNotTerminated) {
    size_t at = 0;
    std::vector<uint8_t> image = imageWithBspx(&at);
    std::memset(image.data() + at + 8, 'Z', 24);
    expectError(image, "bspx: entry 0: name is not NUL-terminated");
}

TEST(BspBadInput, BspxEmptyName) {
    size_t at = 0;
    std::vector<uint8_t> image = imageWithBspx(&at);
    std::memset(image.data() + at + 8 + 32, 0, 24);
    expectError(image, "bspx: entry 1: empty name");
}

TEST(BspBadInput, BspxShGridIsChecked) {
    Bsp bsp = makeSyntheticBsp();
    std::vector<uint8_t> grid = makeShGridLump(2, 1, 1);
    grid.pop_back();
    bsp.setBspx(sh::kBspxLumpName, grid);
    expectError(serializeBsp(bsp), "bspx LIGHTGRID_SH: length");
}

TEST(BspBadInput, BspxWorldLightsAreChecked) {
    Bsp bsp = makeSyntheticBsp();
    std::vector<uint8_t> lights = sh::encodeWorldLights(sh::test::sampleWorldLights());
    bsp.setBspx(sh::kWorldLightsLumpName, lights);
    EXPECT_EQ(parseBsp(serializeBsp(bsp), kName).findBspx(sh::kWorldLightsLumpName)->data, lights);
    std::vector<sh::WorldLight> records = sh::test::sampleWorldLights();
    records[4].cluster = 2;  // the sun
    bsp.setBspx(sh::kWorldLightsLumpName, sh::encodeWorldLights(records));
    expectError(serializeBsp(bsp), ": bspx WORLDLIGHTS: light 4: a sun in cluster 2 (suns have -1)");
}

// Lump 18 --------------------------------------------------------------------------------------------

std::vector<uint8_t> imageWithShGrid(const std::vector<uint8_t>& grid) {
    Bsp bsp = makeSyntheticBsp();
    attachShGrid(bsp, grid);
    return serializeBsp(bsp);
}

TEST(BspBadInput, ShGridWrongLength) {
    std::vector<uint8_t> grid = makeShGridLump(2, 2, 1);
    grid.resize(grid.size() - 108);
    expectError(imageWithShGrid(grid), "lightgrid_sh: length 364 != 40 + 108 * 4");
}

TEST(BspBadInput, ShGridShorterThanHeader) {
    expectError(imageWithShGrid(std::vector<uint8_t>(12, 0)), "lightgrid_sh: 12 bytes is shorter");
}

TEST(BspBadInput, ShGridCountMismatch) {
    std::vector<uint8_t> grid = makeShGridLump(2, 2, 1);
    storeI32(grid, 36, 5);
    expectError(imageWithShGrid(grid), "lightgrid_sh: numPoints 5 != gridBounds product 4");
}

TEST(BspBadInput, ShGridNaN) {
    std::vector<uint8_t> grid = makeShGridLump(2, 1, 1);
    const float nan = kNaN;
    std::memcpy(grid.data() + 40 + 108 + 4 * 5, &nan, 4);
    expectError(imageWithShGrid(grid), "lightgrid_sh: point 1 coefficient 1 channel 2 is not finite");
}

TEST(BspBadInput, ShGridBadBounds) {
    std::vector<uint8_t> grid = makeShGridLump(1, 1, 1);
    storeI32(grid, 28, 0);
    expectError(imageWithShGrid(grid), "lightgrid_sh: gridBounds y = 0 is not positive");
}

// Random corruption ------------------------------------------------------------------------------------

// Whatever bytes are damaged, the outcome is a parsed BSP or one BspError naming the file: never a
// crash, another exception type or a huge allocation. Fixed seed, so the cases are reproducible.
TEST(BspBadInput, RandomCorruptionIsAlwaysAReportedError) {
    Bsp bsp = makeSyntheticBsp();
    attachShGrid(bsp, makeShGridLump(2, 1, 1));
    bsp.setBspx("FOO", {1, 2, 3, 4, 5});
    const std::vector<uint8_t> valid = serializeBsp(bsp);
    std::mt19937 rng(20261121);
    int errors = 0;
    for (int iteration = 0; iteration < 4000; ++iteration) {
        std::vector<uint8_t> image = valid;
        const int damaged = 1 + static_cast<int>(rng() % 4);
        for (int k = 0; k < damaged; ++k) {
            // Half of the damage hits the header, where offsets and counts live.
            const size_t at = (rng() & 1) ? rng() % 160 : rng() % image.size();
            image[at] = static_cast<uint8_t>(rng());
        }
        if (rng() % 8 == 0) image.resize(rng() % image.size());
        try {
            (void)parseBsp(image, kName);
        } catch (const BspError& e) {
            ++errors;
            ASSERT_EQ(std::string(e.what()).rfind(std::string(kName) + ": ", 0), 0u) << e.what();
        }
    }
    EXPECT_GT(errors, 1000);
}

TEST(BspBadInput, RandomEntityTextIsAlwaysAReportedError) {
    const std::string valid = makeSyntheticBsp().entities;
    std::mt19937 rng(7);
    const char alphabet[] = "{}\"/* \nab";
    int errors = 0;
    for (int iteration = 0; iteration < 4000; ++iteration) {
        std::string text = valid;
        for (int k = 0; k < 3; ++k) text[rng() % text.size()] = alphabet[rng() % (sizeof alphabet - 1)];
        try {
            (void)parseEntities(text, kName);
        } catch (const BspError& e) {
            ++errors;
            ASSERT_EQ(std::string(e.what()).rfind(std::string(kName) + ": entities: line ", 0), 0u) << e.what();
        }
    }
    EXPECT_GT(errors, 500);
}

// Writer refusals --------------------------------------------------------------------------------------

TEST(BspWriter, RefusesLumpsWithoutAHeaderEntry) {
    Bsp bsp = makeSyntheticBsp();
    bsp.shGrid = makeShGridLump(1, 1, 1);
    try {
        (void)serializeBsp(bsp, "out.bsp");
        ADD_FAILURE() << "expected an error";
    } catch (const BspError& e) {
        EXPECT_STREQ(e.what(), "out.bsp: lightgrid_sh: 148 bytes but the header has only 17 entries");
    }
    bsp = makeSyntheticBsp();
    bsp.lump17 = {1, 2, 3, 4};
    EXPECT_THROW(serializeBsp(bsp), BspError);
    bsp.headerLumps = 20;
    EXPECT_THROW(serializeBsp(bsp), BspError);
}

TEST(BspWriter, RefusesBadBspxNames) {
    Bsp bsp = makeSyntheticBsp();
    bsp.setBspx(std::string(24, 'L'), {1});
    EXPECT_THROW(serializeBsp(bsp), BspError);
    bsp.bspx = {{"", {1}}};
    EXPECT_THROW(serializeBsp(bsp), BspError);
}

TEST(BspValidate, RejectsInconsistentStructs) {
    Bsp bsp = makeSyntheticBsp();
    bsp.shGrid = makeShGridLump(1, 1, 1);
    EXPECT_THROW(validateBsp(bsp, kName), BspError);
    bsp.headerLumps = 19;
    EXPECT_NO_THROW(validateBsp(bsp, kName));
}

TEST(BspValidate, CanBeSkippedOnRead) {
    Bsp bsp = makeSyntheticBsp();
    bsp.surfaces[0].shaderNum = 99;
    ReadOptions raw;
    raw.validate = false;
    Bsp back = parseBsp(serializeBsp(bsp), kName, raw);
    EXPECT_EQ(back.surfaces[0].shaderNum, 99);
    EXPECT_THROW(validateBsp(back, kName), BspError);
}

}  // namespace
}  // namespace q3::bsp::test
