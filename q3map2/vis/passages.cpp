#include "passages.h"

#include <tbb/parallel_for.h>

#include <array>

namespace q3::vis {

namespace {

// Whether `candidate` keeps some area in front of every separator.
bool survivesSeparators(const VisPortal& candidate, const Plane* separators, int count) {
    for (int k = 0; k < count; ++k) {
        // Entirely behind (q3map2 allows the epsilon on the sphere as well).
        if (separators[k].distanceTo(candidate.origin) < -candidate.radius + kOnEpsilon) return false;
        bool anyInFront = false;
        for (Vec3 p : candidate.winding.view())
            if (separators[k].distanceTo(p) > kOnEpsilon) {
                anyInFront = true;
                break;
            }
        if (!anyInFront) return false;
    }
    std::array<Winding, 2> buffers;
    const Winding* w = &candidate.winding;
    for (int k = 0; k < count; ++k) {
        Winding* out = (w == &buffers[0]) ? &buffers[1] : &buffers[0];
        w = chopWinding(w, separators[k], out);
        if (!w) return false;
    }
    return true;
}

}  // namespace

Passages createPassages(const VisGraph& graph, const BaseVis& base, const std::function<void()>& advance) {
    const size_t n = graph.portals.size();
    Passages passages;
    passages.firstRow.resize(n);
    size_t rows = 0;
    for (size_t i = 0; i < n; ++i) {
        passages.firstRow[i] = rows;
        rows += graph.leafs[static_cast<size_t>(graph.portals[i].leaf)].portals.size();
    }
    passages.canSee = BitMatrix(rows, static_cast<size_t>(graph.clusterCount));
    const size_t words = base.flood.words();

    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 4), [&](const tbb::blocked_range<size_t>& range) {
        std::array<Plane, 2 * kMaxSeparators> separators;
        for (size_t i = range.begin(); i != range.end(); ++i) {
            const VisPortal& portal = graph.portals[i];
            const std::vector<int>& targets = graph.leafs[static_cast<size_t>(portal.leaf)].portals;
            for (size_t k = 0; !portal.removed && k < targets.size(); ++k) {
                const VisPortal& target = graph.portals[static_cast<size_t>(targets[k])];
                if (target.removed) continue;
                int count = findSeparators(portal.winding, target.winding, false, separators.data());
                count += findSeparators(target.winding, portal.winding, true, separators.data() + count);
                uint64_t* canSee = passages.canSee.row(passages.firstRow[i] + k);
                setBit(canSee, static_cast<size_t>(target.leaf));
                const uint64_t* targetFlood = base.flood.row(static_cast<size_t>(targets[k]));
                const uint64_t* portalFlood = base.flood.row(i);
                for (size_t w = 0; w < words; ++w) {
                    uint64_t candidates = targetFlood[w] & portalFlood[w];
                    while (candidates) {
                        const size_t j = w * 64 + static_cast<size_t>(std::countr_zero(candidates));
                        candidates &= candidates - 1;
                        const VisPortal& candidate = graph.portals[j];
                        // A cluster already seen needs no second portal into it.
                        if (candidate.removed || testBit(canSee, static_cast<size_t>(candidate.leaf))) continue;
                        if (survivesSeparators(candidate, separators.data(), count))
                            setBit(canSee, static_cast<size_t>(candidate.leaf));
                    }
                }
            }
            if (advance) advance();
        }
    });
    return passages;
}

}  // namespace q3::vis
