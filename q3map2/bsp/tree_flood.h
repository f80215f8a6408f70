// Finding the inside of the map (q3map2 portals.cpp, leakfile.cpp): point entities flood the
// leaves they can reach through portals; reaching the outside node is a leak, shown by a line file
// from the void back to the entity; unreached leaves are filled; open leaves are grouped in areas
// that areaportals separate.
#pragma once

#include <string>
#include <vector>

#include "bsp_brushes.h"
#include "bsp_tree.h"
#include "plane_set.h"

namespace q3 {
class Log;
}

namespace q3::bspstage {

enum class FloodResult {
    Empty,   // no point entity stands in an open leaf
    Leaked,  // the outside was reached
    Good,
};

struct FloodCounts {
    int floodedLeafs = 0;
};

// Floods from every point entity (entity index >= 1) placed 1 unit above its origin. Entities in
// opaque leaves get the warning "Entity N (classname): Entity in solid".
FloodResult floodEntities(Tree& tree, const std::vector<BspEntity>& entities, const PlaneSet& planes, Log& log,
                          FloodCounts* counts = nullptr);

struct FillCounts {
    int solid = 0;   // already opaque and unreached
    int filled = 0;  // open but unreached: now opaque
    int inside = 0;  // reached
};
FillCounts fillOutside(Tree& tree);

// The leak line: from the outside node, step by step to the neighbour closest to an entity,
// printing each portal's centre, then the entity's origin ("%f %f %f" lines). Empty when the
// outside was not reached. `leakingEntity` gets the entity index at the end of the line.
std::string leakLineText(const Tree& tree, const std::vector<BspEntity>& entities, int* leakingEntity = nullptr);

// Area numbers for open leaves (needs clusters: leaves with cluster -1 get none); every open leaf
// of the last area holding a _skybox leaf becomes a _skybox leaf too. Returns the number of areas.
int floodAreas(Tree& tree);

}  // namespace q3::bspstage
