// The full vis (q3map2's PortalFlow / PassagePortalFlow / PassageFlow): for each portal, a
// recursive walk through the clusters beyond it that keeps a source winding (what is left of the
// portal) and a pass winding (what is left of the last portal walked through), clips every next
// portal by the separating planes between them, and marks the cluster behind each portal where
// something survives.
//
// The walk's "might see" sets hold clusters rather than portals (as ericw-tools' vis does): a
// branch stops as soon as every cluster it could still reach is marked already, which prunes far
// more than q3map2's portal sets while marking the same clusters.
//
// Two more cuts, both exact-conservative: at each step the clusters not yet marked whose portals
// lie wholly behind one of the separators (or behind the portal just passed or the base portal)
// leave the "might see" set, since no line of the chain can reach them however deep it goes
// (flow_beam.h); and a walk only works on the pairs of clusters earlier waves left open
// (cluster_knowledge.h): those known visible are marked from the start, those known hidden are
// not looked for.
//
// Portals are done in waves along the order of their "might see" counts (smallest first); a
// portal's walk prunes with the finished results of earlier waves and with the base flood of the
// rest. The waves depend only on the portal count, so the result is the same at any thread count.
#pragma once

#include "base_vis.h"
#include "passages.h"
#include "portal_bits.h"
#include "vis_graph.h"

#include <functional>

namespace q3::vis {

enum class FlowMode {
    Portal,         // -nopassage: clipping by separators only
    PassagePortal,  // default: clipping, with the passages' sets pruning the walk
    Passage,        // -passageOnly: the passages' sets alone, no clipping
};

struct FlowOptions {
    FlowMode mode = FlowMode::PassagePortal;
    bool sort = true;  // false: -nosort (portal index order)
};

// `passages` is required for the two passage modes. Returns per portal the clusters it sees
// (the one it leads into included), for buildVisibilityLump.
BitMatrix computePortalFlow(const VisGraph& graph, const BaseVis& base, const Passages* passages,
                            const FlowOptions& options, const std::function<void()>& advance = {});

// The wave boundaries over `count` portals in processing order: wave w covers
// [bounds[w], bounds[w + 1]).
std::vector<size_t> flowWaveBounds(size_t count);

}  // namespace q3::vis
