// Regenerates the golden outputs of the -bsp samples (bsp-samples/golden/) from this build:
//   bspgolden [NAME...]     (no name: every sample)
// Run it after a change that is meant to alter -bsp output, and review the difference.
#include <cstdio>
#include <exception>
#include <filesystem>

#include "bsp_samples.h"

int main(int argc, char** argv) {
    namespace fs = std::filesystem;
    using namespace q3::bspstage::test;
    std::vector<std::string> names(argv + 1, argv + argc);
    if (names.empty()) names = sampleNames();
    try {
        fs::create_directories(goldenDir());
        for (const std::string& name : names) {
            const fs::path work = fs::temp_directory_path() / ("bsp-golden-" + name);
            const fs::path out = compileSample(name, work);
            for (const char* ext : {".bsp", ".srf", ".prt", ".lin"}) fs::remove(goldenDir() / (name + ext));
            for (const std::string& ext : sampleOutputExtensions(out, name))
                fs::copy_file(out / (name + ext), goldenDir() / (name + ext), fs::copy_options::overwrite_existing);
            fs::remove_all(work);
            std::printf("%s\n", name.c_str());
        }
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "ERROR: %s\n", e.what());
        return 1;
    }
}
