// Shared pieces of the .map parser (not part of the public interface).
#pragma once

#include <string>
#include <string_view>
#include <type_traits>

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

// What a parser is reading, for its error messages: text, or a function composing the text that
// is called only when a message is given, so that reading a number never builds a string.
class Described {
public:
    Described(const char* text) : text_(text) {}
    Described(std::string_view text) : text_(text) {}
    Described(const std::string& text) : text_(text) {}
    template <class Compose>
        requires std::is_invocable_r_v<std::string, const Compose&>
    Described(const Compose& compose)
        : compose_(&compose), call_([](const void* f) { return std::string((*static_cast<const Compose*>(f))()); }) {}
    std::string text() const { return call_ ? call_(compose_) : std::string(text_); }

private:
    std::string_view text_;
    const void* compose_ = nullptr;
    std::string (*call_)(const void*) = nullptr;
};

// Reads the next token (any line) and requires it to be the unquoted `text`.
void require(Script& s, std::string_view text, const Described& where);
// Next token as a finite number that fits a float.
float readFloat(Script& s, const Described& what, bool sameLine = false);
// The same number kept in double precision.
double readDouble(Script& s, const Described& what, bool sameLine = false);
// Next token as an integer (what editors write for flags and sizes); values up to 2^32-1 wrap to
// int32 the way q3map2's atoi-and-store does for unsigned flag words.
int readInt(Script& s, const Described& what, bool sameLine = false);
// A texture/material name: any token except an unquoted brace or parenthesis.
std::string readTextureName(Script& s, const Described& where);

// The current token is the "(" of the first face.
MapBrush parseClassicBrush(Script& s, const PrimitiveContext& ctx);
// The current token is "brushDef".
MapBrush parseBrushDef(Script& s, const PrimitiveContext& ctx);
// The current token is "patchDef2" or "patchDef3"; reads up to and including the patch's own "}".
MapPatch parsePatchDef(Script& s, const PrimitiveContext& ctx, bool patchDef3);

}  // namespace q3::map::detail
