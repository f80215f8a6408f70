// Every option of the -light stage: q3map2's (defaults of its quake3 profile) and the SH grid
// options of docs/../specs/sh-grid.md. lightOptionTable() binds each to its field and says whether
// this build implements it; the parser refuses the others.
#pragma once

#include "option_table.h"

#include <string>

namespace q3::light {

struct LightOptions {
    // Scaling of light sources.
    float pointScale = 7500;        // -point/-pointscale set point and spot; -spherical point only
    float spotScale = 7500;         // -spot/-spotscale
    float areaScale = 0.25f;        // -area/-areascale
    float skyScale = 1;             // -sky/-skyscale
    float vertexScale = 1;          // -vertexscale
    float backsplashFractionScale = 1;  // -backsplash scale distance
    float backsplashDistance = 23;      //   (a distance < -900 keeps this one)
    float extraDist = 0;            // -extradist

    // Radiosity.
    int bounce = 0;
    float bounceScale = 0.25f;
    float bounceColorRatio = 1;
    bool bounceOnly = false;
    bool bounceGrid = false;        // also bounce into the legacy and SH grids
    bool noBounceStore = false;
    bool fastBounce = false;
    bool dump = false;

    // Quality and sampling.
    int superSample = 1;            // -super/-supersample
    int lightSamples = 1;           // -samples N
    bool lightSamplesInsist = false;  // -samples +N: keep N even with -randomsamples
    bool randomSamples = false;
    int samplesSearchBoxSize = 1;
    bool filter = false;
    bool dark = false;
    float subdivideThreshold = 1;   // -thresh
    int approximateTolerance = 0;   // -approx
    bool shade = false;             // -shade / -shadeangle
    float shadeAngle = 0;
    bool triangleCheck = false;
    bool extraVisNudge = false;
    bool fastPoint = true;          // -nofastpoint clears
    bool fast = false;
    bool faster = false;            // implies fast
    bool fastGrid = false;
    bool cheap = false;
    bool cheapGrid = false;
    bool noTrace = false;
    bool noSurf = false;
    bool patchShadows = false;
    bool oneSky = false;
    bool sunOnly = false;
    bool loMem = false;

    // Lightmap size and storage.
    int sampleSize = 16;
    int minSampleSize = 0;
    int sampleScale = 0;            // 0 = not set
    int lightmapWidth = 128;        // -lightmapsize N [N]
    int lightmapHeight = 128;
    int extLmHackWidth = 0;         // -extlmhacksize N [N]; 0 = off
    int extLmHackHeight = 0;
    bool externalLightmaps = false;
    std::string lightmapDir;        // -lightmapdir, empty = maps/<map>/
    int rawLightmapSizeLimit = 0;
    bool noCollapse = false;
    bool noLightmapSearch = false;
    int lightmapSearchPower = 0;
    int lightmapSearchBlockSize = 0;
    bool slowAllocate = false;
    bool fill = false;
    bool fillPink = false;
    bool noLightmaps = false;       // -nolm
    bool noVertexLight = false;     // -novertex
    float vertexLightValue = -1;    // -novertex F: constant vertex light 0..1; -1 = none
    bool noGrid = false;
    bool exportLightmaps = false;
    std::string lightmapAtlas;      // -lightmapatlas FILE.png: packed pages as one picture; empty = off
    bool triSoup = false;

    // Deluxe maps.
    bool deluxe = false;
    int deluxeMode = 0;
    bool debugDeluxe = false;

    // Dirt and floodlight.
    bool dirty = false;
    int dirtMode = 0;
    float dirtDepth = 128;
    float dirtScale = 1;
    float dirtGain = 1;
    bool dirtDebug = false;
    bool floodlight = false;
    bool lowQuality = false;

    // Legacy grid.
    float gridScale = 1;
    float gridAmbientScale = 1;
    float gridDirectionality = 1;
    float gridAmbientDirectionality = 0;

    // Colour pipeline.
    float gamma = 1;
    float exposure = 0;
    float compensate = 1;
    float brightness = 1;
    float contrast = 0;
    float saturation = 1;
    bool lightmapsRGB = false;
    bool texturesRGB = false;
    bool colorsRGB = false;
    bool lightAngleHL = false;
    bool wolfLight = false;         // -wolf: linear default falloff; -q3 clears
    bool noStyles = false;

    // Misc and debugging.
    bool cpma = false;
    bool custInfoParms = false;
    bool debugBorder = false;
    bool debug = false;
    bool debugSurfaces = false;
    bool debugAxis = false;
    bool debugCluster = false;
    bool debugOrigin = false;
    bool debugNormals = false;
    bool normalmap = false;
    bool debugSampleSize = false;

    // SH light grid.
    bool sh = false;
    bool shBspx = false;            // store it as the BSPX lump LIGHTGRID_SH of a v46 file
    float gridScaleSH = 2;          // SH cell = legacy cell / this, per axis
    float gridSizeSH[3] = {0, 0, 0};  // -gridsh X Y Z; all 0 = derived from gridScaleSH
    bool shGather = false;          // -shgather: add gathered indirect light to the SH grid
    int shGatherSamples = 64;       // -shgathersamples: rays per probe (docs/sh-for-mappers.md)
    int shGatherStep = 2;           // -shgatherstep: probes that gather, every Nth per axis
    bool shExact = false;           // -shexact: every probe lights every light itself (no block sharing)

    // -worldlights: the BSPX lump WORLDLIGHTS (docs/world-lights-format.md).
    bool worldLights = false;
    // -shnoworldlights: the SH grid leaves out the direct light of the lights WORLDLIGHTS lists.
    bool shNoWorldLights = false;
};

const cli::OptionTable<LightOptions>& lightOptionTable();

}  // namespace q3::light
