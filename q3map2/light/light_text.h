// Message building for the light stage: concatenates any streamable values (std::format is not
// available with every supported compiler).
#pragma once

#include <sstream>
#include <string>

namespace q3::light {

template <typename... Args>
std::string strCat(const Args&... args) {
    std::ostringstream out;
    (out << ... << args);
    return out.str();
}

}  // namespace q3::light
