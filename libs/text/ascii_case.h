// ASCII case folding, as std::tolower and strcasecmp do in the "C" locale the tools run in, without a
// library call per character: paths, keys, shader names and keywords are all compared this way.
#pragma once

#include <string>
#include <string_view>

namespace q3 {

constexpr char asciiLower(char c) { return c >= 'A' && c <= 'Z' ? char(c - 'A' + 'a') : c; }

// Case-insensitive ASCII comparison, as the engines compare keys and shader names.
constexpr bool equalsNoCase(std::string_view a, std::string_view b) {
    if (a.size() != b.size()) return false;
    for (size_t i = 0; i < a.size(); ++i)
        if (asciiLower(a[i]) != asciiLower(b[i])) return false;
    return true;
}

inline std::string toLower(std::string_view text) {
    std::string out(text);
    for (char& c : out) c = asciiLower(c);
    return out;
}

}  // namespace q3
