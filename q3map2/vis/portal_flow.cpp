



#include "portal_flow.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <memory>
#include <numeric>
#include <stdexcept>

namespace q3::vis {

namespace {

// One step of the walk: the state after passing through one more portal.
struct FlowLevel {
    explicit FlowLevel(size_t words) : mightSee(words) {}

    // Only words [first, last) of mightSee may be non-zero (the rest is stale): deep in the walk
    // the set is sparse, and the bit operations skip what is known to be empty.
    std::vector<uint64_t> mightSee;
    size_t first = 0, last = 0;
    bool mightSeePortal(size_t p) const {
        const size_t w = p >> 6;
        return w >= first && w < last && ((mightSee[w] >> (p & 63)) & 1u);
    }
    const Winding* source = nullptr;
    const Winding* pass = nullptr;  // nullptr at the base portal
    Winding sourceBuffer;
    std::array<Winding, 2> passBuffers;
    // The separators between the previous level's source and pass, found once per level.
    std::array<std::array<Plane, kMaxSeparators>, 2> separators;
    std::array<int, 2> separatorCount{};
    bool separatorsFound = false;
};

struct FlowShared {
    const VisGraph& graph;
    const BaseVis& base;
    const Passages* passages;
    FlowMode mode;
    BitMatrix& portalVis;
    const std::vector<int>& waveOf;  // per portal
};

// The scratch of one thread, reused from portal to portal.
struct FlowScratch {
    std::vector<std::unique_ptr<FlowLevel>> levels;
};

class PortalWalk {
public:
    PortalWalk(const FlowShared& shared, FlowScratch& scratch, int basePortal)
        : s_(shared), scratch_(scratch), baseIndex_(basePortal), base_(shared.graph.portals[static_cast<size_t>(basePortal)]),
          vis_(shared.portalVis.row(static_cast<size_t>(basePortal))), words_(shared.portalVis.words()),
          currentWave_(shared.waveOf[static_cast<size_t>(basePortal)]) {}

    void run() {
        FlowLevel& head = level(0);
        std::copy_n(s_.base.flood.row(static_cast<size_t>(baseIndex_)), words_, head.mightSee.begin());
        head.first = 0;
        head.last = words_;
        head.source = &base_.winding;
        head.pass = nullptr;
        if (s_.mode == FlowMode::Passage)
            passageOnly(baseIndex_, 0);
        else
            clipped(baseIndex_, 0);
    }

private:
    FlowLevel& level(size_t depth) {
        while (scratch_.levels.size() <= depth) scratch_.levels.push_back(std::make_unique<FlowLevel>(words_));
        return *scratch_.levels[depth];
    }

    // Finished results of earlier waves prune harder than the base flood.
    const uint64_t* mask(int portal) const {
        const size_t p = static_cast<size_t>(portal);
        return s_.waveOf[p] < currentWave_ ? s_.portalVis.row(p) : s_.base.flood.row(p);
    }

    // next = prev & mask [& passage]; true when next holds a portal not yet marked visible.
    bool narrow(const FlowLevel& prev, FlowLevel& next, int portal, const uint64_t* passage) const {
        const uint64_t* m = mask(portal);
        uint64_t more = 0;
        size_t first = prev.last, last = prev.first;
        for (size_t w = prev.first; w < prev.last; ++w) {
            uint64_t v = prev.mightSee[w] & m[w];
            if (passage) v &= passage[w];
            next.mightSee[w] = v;
            if (v) {
                first = std::min(first, w);
                last = w + 1;
            }
            more |= v & ~vis_[w];
        }
        next.first = first;
        next.last = std::max(first, last);
        return more != 0;
    }

    const uint64_t* passageRow(int from, size_t k) const {
        return s_.passages ? s_.passages->row(from, k) : nullptr;
    }

    // Chops `pass` by the separators of `next` on one side; nullptr when nothing is left.
    const Winding* clipBySeparators(FlowLevel& next, int side, const VisPortal& candidate, const Winding* pass) {
        for (int k = 0; k < next.separatorCount[side] && pass; ++k) {
            const Plane& plane = next.separators[side][k];
            const float d = plane.distanceTo(candidate.origin);
            if (d < -candidate.radius) return nullptr;  // entirely behind
            if (d > candidate.radius) continue;         // entirely in front
            Winding* out = (pass == &next.passBuffers[0]) ? &next.passBuffers[1] : &next.passBuffers[0];
            pass = chopWinding(pass, plane, out);
        }
        return pass;
    }

