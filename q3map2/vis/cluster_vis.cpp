#include "cluster_vis.h"

#include <tbb/parallel_for.h>

#include <cstring>
#include <stdexcept>
#include <string>

namespace q3::vis {

BitMatrix portalClusterSets(const VisGraph& graph, const BitMatrix& portalBits) {
    BitMatrix sets(graph.portals.size(), static_cast<size_t>(graph.clusterCount));
    tbb::parallel_for(tbb::blocked_range<size_t>(0, graph.portals.size(), 64), [&](const tbb::blocked_range<size_t>& range) {
        for (size_t p = range.begin(); p != range.end(); ++p) {
            uint64_t* out = sets.row(p);
            setBit(out, static_cast<size_t>(graph.portals[p].leaf));
            const uint64_t* row = portalBits.row(p);
            for (size_t w = 0; w < portalBits.words(); ++w)
                for (uint64_t bits = row[w]; bits; bits &= bits - 1)
                    setBit(out, static_cast<size_t>(graph.portals[w * 64 + static_cast<size_t>(std::countr_zero(bits))].leaf));
        }
    });
    return sets;
}

std::vector<uint8_t> buildVisibilityLump(const VisGraph& graph, const BitMatrix& clusterSets) {
    const int clusters = graph.clusterCount;
    const int32_t rowBytes = visRowBytes(clusters);
    std::vector<uint8_t> lump(8 + static_cast<size_t>(clusters) * static_cast<size_t>(rowBytes), 0);
    std::memcpy(lump.data(), &clusters, 4);
    std::memcpy(lump.data() + 4, &rowBytes, 4);
    std::vector<int> rootOf(static_cast<size_t>(clusters));
    for (int c = 0; c < clusters; ++c) rootOf[static_cast<size_t>(c)] = mergedLeaf(graph, c);

    tbb::parallel_for(tbb::blocked_range<int>(0, clusters, 16), [&](const tbb::blocked_range<int>& range) {
        std::vector<uint64_t> seen(clusterSets.words());
        for (int c = range.begin(); c != range.end(); ++c) {
            const int root = rootOf[static_cast<size_t>(c)];
            std::fill(seen.begin(), seen.end(), 0);
            setBit(seen.data(), static_cast<size_t>(root));
            for (int pnum : graph.leafs[static_cast<size_t>(root)].portals) {
                if (graph.portals[static_cast<size_t>(pnum)].removed) continue;
                const uint64_t* row = clusterSets.row(static_cast<size_t>(pnum));
                for (size_t w = 0; w < seen.size(); ++w) seen[w] |= row[w];
            }
            uint8_t* out = lump.data() + 8 + static_cast<size_t>(c) * static_cast<size_t>(rowBytes);
            // A merged-away leaf is seen when the leaf it went into is.
            for (int other = 0; other < clusters; ++other)
                if (testBit(seen.data(), static_cast<size_t>(rootOf[static_cast<size_t>(other)])))
                    out[other >> 3] |= static_cast<uint8_t>(1u << (other & 7));
        }
    });
    return lump;
}

VisSummary summarizeVisibility(std::span<const uint8_t> lump) {
    if (lump.size() < 8) throw std::runtime_error("visibility lump of " + std::to_string(lump.size()) + " bytes has no header");
    int32_t clusters = 0, rowBytes = 0;
    std::memcpy(&clusters, lump.data(), 4);
    std::memcpy(&rowBytes, lump.data() + 4, 4);
    if (clusters < 0 || rowBytes < 0 || static_cast<int64_t>(rowBytes) * 8 < clusters ||
        lump.size() < 8 + static_cast<size_t>(clusters) * static_cast<size_t>(rowBytes))
        throw std::runtime_error("visibility lump header (" + std::to_string(clusters) + " clusters, " +
                                 std::to_string(rowBytes) + " bytes per row) does not fit its " +
                                 std::to_string(lump.size()) + " bytes");
    VisSummary s;
    s.clusters = clusters;
    s.histogram.assign(static_cast<size_t>(clusters) + 1, 0);
    double total = 0;
    s.minVisible = clusters;
    for (int c = 0; c < clusters; ++c) {
        const uint8_t* row = lump.data() + 8 + static_cast<size_t>(c) * static_cast<size_t>(rowBytes);
        int visible = 0;
        for (int j = 0; j < clusters; ++j) visible += (row[j >> 3] >> (j & 7)) & 1;
        ++s.histogram[static_cast<size_t>(visible)];
        total += visible;
        s.minVisible = std::min(s.minVisible, visible);
        s.maxVisible = std::max(s.maxVisible, visible);
    }
    if (clusters == 0) s.minVisible = 0;
    s.averageVisible = clusters ? total / clusters : 0;
    return s;
}

}  // namespace q3::vis
