// q3map2's passages (CreatePassages): for a portal P and each portal T of the cluster P leads into,
// what can be seen through the pair, found with the separating planes between P and T. Kept as
// clusters (T's own, and the one each portal seen through the pair leads into), the unit the flow
// works in. The default full vis intersects its "might see" sets with them, which prunes early.
#pragma once

#include "base_vis.h"
#include "portal_bits.h"
#include "vis_graph.h"

#include <functional>
#include <vector>

namespace q3::vis {

struct Passages {
    // Row of the passage from portal p through the k-th portal of its destination cluster's list.
    std::vector<size_t> firstRow;  // per portal
    BitMatrix canSee;              // one row of cluster bits per passage

    const uint64_t* row(int portal, size_t k) const { return canSee.row(firstRow[static_cast<size_t>(portal)] + k); }
};

Passages createPassages(const VisGraph& graph, const BaseVis& base, const std::function<void()>& advance = {});

}  // namespace q3::vis
