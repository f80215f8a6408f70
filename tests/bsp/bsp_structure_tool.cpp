// Developer tool: runs the -bsp world structure steps on a .map and writes <map>.prt (or <map>.lin
// on a leak) beside it, printing q3map2's counters. Not the -bsp stage: with -emit it writes the
// structure lumps to FILE for inspection, a BSP without draw surfaces that no engine loads.
//   bspstructure [-v] [-leaktest] [-deep] [-altsplit] [-emit FILE] [-fs_basepath DIR]... [-fs_game NAME] MAP
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>

#include "bsp_brushes.h"
#include "log.h"
#include "map_file.h"
#include "shader_loader.h"
#include "vfs.h"
#include "structure_emit.h"
#include "world_structure.h"

int main(int argc, char** argv) {
    q3::Log log;
    q3::VfsOptions vfsOptions;
    q3::bspstage::WorldStructureOptions options;
    std::string mapPath, emitPath;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "-v") log.setVerbose(true);
        else if (arg == "-leaktest") options.leakTest = true;
        else if (arg == "-deep") options.deep = true;
        else if (arg == "-altsplit") options.alternateSplit = true;
        else if (arg == "-emit" && i + 1 < argc) emitPath = argv[++i];
        else if (arg == "-fs_basepath" && i + 1 < argc) vfsOptions.basePaths.emplace_back(argv[++i]);
        else if (arg == "-fs_game" && i + 1 < argc) vfsOptions.gameDirs.emplace_back(argv[++i]);
        else if (arg == "-fs_basegame" && i + 1 < argc) vfsOptions.baseGame = argv[++i];
        else mapPath = arg;
    }
    if (mapPath.empty()) {
        std::fprintf(stderr, "usage: bspstructure [-v] [-leaktest] [-deep] [-fs_basepath DIR] [-fs_game NAME] MAP\n");
        return 2;
    }
    try {
        vfsOptions.mapPath = mapPath;
        q3::Vfs vfs(vfsOptions, log);
        const q3::ShaderTable shaders = q3::loadShaderTable(vfs, log);
        const q3::map::MapFile file = q3::map::loadMap(mapPath);
        q3::bspstage::LoadedMap map = q3::bspstage::loadMapForBsp(file, shaders, {}, log);
        q3::bspstage::WorldStructure world = q3::bspstage::buildWorldStructure(map, options, log);
        q3::bspstage::writeWorldStructureFiles(world, mapPath);
        if (!emitPath.empty()) q3::bsp::writeBsp(emitPath, q3::bspstage::emitStructure(map, world, shaders, {}));
        std::printf("brushes %d detail %d planes %d\n", map.counts.worldBrushes, map.counts.detailBrushes,
                    map.planes.size());
        std::printf("first: faces %d leafs %d filled %d\n", world.first.faceBsp.faces, world.first.faceBsp.leafs,
                    world.first.fill.filled);
        std::printf("second: faces %d leafs %d\n", world.second.faceBsp.faces, world.second.faceBsp.leafs);
        std::printf("clusters %d portals %d solidfaces %d areas %d leaked %d\n", world.clusters.clusters,
                    world.clusters.portals, world.clusters.solidFaces, world.areas, world.leaked ? 1 : 0);
        return 0;
    } catch (const std::exception& e) {
        log.error(e.what());
        return 1;
    }
}
