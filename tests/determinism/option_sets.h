// The benchmark option sets (bench/option-sets.json), shared with bench/run so that every set
// benchmarked is also checked here.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace q3::test {

struct OptionSet {
    std::string name;
    std::vector<std::string> args;  // stage options, e.g. {"-light", "-fast", "-sh"}
    std::string after;              // a set that must run first on the same folder ("" if none)
    bool skipWhenSampled = false;   // "sampledBuilds": "skip": not checked where real maps are sampled
};

// bench/option-sets.json of the source tree.
std::filesystem::path optionSetsFile();

// Reads the sets in file order. Throws std::runtime_error naming the file on any defect.
std::vector<OptionSet> readOptionSets(const std::filesystem::path& file);

}  // namespace q3::test
