// The .prt reader and, on the small files it accepts, every vis pass behind it.
#include "fuzz_entries.h"

#include "base_vis.h"
#include "cluster_vis.h"
#include "leaf_merge.h"
#include "passages.h"
#include "portal_file.h"
#include "portal_flow.h"
#include "vis_graph.h"

#include <string>

namespace q3::fuzz {

namespace {

// Larger accepted inputs are only read: the passes grow with the square of the portal count.
constexpr size_t kMaxPassPortals = 64;
constexpr int kMaxPassClusters = 64;

bool sees(const std::vector<uint8_t>& lump, int rowBytes, int from, int to) {
    return (lump[8 + static_cast<size_t>(from * rowBytes + to / 8)] >> (to % 8)) & 1;
}

void checkLump(const std::vector<uint8_t>& lump, const std::vector<uint8_t>* looser, int clusters) {
    const int rowBytes = vis::visRowBytes(clusters);
    if (lump.size() != 8 + static_cast<size_t>(clusters) * static_cast<size_t>(rowBytes))
        throw PropertyViolation("visibility lump size does not match its cluster count");
    for (int c = 0; c < clusters; ++c) {
        if (!sees(lump, rowBytes, c, c)) throw PropertyViolation("a cluster does not see itself");
        if (!looser) continue;
        for (int o = 0; o < clusters; ++o)
            if (sees(lump, rowBytes, c, o) && !sees(*looser, rowBytes, c, o))
                throw PropertyViolation("the full vis sees a cluster the base flood does not");
    }
}

}  // namespace

void fuzzPrt(std::span<const uint8_t> input, const FuzzContext&) {
    vis::PortalFile file;
    try {
        file = vis::parsePortalFile(std::string_view(reinterpret_cast<const char*>(input.data()), input.size()), "fuzz.prt");
    } catch (const vis::PortalFileError&) {
        return;
    }
    if (file.portals.size() > kMaxPassPortals || file.clusterCount > kMaxPassClusters) return;
    // The input's first byte picks -hint (bit 0), -merge (bit 1) and -mergeportals (bit 2): leading
    // white space ("\v" = hint + merge, "\f" = portal merge, "\r" = hint + portal merge) reaches them.
    const uint8_t switches = input.empty() ? 0 : input[0];
    vis::VisGraph graph = vis::buildVisGraph(file, switches & 1);
    if (switches & 2) vis::mergeLeaves(graph, switches & 1);
    if (switches & 4) vis::mergeLeafPortals(graph);
    const vis::BaseVis base = vis::computeBaseVis(graph, vis::FarPlane{});
    const std::vector<uint8_t> fast = vis::buildVisibilityLump(graph, vis::portalClusterSets(graph, base.flood));
    checkLump(fast, nullptr, file.clusterCount);
    const vis::Passages passages = vis::createPassages(graph, base);
    for (vis::FlowMode mode : {vis::FlowMode::Portal, vis::FlowMode::PassagePortal, vis::FlowMode::Passage}) {
        vis::FlowOptions options;
        options.mode = mode;
        checkLump(vis::buildVisibilityLump(graph, vis::computePortalFlow(graph, base, &passages, options)), &fast,
                  file.clusterCount);
    }
}

}  // namespace q3::fuzz
