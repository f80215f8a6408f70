// Typed reads of entity key values, the way q3map2 reads them (atof/atoi semantics: a malformed
// number reads as 0, missing components of a vector are 0).
#pragma once

#include <cstdlib>
#include <initializer_list>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>

#include "bspfile.h"
#include "vec3.h"

namespace q3::light {

// First present key among `keys`, or nullptr.
inline const std::string* findAnyKey(const bsp::Entity& e, std::initializer_list<std::string_view> keys) {
    for (std::string_view k : keys)
        if (const std::string* v = e.find(k)) return v;
    return nullptr;
}

inline std::optional<float> floatKey(const bsp::Entity& e, std::initializer_list<std::string_view> keys) {
    const std::string* v = findAnyKey(e, keys);
    if (!v) return std::nullopt;
    return static_cast<float>(std::atof(v->c_str()));
}

inline std::optional<int> intKey(const bsp::Entity& e, std::initializer_list<std::string_view> keys) {
    const std::string* v = findAnyKey(e, keys);
    if (!v) return std::nullopt;
    return std::atoi(v->c_str());
}

inline std::optional<Vec3> vecKey(const bsp::Entity& e, std::initializer_list<std::string_view> keys) {
    const std::string* v = findAnyKey(e, keys);
    if (!v) return std::nullopt;
    std::istringstream in(*v);
    Vec3 r;
    in >> r.x >> r.y >> r.z;
    if (in.fail() && !in.eof()) return Vec3{};
    return r;
}

// q3map2's boolean keys: "1" (any non-zero integer) is true.
inline bool boolKey(const bsp::Entity& e, std::initializer_list<std::string_view> keys) {
    const std::string* v = findAnyKey(e, keys);
    return v && std::atoi(v->c_str()) != 0;
}

}  // namespace q3::light
