// Streaming reader of q3map2's one-number-per-member files ({"LightByte#0": {"Num": 12}, ...}),
// which reach tens of megabytes: values go straight into a vector, no tree is built.
#pragma once

#include <cstdint>
#include <functional>
#include <string_view>
#include <utility>
#include <string>
#include <vector>

namespace q3::json {

// Reads the numbers of `name` (shown in errors) from `text`; each must lie in [minValue, maxValue].
// Throws JsonError with file:line:column on any deviation from the form.
std::vector<int64_t> readNumFile(const std::string& name, const std::string& text, int64_t minValue, int64_t maxValue);

}  // namespace q3::json

namespace q3::json {

// One record of a flat record file: each member's numbers in order, nested arrays flattened
// ("ambient": [[1, 2, 3], [0, 0, 0]] gives 1 2 3 0 0 0).
struct FlatRecord {
    std::string name;  // "GridPoint#12"
    std::vector<std::pair<std::string, std::vector<int64_t>>> members;
    const std::vector<int64_t>* find(std::string_view key) const;
};

// Streams {"Prefix#i": {"key": integer or nested arrays of integers, ...}, ...} without building a
// tree (GridPoints.json reaches hundreds of megabytes). `onRecord` converts each record; it reports
// problems by returning a message ("GridPoint#3.ambient: ..."), which becomes a JsonError located
// at the end of that record.
void readFlatRecords(const std::string& name, const std::string& text,
                     const std::function<std::string(const FlatRecord&)>& onRecord);

}  // namespace q3::json
