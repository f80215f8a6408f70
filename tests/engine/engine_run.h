// Running the compiler and the engine check scripts from a test: staging a real oacmp map in a
// game tree of its own, relighting it with this build's q3map2, and calling q3-load-check and
// q3-screenshot (ioquake3, DarkPlaces) on the result. A missing script, engine or data set makes
// the scripts exit non-zero, so the tests fail rather than skip.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "test_data.h"

namespace q3::enginetest {

struct RunResult {
    std::string command;
    int status = -1;
    std::string output;  // stdout and stderr together
};

using test::shellQuote;  // single-quotes a word for /bin/sh

// The folder with q3-load-check and q3-screenshot: $Q3_ENGINE_TOOLS, else the configured one.
// Adds a test failure and throws when a script is missing there.
std::filesystem::path engineToolsDir();
// Game data the engines run on (GAME/*.pk3 and the native game modules): $Q3_ENGINE_DATA, else
// the configured root (Debian's /usr/share/games/openarena).
std::filesystem::path engineDataRoot();
// The oacmp pk3 of the test data (textures and shaders of the oacmp maps), laid over the engines'
// data so that the maps render with their own shaders. Fails the test when it is missing.
std::filesystem::path oacmpPk3();

// Copies the shipped maps/NAME.bsp and its maps/NAME.map source into <root>/baseoa/maps.
// Returns <root>/baseoa, the folder the compiler runs in.
std::filesystem::path stageOacmpMap(const std::filesystem::path& root, const std::string& name);

// `q3map2 -fs_basepath <data cache>/openarena -fs_game baseoa -light OPTIONS maps/NAME.bsp`, run
// in gameDir. `options` is a list of words, e.g. {"-fast", "-sh"}.
RunResult runLight(const std::filesystem::path& gameDir, const std::string& name,
                   const std::vector<std::string>& options);
// stageOacmpMap into `root`, then runLight; returns the lit maps/NAME.bsp. A failed run adds a test
// failure and throws. `output` (optional) receives the compiler's output.
std::filesystem::path relightOacmpMap(const std::filesystem::path& root, const std::string& name,
                                      const std::vector<std::string>& options, std::string* output = nullptr);

// q3-load-check -s (strict: engine warnings about the BSP fail) on `bsp` for the given engines
// ("ioq3,dp"), with the engine logs copied to logDir. Both engine scripts are run again (up to six
// times in all) after a failure that is not a strict complaint about the map: DarkPlaces' client
// crashes at random on any map here; the output then holds every attempt.
RunResult runLoadCheck(const std::filesystem::path& bsp, const std::string& engines,
                       const std::filesystem::path& logDir);

// runLoadCheck, its output printed, expecting exit 0 and one " OK " line per engine of `engines`.
RunResult expectLoads(const std::filesystem::path& bsp, const std::string& engines,
                      const std::filesystem::path& logDir);

// q3-screenshot -s with the given engines and modes ("lightmap,normal"); the PNGs are named by
// screenshotPath(prefix, engine, mode).
RunResult runScreenshot(const std::filesystem::path& bsp, const std::string& engines, const std::string& modes,
                        const std::filesystem::path& prefix, const std::filesystem::path& logDir);
std::filesystem::path screenshotPath(const std::filesystem::path& prefix, const std::string& engine,
                                     const std::string& mode);
// runScreenshot with more of q3-screenshot's options (e.g. {"-P", "X Y Z YAW", "-x", "ioq3:LINE"}) and
// ioquake3 started from `ioq3` (its $IOQ3: a client copy beside other renderers; empty: Debian's).
RunResult runScreenshotWith(const std::filesystem::path& bsp, const std::string& engines, const std::string& modes,
                            const std::filesystem::path& prefix, const std::filesystem::path& logDir,
                            const std::vector<std::string>& options, const std::filesystem::path& ioq3 = {});

// Copies `bsp` into `engineDir` (created) as <name>.bsp: the engines see it under a name no package
// ships. Returns the copy's path.
std::filesystem::path copyForEngines(const std::filesystem::path& bsp, const std::filesystem::path& engineDir,
                                     const std::string& name);

// The lines of `text` that contain `needle`.
std::vector<std::string> linesWith(const std::string& text, const std::string& needle);

// DarkPlaces' light-grid samples the scripts print (getlight() x 128, e.g. "lightgrid at
// info_player_deathmatch '...' = ' 36.0  43.0  49.1'" or "model at '...' lightgrid = '...'"):
// for each line containing `marker`, the sum of the three channels after the last "= '".
std::vector<double> darkPlacesGridSums(const std::string& text, const std::string& marker);

}  // namespace q3::enginetest
