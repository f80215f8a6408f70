#include "portal_flow.h"

#include "cluster_knowledge.h"
#include "cluster_vis.h"
#include "flow_beam.h"

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

    // Clusters still possibly visible. Only words [first, last) may be non-zero (the rest is
    // stale): deep in the walk the set is sparse, and the bit operations skip what is empty.
    std::vector<uint64_t> mightSee;
    size_t first = 0, last = 0;
    bool mightSeeCluster(size_t c) const {
        const size_t w = c >> 6;
        return w >= first && w < last && ((mightSee[w] >> (c & 63)) & 1u);
    }
    const Winding* source = nullptr;
    const Winding* pass = nullptr;  // nullptr at the base portal
    Winding sourceBuffer;
    std::array<Winding, 2> passBuffers;
    Beam beam;  // between source and pass, once the walk arrives at this level
};

// A portal of a cluster as the walk first looks at it, packed per cluster so that rejecting a
// candidate by its bits never touches the portal itself.
struct LeafExit {
    int portal;
    int leaf;        // the cluster it leads into
    int passageSlot;  // its index in the cluster's portal list (the passage row)
};

struct FlowShared {
    const VisGraph& graph;
    const std::vector<std::vector<LeafExit>>& exits;  // per cluster, removed portals left out
    const std::vector<Box>& clusterBounds;
    const BitMatrix& floodClusters;  // per portal: the clusters of its base flood
    const Passages* passages;
    FlowMode mode;
    BitMatrix& clusterVis;           // per portal: the clusters it sees (the result)
    const ClusterKnowledge& known;   // what earlier waves found
    const std::vector<int>& waveOf;  // per portal
};

// The scratch of one thread, reused from portal to portal.
struct FlowScratch {
    std::vector<std::unique_ptr<FlowLevel>> levels;
    std::vector<uint8_t> onStack;  // per cluster: on the current chain
};

class PortalWalk {
public:
    PortalWalk(const FlowShared& shared, FlowScratch& scratch, int basePortal)
        : s_(shared), scratch_(scratch), baseIndex_(basePortal), base_(shared.graph.portals[static_cast<size_t>(basePortal)]),
          vis_(shared.clusterVis.row(static_cast<size_t>(basePortal))), words_(shared.clusterVis.words()),
          currentWave_(shared.waveOf[static_cast<size_t>(basePortal)]) {}

    void run() {
        FlowLevel& head = level(0);
        const uint64_t* flood = s_.floodClusters.row(static_cast<size_t>(baseIndex_));
        // What earlier waves found about the base's cluster: the clusters known hidden from it
        // are not looked for, those known visible are marked from the start (the cluster's row
        // gets them either way).
        std::copy_n(flood, words_, head.mightSee.begin());
        if (const int home = s_.known.home(baseIndex_); home >= 0) {
            const uint64_t* possible = s_.known.possible(home);
            const uint64_t* seen = s_.known.seen(home);
            for (size_t w = 0; w < words_; ++w) {
                head.mightSee[w] &= possible[w];
                vis_[w] |= flood[w] & seen[w];
            }
        }
        head.first = 0;
        head.last = words_;
        head.source = &base_.winding;
        head.pass = nullptr;
        scratch_.onStack.assign(s_.graph.leafs.size(), 0);
        setBit(vis_, static_cast<size_t>(base_.leaf));
        enter(baseIndex_, 0);
    }

private:
    FlowLevel& level(size_t depth) {
        while (scratch_.levels.size() <= depth) scratch_.levels.push_back(std::make_unique<FlowLevel>(words_));
        return *scratch_.levels[depth];
    }

    bool finished(int portal) const { return s_.waveOf[static_cast<size_t>(portal)] < currentWave_; }

    // next = prev & mask [& passage]; true when next holds a cluster not yet marked visible.
    // Most candidates have nothing new behind them: the words are only trimmed for those that do.
    bool narrow(const FlowLevel& prev, FlowLevel& next, int portal, const uint64_t* passage) const {
        // Finished results of earlier waves prune harder than the base flood. A passage only
        // holds clusters of the base flood of the portal it leads through, so that flood adds
        // nothing to it.
        const size_t p = static_cast<size_t>(portal);
        const uint64_t* mask = s_.floodClusters.row(p);
        if (finished(portal))
            mask = s_.clusterVis.row(p);
        else if (passage)
            std::swap(mask, passage), passage = nullptr;
        const uint64_t* __restrict in = prev.mightSee.data();
        const uint64_t* __restrict m = mask;
        const uint64_t* __restrict seen = vis_;
        uint64_t* __restrict out = next.mightSee.data();
        const size_t begin = prev.first, end = prev.last;
        uint64_t more = 0;
        if (passage) {
            for (size_t w = begin; w < end; ++w) {
                const uint64_t v = in[w] & m[w] & passage[w];
                out[w] = v;
                more |= v & ~seen[w];
            }
        } else {
            for (size_t w = begin; w < end; ++w) {
                const uint64_t v = in[w] & m[w];
                out[w] = v;
                more |= v & ~seen[w];
            }
        }
        if (!more) return false;
        size_t first = begin, last = end;
        while (!out[first]) ++first;  // `more` holds a bit, so some word is non-zero
        while (!out[last - 1]) --last;
        next.first = first;
        next.last = last;
        return true;
    }

    const uint64_t* passageRow(int from, size_t k) const {
        return s_.mode == FlowMode::Portal ? nullptr : s_.passages->row(from, k);
    }

