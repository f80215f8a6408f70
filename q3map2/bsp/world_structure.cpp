#include "world_structure.h"

#include <cstdio>
#include <cstdlib>

#include "brush_filter.h"
#include "count_line.h"
#include "feedback_log.h"
#include "file_io.h"
#include "log.h"
#include "script.h"
#include "visible_hull.h"

namespace q3::bspstage {
namespace {


bool keyIsTrue(const map::MapEntity& e, std::string_view a, std::string_view b) {
    const std::string* v = e.find(a);
    if (!v) v = e.find(b);
    return v && std::atoi(v->c_str()) != 0;
}

// FaceBSP, MakeTreePortals and FilterStructuralBrushesIntoTree on one face list.
Tree buildTreePass(std::vector<BspFace> faces, LoadedMap& map, const BlockSize& blockSize, bool alternateSplit,
                   TreePassCounts& counts, Log& log) {
    log.debug("--- FaceBSP ---");
    Tree tree = buildFaceTree(std::move(faces), map.planes, blockSize, alternateSplit, &counts.faceBsp);
    log.debug(countLine(counts.faceBsp.faces, "faces"));
    log.debug(countLine(counts.faceBsp.leafs, "leafs"));
    log.debug("--- MakeTreePortals ---");
    counts.portals = makeTreePortals(tree, map.planes);
    log.debug(countLine(counts.portals.tinyPortals, "tiny portals"));
    log.debug("--- FilterStructuralBrushesIntoTree ---");
    counts.structuralReferences = filterStructuralBrushesIntoTree(map.entities.front().brushes, tree, map.planes);
    log.debug(countLine(counts.structuralReferences, "cluster references"));
    return tree;
}

FloodResult floodPass(Tree& tree, LoadedMap& map, TreePassCounts& counts, Log& log) {
    log.debug("--- FloodEntities ---");
    const FloodResult result = floodEntities(tree, map.entities, map.planes, log, &counts.flood);
    log.debug(countLine(counts.flood.floodedLeafs, "flooded leafs"));
    // Verbose only, as in q3map2: the leak banner and the line file say it for everyone.
    if (result == FloodResult::Empty) log.debug("no entities in open -- no filling");
    if (result == FloodResult::Leaked) log.debug("entity reached from outside -- leak detected");
    return result;
}

void fillPass(Tree& tree, TreePassCounts& counts, Log& log) {
    log.debug("--- FillOutside ---");
    counts.fill = fillOutside(tree);
    log.debug(countLine(counts.fill.solid, "solid leafs"));
    log.info(countLine(counts.fill.filled, "leafs filled"));
    log.debug(countLine(counts.fill.inside, "inside leafs"));
}

}  // namespace

BlockSize blockSizeForWorld(const map::MapEntity& worldspawn) {
    BlockSize size = kDefaultBlockSize;
    const std::string* value = worldspawn.find("_blocksize");
    if (!value) value = worldspawn.find("blocksize");
    if (!value) value = worldspawn.find("chopsize");
    if (!value) return size;
    float v[3] = {0, 0, 0};
    const int read = std::sscanf(value->c_str(), "%f %f %f", &v[0], &v[1], &v[2]);
    if (read == 1) v[1] = v[2] = v[0];
    if (read >= 1)
        for (int i = 0; i < 3; ++i) size[size_t(i)] = v[i];
    return size;
}

WorldStructure buildWorldStructure(LoadedMap& map, const WorldStructureOptions& options, Log& log) {
    WorldStructure out;
    BspEntity& world = map.entities.front();
    out.blockSize = blockSizeForWorld(*world.source);
    const bool ignoreLeaks = keyIsTrue(*world.source, "_ignoreleaks", "ignoreleaks");
    char line[128];
    std::snprintf(line, sizeof line, "block size = { %g %g %g }", out.blockSize[0], out.blockSize[1], out.blockSize[2]);
    log.info(line);

    Tree tree = buildTreePass(makeStructuralFaceList(world.brushes, options.deep), map, out.blockSize,
                              options.alternateSplit, out.first, log);
    out.flood = floodPass(tree, map, out.first, log);
    if (ignoreLeaks && out.flood == FloodResult::Leaked) out.flood = FloodResult::Good;
    out.leaked = out.flood != FloodResult::Good;
    if (out.leaked) {
        // q3map2's banner (and, with -connect, the line to the editor); the compile goes on (the
        // map is usable, only without vis).
        std::vector<Vec3> points;
        out.leakLine = leakLineText(tree, map.entities, &out.leakingEntity, &points);
        reportLeak(log, options.feedback, points);
        if (out.leakingEntity >= 0) {
            const int entity = map.entities[size_t(out.leakingEntity)].mapEntityNum;
            {
                FeedbackEchoMute mute(options.feedback);
                log.info("Entity " + std::to_string(entity) + ", Brush 0: Entity leaked");
            }
            if (options.feedback) options.feedback->brushSelect(entity, 0, "Entity leaked", false);
        }
        if (options.leakTest) {
            log.warning("--- MAP LEAKED, ABORTING LEAKTEST ---");
            out.stoppedForLeakTest = true;
            out.tree = std::move(tree);
            return out;
        }
    }

    if (out.flood != FloodResult::Empty) {
        // Without an entity in open space every leaf would be filled: keep the first tree then.
        fillPass(tree, out.first, log);
        clipSidesIntoTree(world.brushes, tree, map.planes);
        tree = buildTreePass(makeVisibleFaceList(world.brushes, options.deep), map, out.blockSize, options.alternateSplit,
                             out.second, log);
        // Flooding again drops the portals in the void.
        floodPass(tree, map, out.second, log);
        fillPass(tree, out.second, log);
    }

    log.debug("--- NumberClusters ---");
    out.clusters = numberClusters(tree);
    log.debug(countLine(out.clusters.clusters, "visclusters"));
    log.debug(countLine(out.clusters.portals, "visportals"));
    log.debug(countLine(out.clusters.solidFaces, "solidfaces"));
    if (!out.leaked) out.portalFile = portalFileText(tree, out.clusters);
    log.debug("--- FloodAreas ---");
    out.areas = floodAreas(tree);
    log.debug(countLine(out.areas, "areas"));
    out.tree = std::move(tree);
    return out;
}

void writeWorldStructureFiles(const WorldStructure& world, const std::filesystem::path& mapPath) {
    std::filesystem::path prt = mapPath, lin = mapPath;
    prt.replace_extension(".prt");
    lin.replace_extension(".lin");
    std::error_code ignored;
    std::filesystem::remove(prt, ignored);
    std::filesystem::remove(lin, ignored);
    if (!world.leakLine.empty()) writeFileAtomic(lin, world.leakLine);
    if (!world.leaked) writeFileAtomic(prt, world.portalFile);
}

}  // namespace q3::bspstage
