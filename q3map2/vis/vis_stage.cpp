#include "vis_stage.h"

#include "base_vis.h"
#include "bspfile.h"
#include "cluster_vis.h"
#include "leaf_merge.h"
#include "passages.h"
#include "portal_file.h"
#include "portal_flow.h"
#include "progress.h"
#include "vis_graph.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>

namespace q3::vis {

namespace fs = std::filesystem;

namespace {

// printf into a string, for q3map2's number formats.
std::string formatNumbers(const char* pattern, double a, double b = 0) {
    char buf[128];
    std::snprintf(buf, sizeof buf, pattern, a, b);
    return buf;
}

// "   271 portalclusters": q3map2's right-aligned count lines.
std::string countLine(size_t count, const char* label) {
    char buf[128];
    std::snprintf(buf, sizeof buf, "%6zu %s", count, label);
    return buf;
}

// The cluster count the BSP's leafs use (highest cluster + 1), which the .prt must match: the
// engines size their cluster tables from the visibility header.
int leafClusterCount(const bsp::Bsp& bsp) {
    int count = 0;
    for (const bsp::Leaf& leaf : bsp.leafs) count = std::max(count, leaf.cluster + 1);
    return count;
}

FarPlane farPlaneOf(const bsp::Entity& worldspawn) {
    for (const char* key : {"_farplanedist", "fogclip", "distancecull"})
        if (const std::string* value = worldspawn.find(key)) return FarPlane::parse(*value);
    return {};
}

// Runs `job` over `total` items with q3map2's progress dots (or a bar on a terminal).
template <class Job>
auto withProgress(Log& log, const char* title, size_t total, Job job) {
    log.info(std::string("\n--- ") + title + " (" + std::to_string(total) + ") ---");
    Progress progress = Progress::forConsole(log, total);
    auto result = job([&progress] { progress.advance(); });
    progress.finish();
    return result;
}

void reportSummary(const VisSummary& s, bool histogram, Log& log) {
    if (histogram)
        for (size_t v = 0; v < s.histogram.size(); ++v)
            if (s.histogram[v])
                log.info(formatNumbers("%4.0f clusters have exactly %4.0f visible clusters", s.histogram[v],
                                       static_cast<double>(v)));
    const double total = s.averageVisible * s.clusters;
    log.info("Total clusters: " + std::to_string(s.clusters));
    log.info(formatNumbers("Total visible clusters: %.0f", total));
    log.info(formatNumbers("Average clusters visible: %.2f (%.3f%%/total)", s.averageVisible,
                    s.clusters ? s.averageVisible / s.clusters * 100.0 : 0.0));
    log.info("  Minimum: " + std::to_string(s.minVisible) + "  Maximum: " + std::to_string(s.maxVisible));
}

}  // namespace

const cli::OptionTable<VisOptions>& visOptionTable() {
    using cli::flag;
    using cli::kImplemented;
    using O = VisOptions;
    static const cli::OptionTable<VisOptions> table = {
        flag<O>({"-fast"}, &O::fast, "Very fast and crude vis calculation (the base flood only)", kImplemented),
        flag<O>({"-merge"}, &O::merge, "Faster but still okay vis calculation: merge leaves, then coplanar portals",
                kImplemented),
        flag<O>({"-mergeportals"}, &O::mergePortals,
                "The less crude half of -merge: merge coplanar portals between the same two clusters", kImplemented),
        flag<O>({"-hint"}, &O::hint, "Merge all but hint portals (-merge that never merges through hint portals)",
                kImplemented),
        flag<O>({"-nopassage"}, &O::noPassage, "Just use PortalFlow vis (clipping without passages)", kImplemented),
        flag<O>({"-passageOnly"}, &O::passageOnly, "Just use PassageFlow vis (passages without clipping)",
                kImplemented),
        flag<O>({"-nosort"}, &O::noSort, "Do not sort the portals before calculating vis (usually slower)",
                kImplemented),
        flag<O>({"-saveprt"}, &O::savePrt, "Keep the portal file after running vis (so you can run vis again)",
                kImplemented),
        flag<O>({"-v"}, &O::clusterHistogram, "Print how many clusters see how many clusters", kImplemented),
    };
    return table;
}

int runVisStage(const VisOptions& options, const CommonOptions& common, Log& log) {
    fs::path bspPath = common.mapPath;
    bspPath.replace_extension(".bsp");
    fs::path prtPath = bspPath;
    prtPath.replace_extension(".prt");
    log.info("--- Vis ---");

    log.info("Loading " + bspPath.string());
    bsp::Bsp bsp = bsp::readBsp(bspPath, bsp::ReadOptions{common.force, true});
    log.info("Loading " + prtPath.string());
    const PortalFile file = readPortalFile(prtPath);
    log.info(countLine(static_cast<size_t>(file.clusterCount), "portalclusters"));
    log.info(countLine(file.portals.size(), "numportals"));
    log.info(countLine(file.faces.size(), "numfaces"));
    const int leafClusters = leafClusterCount(bsp);
    if (file.clusterCount != leafClusters)
        throw PortalFileError(prtPath.string() + ": " + std::to_string(file.clusterCount) +
                              " clusters, but the leafs of " + bspPath.string() + " use " +
                              std::to_string(leafClusters) + " (the .prt belongs to another compile)");
    if (file.portals.empty()) {
        log.info("No portals means no vis, exiting.");
        return 0;
    }

    std::vector<bsp::Entity> entities = bsp::parseEntities(bsp.entities, bspPath.string());
    if (entities.empty()) throw bsp::BspError(bspPath.string() + ": entities: no worldspawn");
    const FarPlane farPlane = farPlaneOf(entities[0]);
    if (farPlane.distance != 0) log.info(formatNumbers("farplane distance = %.1f", farPlane.distance));
    bsp::injectCommandLine(entities[0], common.commandLine);
    bsp.entities = bsp::unparseEntities(entities);

    VisGraph graph = buildVisGraph(file, options.hint);
    if (options.merge || options.hint)
        log.info(countLine(static_cast<size_t>(mergeLeaves(graph, options.hint)), "leaves merged"));
    if (options.merge || options.hint || options.mergePortals) {
        const PortalMergeCount merged = mergeLeafPortals(graph);
        log.info(countLine(static_cast<size_t>(merged.portals), "portals merged"));
        log.info(countLine(static_cast<size_t>(merged.hintPortals), "hint portals merged"));
    }
    const size_t portalCount = graph.portals.size();
    const auto active = std::count_if(graph.portals.begin(), graph.portals.end(), [](const VisPortal& p) { return !p.removed; });
    const auto hints = std::count_if(graph.portals.begin(), graph.portals.end(),
                                     [](const VisPortal& p) { return !p.removed && p.hint; });
    log.info(countLine(static_cast<size_t>(active), "active portals"));
    log.info(countLine(static_cast<size_t>(hints), "hint portals"));

    const BaseVis base = withProgress(log, "BasePortalVis", portalCount,
                                      [&](auto advance) { return computeBaseVis(graph, farPlane, advance); });
    BitMatrix clusterSets;
    if (options.fast) {
        clusterSets = portalClusterSets(graph, base.flood);
    } else {
        FlowOptions flow;
        flow.sort = !options.noSort;
        flow.mode = options.noPassage ? FlowMode::Portal : options.passageOnly ? FlowMode::Passage : FlowMode::PassagePortal;
        Passages passages;
        if (flow.mode != FlowMode::Portal)
            passages = withProgress(log, "CreatePassages", portalCount,
                                    [&](auto advance) { return createPassages(graph, base, advance); });
        const char* title = flow.mode == FlowMode::Portal ? "PortalFlow"
                            : flow.mode == FlowMode::Passage ? "PassageFlow" : "PassagePortalFlow";
        clusterSets = withProgress(log, title, portalCount, [&](auto advance) {
            return computePortalFlow(graph, base, flow.mode == FlowMode::Portal ? nullptr : &passages, flow, advance);
        });
    }

    log.info("creating leaf vis...");
    bsp.visibility = buildVisibilityLump(graph, clusterSets);
    reportSummary(summarizeVisibility(bsp.visibility), options.clusterHistogram, log);

    log.info("Writing " + bspPath.string());
    bsp::writeBsp(bspPath, bsp);
    if (!options.savePrt) {
        std::error_code ec;
        fs::remove(prtPath, ec);
        if (ec) log.warning("cannot delete " + prtPath.string() + ": " + ec.message());
    }
    return 0;
}

}  // namespace q3::vis
