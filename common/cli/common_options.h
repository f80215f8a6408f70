// Options every stage shares: those given before the stage switch, and the map path.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace q3 {

struct CommonOptions {
    bool verbose = false;
    int threads = 0;                       // 0 = one per core
    std::string game = "quake3";           // -game
    std::vector<std::string> basePaths;    // -fs_basepath, repeatable
    std::string fsGame;                    // -fs_game
    std::string baseGame;                  // -fs_basegame; empty = the game profile's folder
    std::string homePath;                  // -fs_homepath
    std::string connect;                   // -connect host:port
    bool force = false;                    // -force
    int maxMapDrawSurfs = 0x20000;         // -maxmapdrawsurfs: draw surfaces -bsp may hold
    bool warningsAsErrors = false;         // -werror: a run with warnings fails (exit 1)
    std::filesystem::path statsPath;       // -stats FILE.json: machine-readable summary
    std::filesystem::path mapPath;         // the .bsp the map argument names (x.map and x give x.bsp)
    std::filesystem::path mapArgument;     // the map argument as given (-bsp reads .reg and .ent files as named)
    std::string commandLine;               // the stage switch and its options, for _q3map2_cmdline
    // Set by the executable, never by an option: the process ends right after the stage, so a
    // stage may leave its large state for the end of the process to take back at once.
    bool processEndsAfterStage = false;
};

}  // namespace q3
