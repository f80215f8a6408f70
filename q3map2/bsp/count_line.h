// q3map2's right-aligned counter lines ("     2175 hidden faces culled").
#pragma once

#include <cstdio>
#include <string>

namespace q3::bspstage {

inline std::string countLine(int value, const char* what) {
    char line[160];
    std::snprintf(line, sizeof line, "%9d %s", value, what);
    return line;
}

}  // namespace q3::bspstage
