// The WORLDLIGHTS lump in the unpacked JSON folder: its records as readable members of its entry
// in the BSPX lump file, read back to the same bytes.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "json_value.h"
#include "json_writer.h"

namespace q3::json {

// Writes the member "lights" (an array of records) for a lump image; a malformed image throws
// bsp::BspError naming `where`.
void writeWorldLightsMember(Writer& w, const std::vector<uint8_t>& lump, const std::string& where);
// The lump image of an entry's "lights" array; malformed records throw JsonError naming `context`.
std::vector<uint8_t> readWorldLightsMember(const Value& lights, const std::string& context);

}  // namespace q3::json
