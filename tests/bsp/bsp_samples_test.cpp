// Regression test of the -bsp samples: each compiles to the same bytes as its golden files,
// lump by lump (regenerate them with `bspgolden` after an intended change, never from here).
#include <gtest/gtest.h>

#include <unistd.h>

#include "bsp_samples.h"
#include "bspfile.h"
#include "file_io.h"

namespace q3::bspstage::test {
namespace {

namespace fs = std::filesystem;

class BspSamples : public ::testing::TestWithParam<std::string> {};

TEST_P(BspSamples, OutputsEqualTheGoldenFiles) {
    const std::string name = GetParam();
    const fs::path work = fs::temp_directory_path() / ("bsp-sample-" + name + "-" + std::to_string(::getpid()));
    const fs::path out = compileSample(name, work);
    const std::vector<std::string> produced = sampleOutputExtensions(out, name);
    EXPECT_EQ(produced, sampleOutputExtensions(goldenDir(), name)) << "files written for " << name;
    for (const std::string& ext : produced) {
        const fs::path golden = goldenDir() / (name + ext);
        ASSERT_TRUE(fs::exists(golden)) << golden;
        if (ext == ".bsp") {
            const bsp::Bsp ours = bsp::readBsp(out / (name + ext));
            const bsp::Bsp expected = bsp::readBsp(golden);
            for (int lump = 0; lump < bsp::kMaxLumps; ++lump)
                EXPECT_TRUE(bsp::lumpBytes(ours, lump) == bsp::lumpBytes(expected, lump))
                    << name << ".bsp: lump " << bsp::lumpName(lump) << " differs from the golden file";
            EXPECT_EQ(ours.headerLumps, expected.headerLumps);
        } else {
            EXPECT_EQ(readFileText(out / (name + ext)), readFileText(golden)) << name << ext;
        }
    }
    fs::remove_all(work);
}

INSTANTIATE_TEST_SUITE_P(Samples, BspSamples, ::testing::ValuesIn(sampleNames()),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

}  // namespace
}  // namespace q3::bspstage::test