    // Walk into the cluster `from` leads to; `depth` is the level of the state on arrival.
    void clipped(int from, size_t depth) {
        const VisPortal& entry = s_.graph.portals[static_cast<size_t>(from)];
        const std::vector<int>& leafPortals = s_.graph.leafs[static_cast<size_t>(entry.leaf)].portals;
        FlowLevel& next = level(depth + 1);
        next.separatorsFound = false;
        for (size_t k = 0; k < leafPortals.size(); ++k) {
            // `level` may grow the scratch in deeper calls: fetch the levels again each time.
            FlowLevel& prev = *scratch_.levels[depth];
            FlowLevel& cur = *scratch_.levels[depth + 1];
            const int pnum = leafPortals[k];
            const VisPortal& p = s_.graph.portals[static_cast<size_t>(pnum)];
            if (p.removed || !prev.mightSeePortal(static_cast<size_t>(pnum))) continue;
            const uint64_t* passage = s_.mode == FlowMode::PassagePortal ? passageRow(from, k) : nullptr;
            // Through a portal already seen the walk only goes on when it may reveal more; the
            // narrowed set is built after the geometry otherwise, when the portal survives.
            const bool seen = testBit(vis_, static_cast<size_t>(pnum));
            if (seen && !narrow(prev, cur, pnum, passage)) continue;

            // The part of p in front of the base portal.
            const float dp = base_.plane.distanceTo(p.origin);
            const Winding* pass;
            if (dp < -p.radius) continue;
            if (dp > p.radius)
                pass = &p.winding;
            else if (!(pass = chopWinding(&p.winding, base_.plane, &cur.passBuffers[0])))
                continue;
            // The part of the source behind p.
            const float ds = p.plane.distanceTo(base_.origin);
            const Winding* source;
            if (ds > base_.radius) continue;
            if (ds < -base_.radius)
                source = prev.source;
            else if (!(source = chopWinding(prev.source, p.plane.flipped(), &cur.sourceBuffer)))
                continue;

            if (prev.pass) {
                if (!cur.separatorsFound) {
                    cur.separatorCount[0] = findSeparators(*prev.source, *prev.pass, false, cur.separators[0].data());
                    cur.separatorCount[1] = findSeparators(*prev.pass, *prev.source, true, cur.separators[1].data());
                    cur.separatorsFound = true;
                }
                pass = clipBySeparators(cur, 0, p, pass);
                if (pass) pass = clipBySeparators(cur, 1, p, pass);
                if (!pass) continue;
            }
            setBit(vis_, static_cast<size_t>(pnum));
            // Nothing new in the set: every portal the walk could reach is already marked.
            if (!seen && !narrow(prev, cur, pnum, passage)) continue;
            cur.source = source;
            cur.pass = pass;
            clipped(pnum, depth + 1);
        }
    }

    void passageOnly(int from, size_t depth) {
        const VisPortal& entry = s_.graph.portals[static_cast<size_t>(from)];
        const std::vector<int>& leafPortals = s_.graph.leafs[static_cast<size_t>(entry.leaf)].portals;
        level(depth + 1);
        for (size_t k = 0; k < leafPortals.size(); ++k) {
            FlowLevel& prev = *scratch_.levels[depth];
            FlowLevel& cur = *scratch_.levels[depth + 1];
            const int pnum = leafPortals[k];
            if (s_.graph.portals[static_cast<size_t>(pnum)].removed || !prev.mightSeePortal(static_cast<size_t>(pnum)))
                continue;
            setBit(vis_, static_cast<size_t>(pnum));
            if (!narrow(prev, cur, pnum, passageRow(from, k))) continue;
            passageOnly(pnum, depth + 1);
        }
    }

    const FlowShared& s_;
    FlowScratch& scratch_;
    int baseIndex_;
    const VisPortal& base_;
    uint64_t* vis_;
    size_t words_;
    int currentWave_;
};

}  // namespace

std::vector<size_t> flowWaveBounds(size_t count) {
    // Waves grow with the work done: each is 1/32 of the portals before it, at least 16, so
    // that late (large) portals find most earlier results finished while both cores stay busy.
    std::vector<size_t> bounds{0};
    while (bounds.back() < count) bounds.push_back(std::min(count, bounds.back() + std::max<size_t>(16, bounds.back() / 32)));
    return bounds;
}

BitMatrix computePortalFlow(const VisGraph& graph, const BaseVis& base, const Passages* passages,
                            const FlowOptions& options, const std::function<void()>& advance) {
    if (options.mode != FlowMode::Portal && !passages)
        throw std::logic_error("computePortalFlow: the passage modes need passages");
    const size_t n = graph.portals.size();
    std::vector<int> order(n);
    std::iota(order.begin(), order.end(), 0);
    if (options.sort)
        std::stable_sort(order.begin(), order.end(),
                         [&](int a, int b) { return base.mightSee[static_cast<size_t>(a)] < base.mightSee[static_cast<size_t>(b)]; });
    const std::vector<size_t> bounds = flowWaveBounds(n);
    std::vector<int> waveOf(n, 0);
    for (size_t w = 0; w + 1 < bounds.size(); ++w)
        for (size_t i = bounds[w]; i < bounds[w + 1]; ++i) waveOf[static_cast<size_t>(order[i])] = static_cast<int>(w);

    BitMatrix portalVis(n, n);
    FlowShared shared{graph, base, passages, options.mode, portalVis, waveOf};
    tbb::enumerable_thread_specific<FlowScratch> scratch;
    for (size_t w = 0; w + 1 < bounds.size(); ++w) {
        // Within a wave the largest first, so that the longest walks do not start last.
        std::vector<int> wave(order.begin() + static_cast<std::ptrdiff_t>(bounds[w]),
                              order.begin() + static_cast<std::ptrdiff_t>(bounds[w + 1]));
        std::reverse(wave.begin(), wave.end());
        tbb::parallel_for(tbb::blocked_range<size_t>(0, wave.size(), 1), [&](const tbb::blocked_range<size_t>& range) {
            for (size_t i = range.begin(); i != range.end(); ++i) {
                const int portal = wave[i];
                if (!graph.portals[static_cast<size_t>(portal)].removed) {
                    PortalWalk walk(shared, scratch.local(), portal);
                    walk.run();
                }
                if (advance) advance();
            }
        }, tbb::simple_partitioner());
    }
    return portalVis;
}

}  // namespace q3::vis
