// The reference q3map2's -vis results on real maps, cached outside the source tree under
//   <data cache>/vis/<map>-<reference hash>-<.map FNV-1a 64 hex>/
// holding NAME.bsp and NAME.prt (the reference's -bsp -meta, no vis), NAME.fast.bsp (its
// -vis -fast) and, when asked for, NAME.full.bsp (its full -vis), each made once.
#pragma once

#include <filesystem>
#include <string>

namespace q3::vis::test {

struct VisReference {
    std::filesystem::path bsp, prt, fastBsp, fullBsp;
};

// Compiles what is missing (safe when several processes ask at once). Throws std::runtime_error
// with the tail of the reference's output when it fails.
VisReference visReference(const std::filesystem::path& reference, const std::string& mapName, bool withFull);

// The reference's -vis with `options` (one option, like "-merge") on the cached inputs: the BSP as
// NAME<options>.bsp and its output as NAME<options>.log beside the others, made once.
std::filesystem::path referenceVisWith(const std::filesystem::path& reference, const VisReference& ref,
                                       const std::string& option);

// Copies the reference's BSP and .prt into `dir`; returns the BSP's path there.
std::filesystem::path stageVisInputs(const VisReference& ref, const std::filesystem::path& dir);

// Runs our q3map2 -vis with `options` at `threads` threads; returns the exit code, output in `log`.
int runOurVis(const std::filesystem::path& bsp, const std::string& options, int threads, std::string* log = nullptr);

}  // namespace q3::vis::test
