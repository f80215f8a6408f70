// The first, rough pass of -vis (q3map2's BasePortalVis): for each portal, the portals that are at
// least partly in front of it and have it partly behind them, then the flood through the clusters
// along those portals. The flood is the "might see" set every later pass starts from, and on its
// own the result of -vis -fast.
#pragma once

#include "portal_bits.h"
#include "vis_graph.h"

#include <functional>
#include <string_view>
#include <vector>

namespace q3::vis {

// Worldspawn's _farplanedist (or fogclip / distancecull): portals farther apart than this never
// see each other; sky portals are exempt. The letter after the number picks the measure: 'o'
// centre to centre, 'r' radius + radius, 'e' centre distance + both radii against twice the
// distance, anything else centre distance minus both radii.
struct FarPlane {
    float distance = 0;  // 0 = off
    char mode = 0;

    static FarPlane parse(std::string_view value);
};

struct BaseVis {
    BitMatrix flood;             // per portal: the portals it might see
    std::vector<int> mightSee;   // per portal: the bit count of its flood row
};

// `advance` is called once per portal done (progress), from any thread.
BaseVis computeBaseVis(const VisGraph& graph, const FarPlane& farPlane, const std::function<void()>& advance = {});

}  // namespace q3::vis
