// Optimal-string-alignment distance (insertions, deletions, substitutions and swaps of adjacent
// characters), case-insensitive: how far a mistyped option name is from a real one.
#pragma once

#include <cstddef>
#include <string_view>

namespace q3::cli {

size_t editDistance(std::string_view a, std::string_view b);

}  // namespace q3::cli
