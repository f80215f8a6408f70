// Shared pieces of the .map parser (not part of the public interface).
#pragma once

#include <string>
#include <string_view>

#include "map_file.h"
#include "script.h"

namespace q3::map::detail {

// Where in the file a primitive sits, for messages ("entity 2, primitive 7").
struct PrimitiveContext {
    int entityNum = 0;
    int primitiveNum = 0;
    std::string describe() const;
};

// Text for a one-line message: control characters become spaces, long text is cut short.
std::string shown(std::string_view text);

// Reads the next token (any line) and requires it to be the unquoted `text`.
void require(Script& s, std::string_view text, std::string_view where);
// Next token as a finite number that fits a float.
float readFloat(Script& s, std::string_view what, bool sameLine = false);
// The same number kept in double precision.
double readDouble(Script& s, std::string_view what, bool sameLine = false);
// Next token as an integer (what editors write for flags and sizes); values up to 2^32-1 wrap to
// int32 the way q3map2's atoi-and-store does for unsigned flag words.
int readInt(Script& s, std::string_view what, bool sameLine = false);
// A texture/material name: any token except an unquoted brace or parenthesis.
std::string readTextureName(Script& s, std::string_view where);

// The current token is the "(" of the first face.
MapBrush parseClassicBrush(Script& s, const PrimitiveContext& ctx);
// The current token is "brushDef".
MapBrush parseBrushDef(Script& s, const PrimitiveContext& ctx);
// The current token is "patchDef2" or "patchDef3"; reads up to and including the patch's own "}".
MapPatch parsePatchDef(Script& s, const PrimitiveContext& ctx, bool patchDef3);

}  // namespace q3::map::detail
