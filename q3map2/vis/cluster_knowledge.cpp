#include "cluster_knowledge.h"

namespace q3::vis {

ClusterKnowledge::ClusterKnowledge(const VisGraph& graph, const BitMatrix& results)
    : graph_(graph), results_(results), holders_(graph.portals.size()), home_(graph.portals.size(), -1),
      seen_(graph.leafs.size(), static_cast<size_t>(graph.clusterCount)),
      possible_(graph.leafs.size(), static_cast<size_t>(graph.clusterCount)), portalsLeft_(graph.leafs.size(), 0) {
    for (size_t c = 0; c < graph.leafs.size(); ++c) {
        for (size_t x = 0; x < static_cast<size_t>(graph.clusterCount); ++x) setBit(possible_.row(c), x);
        if (graph.leafs[c].merged >= 0) continue;  // its list is stale: the portals moved on
        for (int p : graph.leafs[c].portals) {
            if (graph.portals[static_cast<size_t>(p)].removed) continue;
            holders_[static_cast<size_t>(p)].push_back(static_cast<int>(c));
            ++portalsLeft_[c];
        }
    }
    for (size_t p = 0; p < graph.portals.size(); ++p)
        if (holders_[p].size() == 1) home_[p] = holders_[p][0];
}

void ClusterKnowledge::learn(int portal) {
    const size_t words = seen_.words();
    const uint64_t* seen = results_.row(static_cast<size_t>(portal));
    for (int holder : holders_[static_cast<size_t>(portal)]) {
        const size_t h = static_cast<size_t>(holder);
        uint64_t* own = seen_.row(h);
        for (size_t w = 0; w < words; ++w) {
            own[w] |= seen[w];
            for (uint64_t bits = seen[w]; bits; bits &= bits - 1)
                setBit(seen_.row(w * 64 + static_cast<size_t>(std::countr_zero(bits))), h);
        }
        if (--portalsLeft_[h] != 0) continue;
        // The cluster is done: whoever its row misses cannot see it.
        std::vector<uint64_t> row(words, 0);
        setBit(row.data(), h);
        for (int p : graph_.leafs[h].portals) {
            if (graph_.portals[static_cast<size_t>(p)].removed) continue;
            const uint64_t* result = results_.row(static_cast<size_t>(p));
            for (size_t w = 0; w < words; ++w) row[w] |= result[w];
        }
        for (size_t c = 0; c < static_cast<size_t>(graph_.clusterCount); ++c)
            if (!testBit(row.data(), c)) possible_.row(c)[h >> 6] &= ~(uint64_t{1} << (h & 63));
    }
}

}  // namespace q3::vis
