// Comparing two compiles of one map by what players meet, whatever the tree and surface layout:
// the contents at points (what collision sees) and the drawn area per shader.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "bspfile.h"
#include "vec3.h"

namespace q3::bspstage::test {

// The engines' CM_PointContents on the world model: the OR of the contents of the leaf's brushes
// that hold the point.
int pointContents(const bsp::Bsp& bsp, const Vec3& point);

// Deterministic pseudo-random points inside the world model's bounds.
std::vector<Vec3> randomPoints(const bsp::Bsp& bsp, int count, unsigned seed);

// Drawn area per shader name (case kept as written), over every surface of every model: triangle
// areas for planar and triangle surfaces, the tessellated area for patches; flares count nothing.
std::map<std::string, double> drawnAreaByShader(const bsp::Bsp& bsp);

struct AreaComparison {
    int shaders = 0;          // shaders drawn by either compile
    int within = 0;           // of those, with areas within `tolerance` (relative)
    std::vector<std::string> outside;  // "name: ours vs theirs"
};
AreaComparison compareAreas(const std::map<std::string, double>& ours, const std::map<std::string, double>& theirs,
                            double tolerance);

// Brush by brush (same order), how far the two compiles' side planes are apart: for every plane of
// either brush the nearest plane of the other (largest difference of a normal component or the
// distance), the worst of those over all brushes. Brushes whose content shader or side count
// differ are counted.
struct BrushPlaneComparison {
    int brushes = 0;          // compared (the smaller count)
    int otherShader = 0;      // content shader names differ
    int otherSideCount = 0;   // side counts differ
    double worstPlane = 0;    // over all brushes
};
BrushPlaneComparison compareBrushPlanes(const bsp::Bsp& ours, const bsp::Bsp& theirs);

}  // namespace q3::bspstage::test
