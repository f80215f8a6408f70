// The mapper's flow for conformance runs: the reference compiles a .map (-bsp -meta, then
// -vis -fast) into a fresh BSP whose surfaces are all unlit, and each compiler lights a copy.
//
// Fresh compiles are cached outside the source tree, under
//   <data cache>/conformance/fresh/<map>-<reference hash>-<.map FNV-1a 64 hex>/maps/
// holding NAME.bsp, NAME.srf and NAME.map; bench/conformance uses the same layout and key.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace q3::conformance {

// $Q3MAP2_REFERENCE when set, else `fallback` (the build's default beside the source tree).
std::filesystem::path referenceBinary(const std::filesystem::path& fallback);

// 64-bit FNV-1a of a file's bytes, as 16 lower-case hex digits. Throws FileError naming the file.
std::string fileHash(const std::filesystem::path& path);

// 64-bit FNV-1a over the reference's folder (each regular file's name, a NUL, its bytes, in name
// order), as 16 hex digits: the reference's identity in cache keys, whatever its timestamps.
std::string referenceHash(const std::filesystem::path& reference);

// The cache folder name for a map compiled by a reference binary (see above).
std::string freshCacheKey(const std::filesystem::path& reference, const std::filesystem::path& mapSource);

// The cached fresh compile of `mapSource` (a folder whose maps/ holds NAME.bsp/.srf/.map),
// compiled first when absent. Safe when several processes ask at once: each compiles into its own
// temporary folder and renames it into place. Throws std::runtime_error (one line, with the tail
// of the reference's output) when the reference fails.
std::filesystem::path freshCompile(const std::filesystem::path& reference, const std::filesystem::path& gameBase,
                                   const std::filesystem::path& dataCache, const std::filesystem::path& mapSource);

// The same compile by ours (`ours` -bsp -meta, then -vis -fast) in `dest` (emptied first), not
// cached: it follows every build. Returns `dest`, holding maps/NAME.bsp, .srf and .map.
std::filesystem::path ownFreshCompile(const std::filesystem::path& ours, const std::filesystem::path& gameBase,
                                      const std::filesystem::path& mapSource, const std::filesystem::path& dest);

// Copies the fresh maps/ folder into dest/maps (dest emptied first); returns dest/maps/NAME.bsp.
std::filesystem::path stageFresh(const std::filesystem::path& fresh, const std::filesystem::path& dest,
                                 const std::string& mapName);

struct ToolRun {
    int exitCode = -1;
    double wallSeconds = 0;
    std::string output;
};

// The reference's -light with `args` ("-fast", ...) at `threads` threads.
ToolRun lightWithReference(const std::filesystem::path& reference, const std::filesystem::path& gameBase,
                           const std::filesystem::path& bsp, const std::vector<std::string>& args, int threads);
// Ours: the same options with our base path spelling (-fs_basepath DIR -fs_game baseoa).
ToolRun lightWithOurs(const std::filesystem::path& ours, const std::filesystem::path& gameBase,
                      const std::filesystem::path& bsp, const std::vector<std::string>& args, int threads);

}  // namespace q3::conformance
