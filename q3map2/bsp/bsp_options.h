// The -bsp command line (q3map2 bsp.cpp BSPMain, help.cpp HelpBsp): every q3map2 option, either
// implemented or refused by name with a one-line message.
#pragma once

#include <string>

#include "option_table.h"
#include "shader_flag_rules.h"

namespace q3::bspstage {

struct BspOptions {
    bool onlyEnts = false;       // -onlyents: replace only the entity lump of the existing BSP
    std::string tempName;        // -tempname: read the map from this file, deleted afterwards
    bool noWater = false;        // -nowater
    bool keepLights = false;     // -keeplights
    bool keepModels = false;     // -keepmodels
    bool noDetail = false;       // -nodetail
    bool fullDetail = false;     // -fulldetail
    bool noFog = false;          // -nofog
    bool noSubdivide = false;    // -nosubdivide
    bool leakTest = false;       // -leaktest
    bool verboseEntities = false;  // -verboseentities
    bool noCurves = false;       // -nocurves
    bool noTJunc = false;        // -notjunc
    int sampleSize = 16;         // -samplesize (at least 1)
    int minSampleSize = 0;       // -minsamplesize (at least 1 when given)
    float normalEpsilon = 0.00005f;  // -ne
    float distanceEpsilon = 0.005f;  // -de
    int maxLightmappedVerts = 64;    // -mv (at least 3)
    int maxIndexes = 6000;           // -mi (at least 3)
    bool meta = false;               // -meta
    bool patchMeta = false;          // -patchmeta
    float npDegrees = 0;             // -np: meta shade angle (at least 0)
    int metaAdequateScore = -1;      // -metaadequatescore (negative: built in)
    int metaGoodScore = -1;          // -metagoodscore (negative: built in)
    float metaMaxBBoxDistance = -1;  // -metamaxbboxdistance (negative: off)
    std::string celShader;           // -celshader, with textures/ in front
    bool noBrushSnap = false;    // -nobrushsnap
    bool noHint = false;         // -nohint
    bool flares = false;         // -flares / -noflares (quake3's default: off)
    bool alternateSplit = false;  // -altsplit
    bool deep = false;           // -deep
    bool maxArea = false;        // -maxarea
    int bevelSnap = 0;           // -snap (negative: off)
    bool fakeMap = false;        // -fakemap: write fakemap.map with the world brushes
    bool skyFix = false;         // -skyfix
    bool renameModelShaders = false;  // -rename
    bool autocaulk = false;      // -autocaulk
    bool debugPortals = false;   // -debugportals
    bool debugInset = false;     // -debuginset
    bool debugSurfaces = false;  // -debugsurfaces
    bool debugClip = false;      // -debugclip
    float clipDepth = 2;         // -clipdepth
    ShaderFlagRules flagRules;   // -noob, -globalflag
};

const cli::OptionTable<BspOptions>& bspOptionTable();

}  // namespace q3::bspstage
