// The -bsp samples (bsp-samples/samples/maps/*.map, with their own shaders) and their golden
// outputs (bsp-samples/golden/): compiling one the way the golden files were made, for the
// regression test and for the tool that regenerates the goldens.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace q3 {
class Log;
}

namespace q3::bspstage::test {

std::filesystem::path samplesRoot();  // bsp-samples/
std::filesystem::path goldenDir();    // bsp-samples/golden/
std::vector<std::string> sampleNames();

// The files a compile of a sample writes: .bsp, .srf, and .prt or .lin.
std::vector<std::string> sampleOutputExtensions(const std::filesystem::path& dir, const std::string& name);

// The -bsp options a sample is compiled with: its first line "// options: -meta ..." (none without).
std::vector<std::string> sampleOptions(const std::string& name);

// Copies the sample game folder under `work` and runs -bsp on the sample there (quiet), with the
// sample's options and then `extraOptions`; returns the folder holding the outputs. Throws what the
// stage throws. Messages go to `log` when given.
std::filesystem::path compileSample(const std::string& name, const std::filesystem::path& work, Log* log = nullptr,
                                    const std::vector<std::string>& extraOptions = {});
// The same with the options given instead of the sample's own.
std::filesystem::path compileSampleWith(const std::string& name, const std::vector<std::string>& args,
                                        const std::filesystem::path& work, Log* log = nullptr);
// The sample's own options followed by `extraOptions`.
std::vector<std::string> sampleOptionsWith(const std::string& name, const std::vector<std::string>& extraOptions);

}  // namespace q3::bspstage::test
