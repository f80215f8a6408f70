// Bezier patches: patchDef2 (Quake 3) and patchDef3 (explicit subdivisions, Doom 3 style).
#include <string>

#include "map_parse_internal.h"

namespace q3::map::detail {
namespace {

int readPatchSize(Script& s, const std::string& what) {
    const int size = readInt(s, what);
    if (size < 3 || size > kMaxPatchSize || (size % 2) == 0)
        s.fail(what + " must be an odd number from 3 to " + std::to_string(kMaxPatchSize) + ", found '" + shown(s.token()) +
               "'");
    return size;
}

}  // namespace

MapPatch parsePatchDef(Script& s, const PrimitiveContext& ctx, bool patchDef3) {
    const std::string where = "of " + std::string(patchDef3 ? "patchDef3" : "patchDef2") + " in " + ctx.describe();
    MapPatch patch;
    patch.patchDef3 = patchDef3;
    require(s, "{", "to open the body " + where);
    patch.texture = readTextureName(s, where);

    require(s, "(", "to open the size line " + where);
    patch.width = readPatchSize(s, "width " + where);
    patch.height = readPatchSize(s, "height " + where);
    if (patchDef3) {
        patch.subdivisions[0] = readInt(s, "horizontal subdivisions " + where);
        patch.subdivisions[1] = readInt(s, "vertical subdivisions " + where);
    }
    patch.contentFlags = readInt(s, "content flags " + where);
    patch.surfaceFlags = readInt(s, "surface flags " + where);
    patch.value = readInt(s, "surface value " + where);
    require(s, ")", "to close the size line " + where);

    patch.control.resize(size_t(patch.width) * patch.height);
    require(s, "(", "to open the control points " + where);
    // The file lists one group per column, each holding that column's rows.
    for (int column = 0; column < patch.width; ++column) {
        const auto columnWhere = [&] { return "column " + std::to_string(column) + " " + where; };
        require(s, "(", [&] { return "to open " + columnWhere(); });
        for (int row = 0; row < patch.height; ++row) {
            const auto what = [&] { return "control point " + std::to_string(row) + " of " + columnWhere(); };
            require(s, "(", [&] { return "to open " + what(); });
            PatchControl& c = patch.control[size_t(row) * patch.width + column];
            c.xyz.x = readFloat(s, [&] { return what() + " x"; });
            c.xyz.y = readFloat(s, [&] { return what() + " y"; });
            c.xyz.z = readFloat(s, [&] { return what() + " z"; });
            c.st[0] = readFloat(s, [&] { return what() + " s"; });
            c.st[1] = readFloat(s, [&] { return what() + " t"; });
            require(s, ")", [&] { return "to close " + what(); });
        }
        require(s, ")", [&] { return "to close " + columnWhere(); });
    }
    require(s, ")", "to close the control points " + where);

    // Brush-primitive editors may append key/value pairs before the closing brace; they carry
    // nothing the compiler uses.
    for (;;) {
        if (!s.next(true)) s.fail("unexpected end of file, expected '}' to close the body " + where);
        if (!s.tokenWasQuoted() && s.token() == "}") break;
        if (!s.tokenWasQuoted() && (s.token() == "{" || s.token() == "(" || s.token() == ")"))
            s.fail("expected '}' to close the body " + where + ", found '" + shown(s.token()) + "'");
        const std::string key = s.token();
        if (!s.next(false)) s.fail("key '" + shown(key) + "' " + where + " has no value on its line");
    }
    return patch;
}

}  // namespace q3::map::detail
