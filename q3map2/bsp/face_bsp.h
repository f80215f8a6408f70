// Building the tree from brush faces (q3map2 facebsp.cpp): forced axial splits on block-size
// boundaries first, then the face plane with the best score (5 per coplanar face, -5 per face it
// cuts, +5 if axial, plus the face priority: hint +1000, antiportal/areaportal -1000, detail -3000).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "bsp_brushes.h"
#include "bsp_tree.h"
#include "plane_set.h"
#include "winding.h"

namespace q3::bspstage {

struct BspFace {
    Winding winding;
    int planeNum = -1;  // even plane of the pair
    int priority = 0;
    uint32_t compileFlags = 0;
};

inline constexpr int kHintPriority = 1000;
inline constexpr int kAntiportalPriority = -1000;
inline constexpr int kAreaportalPriority = -1000;
inline constexpr int kDetailPriority = -3000;

// 1024 on every axis unless worldspawn _blocksize/blocksize/chopsize says otherwise (one or
// three numbers; 0 or less turns an axis off).
using BlockSize = std::array<double, 3>;
inline constexpr BlockSize kDefaultBlockSize = {1024, 1024, 1024};

// Faces from every side winding of the structural brushes (also detail ones with `deep`), skip
// faces left out. In q3map2's list order (the reverse of brush and side order), which decides ties.
// A structural brush with fewer than four windings is malformed: it becomes detail here, as in
// q3map2, and takes no part in the structure.
std::vector<BspFace> makeStructuralFaceList(std::vector<Brush>& brushes, bool deep);
// The same from the sides' visible hulls (after clipSidesIntoTree).
std::vector<BspFace> makeVisibleFaceList(const std::vector<Brush>& brushes, bool deep);

struct FaceBspCounts {
    int faces = 0;
    int leafs = 0;
};

// The tree from the faces. Block splits may add planes to `planes`. `alternateSplit` (-altsplit)
// scores instead 20000 - |front - back| - times the plane was used - coplanar faces - 5 per face
// cut + 10 x the face's area, plus the priority.
Tree buildFaceTree(std::vector<BspFace> faces, PlaneSet& planes, const BlockSize& blockSize, bool alternateSplit = false,
                   FaceBspCounts* counts = nullptr);

}  // namespace q3::bspstage
