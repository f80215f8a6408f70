// The first step of -bsp: the .map's entities turned into brushes on the map's plane set, with
// content and compile flags from their shaders, windings, and bevels; func_group brushes merged
// into the world, origin brushes folded into their entity's origin.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "dvec3.h"
#include "map_file.h"
#include "plane_set.h"
#include "shader_flag_rules.h"
#include "winding.h"

namespace q3 {
class FeedbackStream;
class Log;
class ShaderTable;
struct ShaderInfo;
}  // namespace q3

namespace q3::bspstage {

struct BrushSide {
    int planeNum = -1;
    DPlane exactPlane;                  // from the three points, unsnapped; zero normal for bevels
    const ShaderInfo* shader = nullptr; // nullptr for bevels
    uint32_t contentFlags = 0;
    uint32_t surfaceFlags = 0;
    uint32_t compileFlags = 0;
    bool bevel = false;
    bool culled = false;  // hidden inside another brush or behind a coincident face (cullSides)
    const map::BrushFace* face = nullptr;  // the .map face (texture projection); nullptr for bevels
    Winding winding;      // empty for bevels and sides clipped away
    Winding visibleHull;  // the part of the winding in open leaves (set by clipSidesIntoTree)
};

struct Brush {
    std::vector<BrushSide> sides;  // after bevelling: sides 0-5 axial (-X +X -Y +Y -Z +Z)
    int mapEntityNum = 0;          // entity index in the .map file
    int brushNum = 0;              // primitive index within that entity, for messages
    uint32_t contentFlags = 0;     // OR over the sides
    uint32_t compileFlags = 0;
    const ShaderInfo* contentShader = nullptr;
    bool detail = false;
    bool opaque = false;
    DBounds bounds;
};

// A patch and the .map entity it was written in (func_group patches join the world).
struct PatchRef {
    const map::MapPatch* patch = nullptr;
    int mapEntityNum = 0;
};

struct BspEntity {
    const map::MapEntity* source = nullptr;
    int mapEntityNum = 0;
    std::string classname;
    // q3map2's order: opaque brushes first (latest first), then translucent ones in file order.
    std::vector<Brush> brushes;
    // Patches (parsed, not yet tessellated), func_group ones moved here; none with -nocurves. In
    // q3map2's order: each entity's latest first, func_groups' ahead of the world's.
    std::vector<PatchRef> patches;
    DVec3 origin;  // "origin" key (0 0 0 when absent), moved by an origin brush
    bool hasOriginBrush = false;
    DVec3 originBrushCenter;  // brushes were moved by minus this; textures stay where the map put them
    std::string model;  // the "model" key it is written with ("*3"), empty for none (numberModels)

    // Point entities start the flood that finds the map's inside.
    bool isPointEntity() const;
};

// A _decal entity (q3map2 ProcessDecals): its patches are decal projectors, not geometry, so they
// leave the entity (which then makes no model) once the entity its "target" names is found.
struct DecalEntity {
    int mapEntityNum = 0;
    DVec3 origin;                   // the decal entity's "origin" key
    DVec3 target;                   // the origin of the entity its "target" names
    DBounds bounds;                 // of all the entity's brushes and patch control points
    std::vector<PatchRef> patches;  // in the entity's list order (latest first)
};

struct MapLoadOptions {
    PlaneEpsilons epsilons;
    bool noDetail = false;    // -nodetail
    bool fullDetail = false;  // -fulldetail
    bool noWater = false;     // -nowater
    bool noHint = false;      // -nohint
    bool noCurves = false;    // -nocurves
    ShaderFlagRules flagRules;  // -noob, -globalflag
    int bevelSnap = 0;          // -snap
    // -autocaulk (q3map2's noCollapseGroups): func_groups stay entities of their own, so that the
    // world's brush numbers are the editor's, and brushes get no bevels.
    bool keepGroups = false;
    bool resolveClones = true;  // off for -onlyents, which numbers clones like other models
    bool decals = true;         // off for -onlyents: only a full -bsp turns _decal patches into projectors
    FeedbackStream* feedback = nullptr;  // -connect: problem brushes go to the editor as selections
};

struct MapLoadCounts {
    int worldBrushes = 0;
    int detailBrushes = 0;
    int patches = 0;
    int boxBevels = 0;
    int edgeBevels = 0;
    int areaportals = 0;
};

struct LoadedMap {
    PlaneSet planes;
    std::vector<BspEntity> entities;  // worldspawn first; func_group and group_info removed
    MapLoadCounts counts;
    DBounds worldBounds;              // of the world brushes
    // Shaders without a script are named as the map first spelled them (q3map2 keeps that
    // spelling; the shader table keys them in lower case).
    std::map<const ShaderInfo*, std::string> implicitShaderNames;
    ShaderFlagRules flagRules;
    std::vector<DecalEntity> decals;  // _decal entities with a target, their patches moved here

    // The name a shader is written under.
    const std::string& shaderName(const ShaderInfo& shader) const;
};

LoadedMap loadMapForBsp(const map::MapFile& map, const ShaderTable& shaders, const MapLoadOptions& options, Log& log);

// Windings for every side (clipped by every other non-bevel side, welded) and the brush bounds.
// False when the brush encloses no volume or leaves the world (+-65536).
bool createBrushWindings(Brush& brush, const PlaneSet& planes);
// Sets the brush's content/compile flags, content shader, detail and opaque from its sides.
void setBrushContents(Brush& brush, bool fullDetail, Log& log);
// Puts the six axial planes first (adding bevel sides where missing), then adds edge bevels.
// Returns the number of (box, edge) bevels added. bevelSnap > 0 (-snap) moves added axial bevels
// inwards to multiples of it.
std::pair<int, int> addBrushBevels(Brush& brush, PlaneSet& planes, int bevelSnap = 0);

// "x y z" as q3map2 reads vectors from keys (missing numbers are 0).
DVec3 parseVectorKey(const std::string& text);

}  // namespace q3::bspstage
