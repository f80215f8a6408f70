// Surface and content flags in shaders.json: q3map2 writes each flag value as an object whose
// members name the surfaceparms it is made of, each with its bits in hex
// ({"default": "0x00000001"}); -useflagnames packs from the names instead of the numbers.
#pragma once

#include "json_value.h"
#include "json_writer.h"

#include <cstdint>
#include <string>
#include <vector>

namespace q3::json {

struct FlagName {
    std::string name;
    uint32_t bits;
};

struct FlagTable {
    std::vector<FlagName> content;
    std::vector<FlagName> surface;
};

// The Quake 3 surfaceparm names and bits, in a fixed order.
const FlagTable& quake3Flags();

// Bits no surfaceparm accounts for are written under this member name.
constexpr const char* kUnnamedFlags = "unnamed";

void writeFlags(Writer& out, uint32_t value, const std::vector<FlagName>& names);

struct FlagReadOptions {
    bool useNames = false;
    bool skipUnknown = false;
};
uint32_t readFlags(const Value& value, const std::vector<FlagName>& names, const FlagReadOptions& options,
                   const std::string& context);

}  // namespace q3::json
