// Locations of test inputs. Real OpenArena data comes from tools/fetch-openarena.sh; a test that
// needs it fails (never skips) when it is missing, so a green run always exercised real maps.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace q3::test {

// Root of the fetched OpenArena cache ($Q3MAP_DATA_CACHE or ~/.cache/q3map2-data).
// Fails the current test (fatal) when the cache is not complete.
std::filesystem::path dataCache();
// The game tree: <cache>/openarena with baseoa/ (pk3s) below it.
std::filesystem::path openArenaBase();
// Every BSP unpacked from the packages (about 110), sorted.
std::vector<std::filesystem::path> allRealBsps();
// The list for test registration (INSTANTIATE_TEST_SUITE_P) of per-map tests: empty, without
// failing, when the cache is missing (pair it with a test that asserts the count through
// allRealBsps()). A build configured with Q3MAP_TEST_MAP_STRIDE=N lists only every Nth map (and
// always the largest): the sanitizer build uses it to keep the heaviest per-map tests affordable.
bool realBspsAreSampled();
std::vector<std::filesystem::path> realBspsForRegistration();
// The 13 .map sources of openarena-oacmp1, sorted.
std::vector<std::filesystem::path> oacmpMapSources();
// The same for test registration: empty, without failing, when the cache is missing (pair it with a
// test that asserts the count through oacmpMapSources()).
std::vector<std::filesystem::path> oacmpMapSourcesForRegistration();
// The shipped BSP of one map by name ("oacmpdm1"); fails the test when absent.
std::filesystem::path realBsp(const std::string& mapName);
// Every unpacked scripts/*.shader file, sorted.
std::vector<std::filesystem::path> allShaderScripts();

// A fresh, empty folder under the build tree, unique to the running test.
std::filesystem::path tempDir();
// Path of the q3map2 executable of this build.
std::filesystem::path q3map2Exe();

// Runs a command line through /bin/sh, capturing stdout+stderr. Returns the exit code.
int runCommand(const std::string& commandLine, std::string* output = nullptr);

// `word` in single quotes for a shell command line (embedded single quotes escaped).
std::string shellQuote(const std::string& word);
inline std::string shellQuote(const char* word) { return shellQuote(std::string(word)); }
inline std::string shellQuote(const std::filesystem::path& path) { return shellQuote(path.string()); }

}  // namespace q3::test
