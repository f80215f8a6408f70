#include "structure_emit.h"

#include "bsp_builder.h"
#include "brush_filter.h"

namespace q3::bspstage {

Tree singleLeafTree(const BspEntity& entity) {
    Tree tree;
    TreeNode leaf;
    leaf.cluster = 0;
    leaf.area = 0;
    // Leaf lists come out latest first: listing the brushes backwards keeps the entity's order.
    for (size_t i = entity.brushes.size(); i-- > 0;) leaf.brushes.push_back(int(i));
    tree.nodes.push_back(std::move(leaf));
    tree.head = 0;
    return tree;
}

bsp::Bsp emitStructure(LoadedMap& map, WorldStructure& world, const ShaderTable& shaders,
                       const EntityLumpOptions& entityOptions) {
    BspBuilder builder(map, shaders);
    for (size_t i = 0; i < map.entities.size(); ++i) {
        BspEntity& e = map.entities[i];
        if (e.brushes.empty() && e.patches.empty()) continue;
        builder.beginModel(e);
        builder.emitBrushes(e.brushes);
        if (i == 0) {
            filterDetailBrushesIntoTree(e.brushes, world.tree, map.planes);
            builder.endModel(world.tree);
        } else {
            builder.endModel(singleLeafTree(e));
        }
    }
    builder.emitPlanes(map.planes);
    builder.bsp().entities = bsp::unparseEntities(bspEntities(map, entityOptions));
    return std::move(builder.bsp());
}

}  // namespace q3::bspstage
