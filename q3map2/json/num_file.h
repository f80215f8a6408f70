// Streaming reader of q3map2's one-number-per-member files ({"LightByte#0": {"Num": 12}, ...}),
// which reach tens of megabytes: values go straight into a vector, no tree is built.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace q3::json {

// Reads the numbers of `name` (shown in errors) from `text`; each must lie in [minValue, maxValue].
// Throws JsonError with file:line:column on any deviation from the form.
std::vector<int64_t> readNumFile(const std::string& name, const std::string& text, int64_t minValue, int64_t maxValue);

}  // namespace q3::json
