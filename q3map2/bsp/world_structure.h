// The world model's structure, in q3map2's order (bsp.cpp ProcessWorldModel): a tree from the
// structural brush faces, portals, brushes filtered in, flood from the entities (leak line on a
// leak), then — unless nothing stands in open space — outside filled, visible hulls, a second tree
// from the visible hulls only, flood and fill again; then clusters, the portal file (only when
// sealed) and areas.
#pragma once

#include <filesystem>
#include <string>

#include "bsp_brushes.h"
#include "bsp_tree.h"
#include "face_bsp.h"
#include "portal_file.h"
#include "tree_flood.h"
#include "tree_portals.h"

namespace q3 {
class FeedbackStream;
class Log;
}

namespace q3::bspstage {

struct WorldStructureOptions {
    bool deep = false;      // -deep: detail faces split the tree too (at low priority)
    bool leakTest = false;  // -leaktest: stop right after a leak is found
    bool alternateSplit = false;  // -altsplit: q3map2's alternative split plane score
    FeedbackStream* feedback = nullptr;  // -connect: the leak line and the leaking entity go to the editor
};

struct TreePassCounts {
    FaceBspCounts faceBsp;
    PortalCounts portals;
    int structuralReferences = 0;
    FloodCounts flood;
    FillCounts fill;
};

struct WorldStructure {
    Tree tree;  // the final tree
    BlockSize blockSize = kDefaultBlockSize;
    FloodResult flood = FloodResult::Empty;  // of the first tree, after _ignoreleaks
    bool leaked = false;                     // anything but Good: no portal file
    bool stoppedForLeakTest = false;
    std::string leakLine;    // .lin text; empty when the outside was not reached
    int leakingEntity = -1;  // entity index at the end of the leak line
    std::string portalFile;  // .prt text; empty when leaked
    ClusterCounts clusters;
    int areas = 0;
    TreePassCounts first, second;
};

// Worldspawn _blocksize / blocksize / chopsize: one or three numbers.
BlockSize blockSizeForWorld(const map::MapEntity& worldspawn);

// Runs the steps on the world entity of `map` (its sides get visible hulls; planes may be added).
WorldStructure buildWorldStructure(LoadedMap& map, const WorldStructureOptions& options, Log& log);

// Writes <map>.prt (sealed) or <map>.lin (leaked) beside `mapPath` after deleting old ones, as
// q3map2 does.
void writeWorldStructureFiles(const WorldStructure& world, const std::filesystem::path& mapPath);

}  // namespace q3::bspstage
