// The full vis (q3map2's PortalFlow / PassagePortalFlow / PassageFlow): for each portal, a
// recursive walk through the clusters beyond it that keeps a source winding (what is left of the
// portal) and a pass winding (what is left of the last portal walked through), clips every next
// portal by the separating planes between them, and marks the portals where something survives.
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

// `passages` is required for the two passage modes. Returns the portal-to-portal visibility.
BitMatrix computePortalFlow(const VisGraph& graph, const BaseVis& base, const Passages* passages,
                            const FlowOptions& options, const std::function<void()>& advance = {});

// The wave boundaries over `count` portals in processing order: wave w covers
// [bounds[w], bounds[w + 1]).
std::vector<size_t> flowWaveBounds(size_t count);

}  // namespace q3::vis
