#include "flag_names.h"

#include <charconv>
#include <cstdio>

namespace q3::json {

namespace {

std::string hex(uint32_t v) {
    char buf[16];
    std::snprintf(buf, sizeof(buf), "0x%08X", v);
    return buf;
}

bool parseHex(const std::string& text, uint32_t& out) {
    if (text.size() < 3 || text[0] != '0' || (text[1] != 'x' && text[1] != 'X')) return false;
    auto r = std::from_chars(text.data() + 2, text.data() + text.size(), out, 16);
    return r.ec == std::errc() && r.ptr == text.data() + text.size();
}

}  // namespace

// Quake 3 content and surface bits (surfaceflags.h of the game code) by surfaceparm name, in a
// fixed order (the first match wins when several names cover the same bits).
const FlagTable& quake3Flags() {
    static const FlagTable table = [] {
        struct Parm {
            const char* name;
            uint32_t content;
            uint32_t surface;
        };
        static const Parm parms[] = {
            {"default", 0x1, 0x0},
            {"origin", 0x1000000, 0x0},
            {"areaportal", 0x8000, 0x0},
            {"trans", 0x20000000, 0x0},
            {"detail", 0x8000000, 0x0},
            {"structural", 0x10000000, 0x0},
            {"hint", 0x0, 0x100},
            {"nodraw", 0x0, 0x80},
            {"alphashadow", 0x0, 0x10000},
            {"lightfilter", 0x0, 0x8000},
            {"nolightmap", 0x0, 0x400},
            {"pointlight", 0x0, 0x800},
            {"nonsolid", 0x0, 0x4000},
            {"trigger", 0x40000000, 0x0},
            {"water", 0x20, 0x0},
            {"slime", 0x10, 0x0},
            {"lava", 0x8, 0x0},
            {"playerclip", 0x10000, 0x0},
            {"monsterclip", 0x20000, 0x0},
            {"nodrop", 0x80000000, 0x0},
            {"clusterportal", 0x100000, 0x0},
            {"donotenter", 0x200000, 0x0},
            {"botclip", 0x400000, 0x0},
            {"fog", 0x40, 0x0},
            {"sky", 0x0, 0x4},
            {"slick", 0x0, 0x2},
            {"noimpact", 0x0, 0x10},
            {"nomarks", 0x0, 0x20},
            {"ladder", 0x0, 0x8},
            {"nodamage", 0x0, 0x1},
            {"metalsteps", 0x0, 0x1000},
            {"flesh", 0x0, 0x40},
            {"nosteps", 0x0, 0x2000},
            {"nodlight", 0x0, 0x20000},
            {"dust", 0x0, 0x40000},
            {"skip", 0x0, 0x200},
        };
        FlagTable t;
        for (const Parm& p : parms) {
            if (p.content) t.content.push_back({p.name, p.content});
            if (p.surface) t.surface.push_back({p.name, p.surface});
        }
        return t;
    }();
    return table;
}

void writeFlags(Writer& out, uint32_t value, const std::vector<FlagName>& names) {
    out.startObject();
    uint32_t remaining = value;
    for (const FlagName& f : names) {
        if (f.bits != 0 && (remaining & f.bits) == f.bits) {
            out.key(f.name);
            out.string(hex(f.bits));
            remaining &= ~f.bits;
        }
    }
    if (remaining != 0) {
        out.key(kUnnamedFlags);
        out.string(hex(remaining));
    }
    out.endObject();
}

uint32_t readFlags(const Value& value, const std::vector<FlagName>& names, const FlagReadOptions& options,
                   const std::string& context) {
    // q3map2 before the named form wrote plain integers; accept those too.
    if (value.kind == Value::Kind::Number) return static_cast<uint32_t>(value.asInt(context));
    value.asObject(context);
    uint32_t result = 0;
    for (size_t i = 0; i < value.keys.size(); ++i) {
        const std::string& name = value.keys[i];
        const Value& member = value.items[i];
        std::string memberContext = context + "." + name;
        uint32_t bits = 0;
        if (!parseHex(member.asString(memberContext), bits))
            member.fail(memberContext, "expected a hexadecimal string such as \"0x00000001\", found \"" + member.text + "\"");
        if (options.useNames && name != kUnnamedFlags) {
            const FlagName* known = nullptr;
            for (const FlagName& f : names)
                if (f.name == name) known = &f;
            if (!known) {
                if (options.skipUnknown) continue;
                member.fail(memberContext, "unknown flag name \"" + name + "\" (use -skipflags to ignore it)");
            }
            bits = known->bits;
        }
        result |= bits;
    }
    return result;
}

}  // namespace q3::json
