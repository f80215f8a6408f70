// Fixture of the tests that run the reference q3map2: it finds the binary ($Q3MAP2_REFERENCE, else
// the build's default beside the source tree) and skips the test when it is missing, or fails it
// when $CI is set (CI must run these tests). tools/run-tests.sh looks for the skip message.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "conformance_pipeline.h"

namespace q3::conformance {

template <class Param>
class ReferenceTest : public ::testing::TestWithParam<Param> {
protected:
    void SetUp() override {
        reference_ = referenceBinary(Q3MAP2_REFERENCE_DEFAULT);
        if (std::filesystem::exists(reference_)) return;
        const std::string message = "conformance tests did not run: reference q3map2 not found at " +
                                    reference_.string() + " (set Q3MAP2_REFERENCE)";
        if (std::getenv("CI")) FAIL() << message;
        GTEST_SKIP() << message;
    }
    const std::filesystem::path& reference() const { return reference_; }

private:
    std::filesystem::path reference_;
};

}  // namespace q3::conformance