    // Drops from `here.mightSee` the clusters not yet marked that no line of the beam can reach:
    // their portals lie wholly behind a separator, behind the plane of the portal just passed or
    // behind the base portal. False when no unmarked cluster is left.
    bool dropUnreachable(FlowLevel& here, const Plane& passPlane) const {
        uint64_t more = 0;
        for (size_t w = here.first; w < here.last; ++w) {
            uint64_t open = here.mightSee[w] & ~vis_[w];
            for (uint64_t bits = open; bits; bits &= bits - 1) {
                const size_t c = w * 64 + static_cast<size_t>(std::countr_zero(bits));
                const Box& box = s_.clusterBounds[c];
                bool shut = boxBehind(passPlane, box) || boxBehind(base_.plane, box);
                for (int k = 0; k < here.beam.count && !shut; ++k) shut = boxBehind(here.beam.planes[static_cast<size_t>(k)], box);
                if (shut) open &= ~(uint64_t{1} << (c & 63));
            }
            here.mightSee[w] = (here.mightSee[w] & vis_[w]) | open;
            more |= open;
        }
        return more != 0;
    }

    // Chops `pass` by the beam of `prev`; nullptr when nothing is left.
    static const Winding* clipByBeam(const FlowLevel& prev, FlowLevel& next, const VisPortal& candidate, const Winding* pass) {
        for (int k = 0; k < prev.beam.count && pass; ++k) {
            const Plane& plane = prev.beam.planes[static_cast<size_t>(k)];
            const float d = plane.distanceTo(candidate.origin);
            if (d < -candidate.radius) return nullptr;  // entirely behind
            if (d > candidate.radius) continue;         // entirely in front
            Winding* out = (pass == &next.passBuffers[0]) ? &next.passBuffers[1] : &next.passBuffers[0];
            pass = chopWinding(pass, plane, out);
        }
        return pass;
    }

    // The part of `p` the walk can see through, or nullptr: in front of the base portal, seen from
    // the part of the source behind p, and inside the separators of the previous source and pass.
    const Winding* clipCandidate(const FlowLevel& prev, FlowLevel& cur, const VisPortal& p) {
        const float dp = base_.plane.distanceTo(p.origin);
        const Winding* pass;
        if (dp < -p.radius) return nullptr;
        if (dp > p.radius)
            pass = &p.winding;
        else if (!(pass = chopWinding(&p.winding, base_.plane, &cur.passBuffers[0])))
            return nullptr;
        const float ds = p.plane.distanceTo(base_.origin);
        if (ds > base_.radius) return nullptr;
        if (ds < -base_.radius)
            cur.source = prev.source;
        else if (!(cur.source = chopWinding(prev.source, p.plane.flipped(), &cur.sourceBuffer)))
            return nullptr;
        if (!prev.pass) return pass;  // the second cluster can only be blocked if coplanar
        return clipByBeam(prev, cur, p, pass);
    }

    // Walk on into the cluster portal `from` leads to; `depth` is the level of the state on arrival.
    void enter(int from, size_t depth) {
        const VisPortal& through = s_.graph.portals[static_cast<size_t>(from)];
        const size_t leaf = static_cast<size_t>(through.leaf);
        // Clusters are convex (q3map2 merges only convex ones): a line never enters one twice.
        if (scratch_.onStack[leaf]) return;
        FlowLevel& here = level(depth);
        if (here.pass) {
            buildBeam(*here.source, *here.pass, here.beam);
            if (!dropUnreachable(here, through.plane)) return;
        }
        // Levels are held by pointer: deeper calls may add levels without moving these two.
        const FlowLevel& prev = here;
        FlowLevel& cur = level(depth + 1);
        scratch_.onStack[leaf] = 1;
        for (const LeafExit& exit : s_.exits[leaf]) {
            if (!prev.mightSeeCluster(static_cast<size_t>(exit.leaf))) continue;
            const int pnum = exit.portal;
            // Nothing new to find behind p: its own cluster is in the set, so this also keeps
            // every cluster not yet marked.
            if (!narrow(prev, cur, pnum, passageRow(from, static_cast<size_t>(exit.passageSlot)))) continue;
            const VisPortal& p = s_.graph.portals[static_cast<size_t>(pnum)];
            if (s_.mode == FlowMode::Passage) {
                setBit(vis_, static_cast<size_t>(p.leaf));
                cur.pass = nullptr;
                enter(pnum, depth + 1);
                continue;
            }
            const Winding* pass = clipCandidate(prev, cur, p);
            if (!pass) continue;
            setBit(vis_, static_cast<size_t>(p.leaf));
            cur.pass = pass;
            enter(pnum, depth + 1);
        }
        scratch_.onStack[leaf] = 0;
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

    const BitMatrix floodClusters = portalClusterSets(graph, base.flood);
    BitMatrix clusterVis(n, static_cast<size_t>(graph.clusterCount));
    std::vector<std::vector<LeafExit>> exits(graph.leafs.size());
    for (size_t l = 0; l < graph.leafs.size(); ++l) {
        const std::vector<int>& portals = graph.leafs[l].portals;
        for (size_t k = 0; k < portals.size(); ++k) {
            const VisPortal& p = graph.portals[static_cast<size_t>(portals[k])];
            if (!p.removed) exits[l].push_back({portals[k], p.leaf, static_cast<int>(k)});
        }
    }
    const std::vector<Box> clusterBounds = clusterPortalBounds(graph);
    ClusterKnowledge known(graph, clusterVis);
    FlowShared shared{graph, exits, clusterBounds, floodClusters, passages, options.mode, clusterVis, known, waveOf};
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
        // Passages alone see through more than the separators let through: told both ways, their
        // loose rows would loosen each other further.
        if (options.mode == FlowMode::Passage) continue;
        for (int portal : wave)
            if (!graph.portals[static_cast<size_t>(portal)].removed)
                known.learn(portal);
    }
    return clusterVis;
}

}  // namespace q3::vis
