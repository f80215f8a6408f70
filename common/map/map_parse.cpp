// Top level of the .map parser: the optional Version line, entities, their key/value pairs, and the
// dispatch of each { } primitive to the brush or patch reader.
#include <cfloat>
#include <cstdint>
#include <cmath>

#include "map_parse_internal.h"

namespace q3::map {
namespace detail {

std::string PrimitiveContext::describe() const {
    return "entity " + std::to_string(entityNum) + ", primitive " + std::to_string(primitiveNum);
}

std::string shown(std::string_view text) {
    constexpr size_t kMaxShown = 48;
    std::string out;
    for (char c : text.substr(0, kMaxShown)) out += static_cast<unsigned char>(c) < ' ' ? ' ' : c;
    if (text.size() > kMaxShown) out += "...";
    return out;
}

static bool isPunctuationToken(const Script& s) {
    if (s.tokenWasQuoted()) return false;
    const std::string& t = s.token();
    return t == "{" || t == "}" || t == "(" || t == ")";
}

void require(Script& s, std::string_view text, const Described& where) {
    if (!s.next(true)) s.fail("unexpected end of file, expected '" + std::string(text) + "' " + where.text());
    if (s.tokenWasQuoted() || s.token() != text)
        s.fail("expected '" + std::string(text) + "' " + where.text() + ", found '" + shown(s.token()) + "'");
}

static double readNumberToken(Script& s, const Described& what, bool sameLine) {
    if (!s.next(!sameLine)) {
        if (sameLine) s.fail("line ends before " + what.text());
        s.fail("unexpected end of file, expected " + what.text());
    }
    double value = 0;
    if (!parseNumber(s.token(), value)) s.fail("expected a number for " + what.text() + ", found '" + shown(s.token()) + "'");
    return value;
}

double readDouble(Script& s, const Described& what, bool sameLine) {
    double value = readNumberToken(s, what, sameLine);
    if (std::fabs(value) > FLT_MAX) s.fail("number out of range for " + what.text() + ": '" + shown(s.token()) + "'");
    return value;
}

float readFloat(Script& s, const Described& what, bool sameLine) { return static_cast<float>(readDouble(s, what, sameLine)); }

int readInt(Script& s, const Described& what, bool sameLine) {
    double value = readNumberToken(s, what, sameLine);
    if (value != std::floor(value) || value < -2147483648.0 || value > 4294967295.0)
        s.fail("expected an integer for " + what.text() + ", found '" + shown(s.token()) + "'");
    if (value > 2147483647.0) return static_cast<int>(static_cast<uint32_t>(value));
    return static_cast<int>(value);
}

std::string readTextureName(Script& s, const Described& where) {
    if (!s.next(true)) s.fail("unexpected end of file, expected a texture name " + where.text());
    if (isPunctuationToken(s) || s.token().empty())
        s.fail("missing texture name " + where.text() + ", found '" + shown(s.token()) + "'");
    return s.token();
}

}  // namespace detail

namespace {

using detail::PrimitiveContext;
using detail::shown;

// Editors sometimes leave spaces at the end of keys or values; q3map2 strips them.
std::string stripTrailingSpace(std::string s) {
    while (!s.empty() && static_cast<unsigned char>(s.back()) <= ' ') s.pop_back();
    return s;
}

// The current token is the primitive's "{".
void parsePrimitive(Script& s, MapEntity& entity, int primitiveNum) {
    const int braceLine = s.line();
    PrimitiveContext ctx{entity.number, primitiveNum};
    if (!s.next(true)) s.fail("unexpected end of file inside " + ctx.describe() + " (missing '}')");
    const std::string& t = s.token();
    const bool bare = !s.tokenWasQuoted();
    if (bare && t == "(") {
        MapBrush brush = detail::parseClassicBrush(s, ctx);
        brush.primitiveNum = primitiveNum;
        brush.line = braceLine;
        entity.brushes.push_back(std::move(brush));
    } else if (bare && t == "}") {
        // An empty brush: nothing to build, but it still takes its primitive number.
        MapBrush brush;
        brush.primitiveNum = primitiveNum;
        brush.line = braceLine;
        entity.brushes.push_back(std::move(brush));
    } else if (bare && equalsNoCase(t, "brushDef")) {
        MapBrush brush = detail::parseBrushDef(s, ctx);
        brush.primitiveNum = primitiveNum;
        brush.line = braceLine;
        detail::require(s, "}", "to close " + ctx.describe());
        entity.brushes.push_back(std::move(brush));
    } else if (bare && (equalsNoCase(t, "patchDef2") || equalsNoCase(t, "patchDef3"))) {
        MapPatch patch = detail::parsePatchDef(s, ctx, equalsNoCase(t, "patchDef3"));
        patch.primitiveNum = primitiveNum;
        patch.line = braceLine;
        detail::require(s, "}", "to close " + ctx.describe());
        entity.patches.push_back(std::move(patch));
    } else {
        s.fail("unknown primitive '" + shown(t) + "' in " + ctx.describe() +
               " (expected a brush face '(', brushDef, patchDef2 or patchDef3)");
    }
}

// The current token is the entity's "{".
MapEntity parseEntity(Script& s, int number) {
    MapEntity entity;
    entity.number = number;
    entity.line = s.line();
    const std::string where = "entity " + std::to_string(number);
    int primitiveNum = 0;
    for (;;) {
        if (!s.next(true)) s.fail("unexpected end of file inside " + where + " opened on line " +
                                  std::to_string(entity.line) + " (missing '}')");
        const bool bare = !s.tokenWasQuoted();
        if (bare && s.token() == "}") break;
        if (bare && s.token() == "{") {
            parsePrimitive(s, entity, primitiveNum++);
            continue;
        }
        if (bare && (s.token() == "(" || s.token() == ")"))
            s.fail("unexpected '" + shown(s.token()) + "' in " + where + " (brush faces must be inside { })");
        std::string key = stripTrailingSpace(s.token());
        if (!s.next(false)) s.fail("key '" + shown(key) + "' of " + where + " has no value on its line");
        if (!s.tokenWasQuoted() && (s.token() == "{" || s.token() == "}"))
            s.fail("key '" + shown(key) + "' of " + where + " has no value");
        entity.pairs.emplace_back(std::move(key), stripTrailingSpace(s.token()));
    }
    return entity;
}

}  // namespace

MapFile parseMap(std::string_view text, const std::string& name) {
    Script s(text, name, true);
    MapFile map;
    map.name = name;
    bool first = true;
    while (s.next(true)) {
        // Doom 3 / Quake 4 editors write "Version N" before the first entity.
        if (first && !s.tokenWasQuoted() && equalsNoCase(s.token(), "Version")) {
            map.version = detail::readInt(s, "the map version", true);
            first = false;
            continue;
        }
        first = false;
        if (s.tokenWasQuoted() || s.token() != "{")
            s.fail("expected '{' to open entity " + std::to_string(map.entities.size()) + ", found '" + shown(s.token()) + "'");
        map.entities.push_back(parseEntity(s, int(map.entities.size())));
    }
    return map;
}

}  // namespace q3::map
