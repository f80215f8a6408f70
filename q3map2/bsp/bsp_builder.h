// The BSP file as -bsp fills it, model by model (q3map2 writebsp.cpp, surface.cpp Emit*): shaders
// unique by name and flags in first-use order, brushes and sides, surfaces with their vertices and
// indexes (index runs shared with earlier surfaces), the tree as nodes and leafs (leaf 0 a reserved
// dummy), models, planes.
#pragma once

#include <map>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "bsp_brushes.h"
#include "bsp_tree.h"
#include "bspfile.h"
#include "draw_surface.h"

namespace q3 {
class ShaderTable;
}

namespace q3::bspstage {

struct SurfaceEmitOptions {
    int maxLightmappedVerts = 64;  // -mv: larger surfaces are written as triangle soup
    bool debugInset = false;       // -debuginset: triangle corners pulled 1 unit towards their centre
    bool debugSurfaces = false;    // -debugsurfaces: shader debugsurfaces, vertex colours by surface number
};

class BspBuilder {
public:
    BspBuilder(const LoadedMap& map, const ShaderTable& shaders);

    bsp::Bsp& bsp() { return out_; }

    int shader(const char* name, uint32_t contentFlags, uint32_t surfaceFlags);
    int shader(const ShaderInfo& si);

    // Starts the entity's model: bounds of its brushes and patch control points (of its lightgrid
    // brushes when it has any).
    void beginModel(const BspEntity& entity);
    // Brushes and sides of the current model, in list order.
    void emitBrushes(const std::vector<Brush>& brushes);
    // Writes a surface (faces are triangulated first) and returns its number; the vertices grow
    // the bounds of a brush model.
    // `mapSurfaceNumber`: the surface's place among all draw surfaces made so far (q3map2's
    // mapDrawSurfs index), which picks its -debugsurfaces colour.
    int emitSurface(DrawSurface& ds, const SurfaceEmitOptions& options, int mapSurfaceNumber = 0);
    // Points the current model's brush sides at the shader of the face drawn from them when the
    // names differ (q3map2 FixBrushSides; the back face of a fog side re-points brush side 0).
    void fixBrushSides(const std::vector<DrawSurface>& surfaces);
    // Writes the tree (the world) or its single leaf (a brush model) and closes the model.
    void endModel(const Tree& tree);
    void emitPlanes(const PlaneSet& planes);

    int nextSurface() const { return int(out_.surfaces.size()); }
    // Warnings of the surfaces written since the last call (autosprite2 quads left as they were).
    std::vector<std::string> takeWarnings() { return std::exchange(warnings_, {}); }
    int brushOutput(int brushIndex) const { return firstBrush_ + brushIndex; }

private:
    void leaf(const TreeNode& n);
    void node(const Tree& tree, int index);
    int findIndexRun(const std::vector<int>& indexes);

    bsp::Bsp out_;
    const LoadedMap& map_;
    const ShaderTable& shaders_;
    int firstBrush_ = 0;
    // Start positions in drawIndexes of every three-index run, for the run search.
    std::map<std::array<int, 3>, std::vector<int>> indexRuns_;
    // The entry each shader was given: entries are only appended, so the first match stays first.
    std::unordered_map<const ShaderInfo*, int> shaderEntries_;
    size_t indexedUpTo_ = 0;
    std::vector<std::string> warnings_;
};

}  // namespace q3::bspstage
