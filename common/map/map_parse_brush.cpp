// Brush faces: the classic Quake 3 form (with the Valve 220 variant) and brushDef brush primitives.
#include <string>

#include "map_parse_internal.h"

namespace q3::map::detail {
namespace {

std::string faceWhere(const PrimitiveContext& ctx, size_t faceIndex) {
    return "in face " + std::to_string(faceIndex) + " of " + ctx.describe();
}

// The three plane points; the current token is the first "(" when `firstOpenRead` is true.
void readPlanePoints(Script& s, BrushFace& face, const Described& where, bool firstOpenRead) {
    face.line = s.line();
    for (int i = 0; i < 3; ++i) {
        const auto what = [&] { return "plane point " + std::to_string(i + 1) + " " + where.text(); };
        if (i > 0 || !firstOpenRead) require(s, "(", [&] { return "to open " + what(); });
        static const char* const axes[3] = {" x", " y", " z"};
        for (int k = 0; k < 3; ++k) {
            face.exactPoints[i][k] = readDouble(s, [&] { return what() + axes[k]; });
            face.points[i][k] = static_cast<float>(face.exactPoints[i][k]);
        }
        require(s, ")", [&] { return "to close " + what(); });
    }
    face.planeValid = planeFromPoints(face.points[0], face.points[1], face.points[2], face.plane);
}

// Optional "contents flags value" at the end of the face's line.
void readOptionalFlags(Script& s, BrushFace& face, const Described& where) {
    if (!s.tokenAvailableOnLine()) return;
    face.hasFlags = true;
    face.contentFlags = readInt(s, [&] { return "content flags " + where.text(); }, true);
    face.surfaceFlags = readInt(s, [&] { return "surface flags " + where.text(); }, true);
    face.value = readInt(s, [&] { return "surface value " + where.text(); }, true);
}

// Everything after the texture name of a classic face.
void readClassicProjection(Script& s, BrushFace& face, const Described& where) {
    if (!s.next(false)) s.fail("line ends before the texture shift " + where.text());
    if (!s.tokenWasQuoted() && s.token() == "[") {
        // Valve 220: [ ux uy uz offset ] [ vx vy vz offset ] rotate scaleS scaleT
        face.projection = TexProjection::Valve220;
        for (int axis = 0; axis < 2; ++axis) {
            const auto what = [&] { return std::string(axis == 0 ? "S" : "T") + " texture axis " + where.text(); };
            if (axis == 1) require(s, "[", [&] { return "to open the " + what(); });
            face.valve.axis[axis].x = readFloat(s, what);
            face.valve.axis[axis].y = readFloat(s, what);
            face.valve.axis[axis].z = readFloat(s, what);
            face.valve.offset[axis] = readFloat(s, [&] { return what() + " offset"; });
            require(s, "]", [&] { return "to close the " + what(); });
        }
        face.valve.rotate = readFloat(s, [&] { return "texture rotation " + where.text(); }, true);
        face.valve.scale[0] = readFloat(s, [&] { return "texture scale S " + where.text(); }, true);
        face.valve.scale[1] = readFloat(s, [&] { return "texture scale T " + where.text(); }, true);
        return;
    }
    double shift = 0;
    if (!parseNumber(s.token(), shift))
        s.fail("expected a number for the texture shift S " + where.text() + ", found '" + shown(s.token()) + "'");
    face.projection = TexProjection::Standard;
    face.standard.shift[0] = static_cast<float>(shift);
    face.standard.shift[1] = readFloat(s, [&] { return "texture shift T " + where.text(); }, true);
    face.standard.rotate = readFloat(s, [&] { return "texture rotation " + where.text(); }, true);
    face.standard.scale[0] = readFloat(s, [&] { return "texture scale S " + where.text(); }, true);
    face.standard.scale[1] = readFloat(s, [&] { return "texture scale T " + where.text(); }, true);
}

}  // namespace

MapBrush parseClassicBrush(Script& s, const PrimitiveContext& ctx) {
    MapBrush brush;
    for (;;) {
        const size_t faceIndex = brush.faces.size();
        const auto where = [&] { return faceWhere(ctx, faceIndex); };
        BrushFace face;
        readPlanePoints(s, face, where, true);
        face.texture = readTextureName(s, where);
        readClassicProjection(s, face, where);
        readOptionalFlags(s, face, where);
        brush.faces.push_back(std::move(face));

        if (!s.next(true)) s.fail("unexpected end of file inside " + ctx.describe() + " (missing '}')");
        if (!s.tokenWasQuoted() && s.token() == "}") break;
        if (s.tokenWasQuoted() || s.token() != "(")
            s.fail("expected '(' to start a face or '}' to close " + ctx.describe() + ", found '" + shown(s.token()) + "'");
    }
    return brush;
}

MapBrush parseBrushDef(Script& s, const PrimitiveContext& ctx) {
    MapBrush brush;
    brush.brushPrimitive = true;
    require(s, "{", "after brushDef in " + ctx.describe());
    for (;;) {
        if (!s.next(true)) s.fail("unexpected end of file inside brushDef of " + ctx.describe() + " (missing '}')");
        if (!s.tokenWasQuoted() && s.token() == "}") break;
        if (s.tokenWasQuoted() || s.token() != "(") {
            // Editors may store brush key/value pairs before the faces; the compiler ignores them.
            if (!s.tokenWasQuoted() && (s.token() == "{" || s.token() == ")"))
                s.fail("expected '(' to start a face or '}' to close brushDef of " + ctx.describe() + ", found '" +
                       shown(s.token()) + "'");
            const std::string key = s.token();
            if (!s.next(false))
                s.fail("expected '(' to start a face or '}' to close brushDef of " + ctx.describe() + ", found '" +
                       shown(key) + "'");
            continue;
        }
        const size_t faceIndex = brush.faces.size();
        const auto where = [&] { return faceWhere(ctx, faceIndex); };
        BrushFace face;
        readPlanePoints(s, face, where, true);
        face.projection = TexProjection::BrushPrimitive;
        require(s, "(", [&] { return "to open the texture matrix " + where(); });
        for (int row = 0; row < 2; ++row) {
            const auto rowWhat = [&] { return "texture matrix row " + std::to_string(row + 1) + " " + where(); };
            require(s, "(", [&] { return "to open " + rowWhat(); });
            for (int col = 0; col < 3; ++col)
                face.primitive.matrix[row][col] = readFloat(s, [&] { return "texture matrix " + where(); });
            require(s, ")", [&] { return "to close " + rowWhat(); });
        }
        require(s, ")", [&] { return "to close the texture matrix " + where(); });
        face.texture = readTextureName(s, where);
        readOptionalFlags(s, face, where);
        brush.faces.push_back(std::move(face));
    }
    return brush;
}

}  // namespace q3::map::detail
