// Shared by the tests that compare the -bsp steps with q3map2 2.5.17n on the oacmp maps.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "bsp_options.h"
#include "shader_info.h"

namespace q3::bspstage::test {

// The reference's compile (-v -bsp -meta and `extraOptions`; without -meta when `meta` is false)
// of `mapSource`, cached under <data cache>/bsp-prt/<key>/ (the key names the map, the reference
// binary's size and mtime, the .map's hash and the options): the folder holding NAME.prt (or
// NAME.lin), NAME.bsp, NAME.srf (or NAME.caulk with -autocaulk) and NAME.log (the -v output).
// Throws when it fails.
std::filesystem::path referenceCompile(const std::filesystem::path& reference, const std::filesystem::path& mapSource,
                                       const std::string& extraOptions = {}, bool meta = true);

// Our compile of a map source in a scratch maps/ folder `work` (emptied first), with the OpenArena
// data; returns the .bsp path. With `log`, the -v output is appended to it.
std::filesystem::path ourCompile(const std::filesystem::path& mapSource, const std::filesystem::path& work,
                                 const BspOptions& options = {}, std::string* log = nullptr);

// The reference's -bsp of the sample `name` (bsp-samples, with the sample's options) in `work`/samples/maps/, uncached
// (a sample compiles in a fraction of a second); returns that folder. Fails the test when it fails.
std::filesystem::path referenceSampleCompile(const std::filesystem::path& reference, const std::string& name,
                                             const std::filesystem::path& work,
                                             const std::vector<std::string>& extraOptions = {});
// The same with the options given instead of the sample's own.
std::filesystem::path referenceSampleCompileWith(const std::filesystem::path& reference, const std::string& name,
                                                 const std::vector<std::string>& args,
                                                 const std::filesystem::path& work);

// The sample `name` compiled by ours (compileSample) and by the reference (referenceSampleCompile),
// each in its own folder under `work`, a scratch folder named after the sample and the process:
// the folders holding each tool's outputs. Remove `work` when done.
struct SampleCompiles {
    std::filesystem::path work, ours, theirs;
};
// `extraOptions` follow the sample's own options in both compiles.
SampleCompiles compileSampleBothWays(const std::filesystem::path& reference, const std::string& name,
                                     const std::vector<std::string>& extraOptions = {});
// Both ways with the options given instead of the sample's own.
SampleCompiles compileSampleBothWaysWith(const std::filesystem::path& reference, const std::string& name,
                                         const std::vector<std::string>& args);

// Test expectations on a sample compiled both ways: every lump but the entities (which record the
// command line) byte for byte, and the same .srf and .prt.
void expectSampleOutputsEqual(const SampleCompiles& compiles, const std::string& name);

// The .map source of an oacmp map by name ("oacmpdm7"); fails the test when it is missing.
std::filesystem::path oacmpSource(const std::string& name);

// Every shader of the OpenArena data (loaded once).
const ShaderTable& openArenaShaders();

}  // namespace q3::bspstage::test
