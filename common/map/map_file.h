// The .map source format: entities (ordered key/value pairs) holding brushes and Bezier patches.
//
// Accepted primitives (all may be mixed in one file):
//   classic brush   ( x y z ) ( x y z ) ( x y z ) texture shiftS shiftT rotate scaleS scaleT [contents flags value]
//   Valve 220 face  ( x y z ) ( x y z ) ( x y z ) texture [ ux uy uz offS ] [ vx vy vz offT ] rotate scaleS scaleT [...]
//   brushDef        { ( p ) ( p ) ( p ) ( ( xx xy xz ) ( yx yy yz ) ) texture [contents flags value] }
//   patchDef2       { texture ( w h contents flags value ) ( ( ( x y z s t ) ... ) ... ) }
//   patchDef3       { texture ( w h subdivX subdivY contents flags value ) ( ... ) }
// Editor comments (// entity 0, // brush 0), a leading "Version N" line, CR/LF endings, key/value
// pairs inside brushDef and after patch control points (ignored, as q3map2 does) are accepted. As in
// q3map2, a face's texture numbers and optional flags must be on the face's own line.
// Texture projections are kept in their source form; texture_projection.h turns them into texture
// vectors.
// Every error is a q3::ScriptError "<file>:<line>: <what is wrong>".
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "vec3.h"

namespace q3::map {

// Plane through three points, oriented the way q3map2 does (normal = (c - a) x (b - a), so a brush's
// planes face outwards for editor-written brushes). Computed in double precision.
struct MapPlane {
    double normal[3] = {0, 0, 0};
    double dist = 0;
    Vec3 normalf() const { return {float(normal[0]), float(normal[1]), float(normal[2])}; }
};

// Returns false (and leaves `out` untouched) when the points are collinear or coincident.
bool planeFromPoints(const Vec3& a, const Vec3& b, const Vec3& c, MapPlane& out);

enum class TexProjection {
    Standard,        // shift, rotate, scale (id's original "quake" projection)
    Valve220,        // explicit texture axes with offsets, rotate kept for the editor, scale
    BrushPrimitive,  // 2x3 matrix in the face's own texture plane (brushDef)
};

struct TexStandard {
    float shift[2] = {0, 0};
    float rotate = 0;
    float scale[2] = {0.5f, 0.5f};
};

struct TexValve {
    Vec3 axis[2];              // S and T axes as written
    float offset[2] = {0, 0};  // the fourth number of each [ ] group
    float rotate = 0;
    float scale[2] = {1, 1};
};

struct TexBrushPrimitive {
    float matrix[2][3] = {{1.0f / 128, 0, 0}, {0, 1.0f / 128, 0}};
};

struct BrushFace {
    Vec3 points[3];       // as written
    double exactPoints[3][3] = {};  // the same in double precision, as q3map2 reads them for -bsp
    MapPlane plane;       // from the points; valid only when planeValid
    bool planeValid = false;
    std::string texture;  // as written, without the "textures/" prefix the compiler adds
    TexProjection projection = TexProjection::Standard;
    TexStandard standard;            // when projection == Standard
    TexValve valve;                  // when projection == Valve220
    TexBrushPrimitive primitive;     // when projection == BrushPrimitive
    bool hasFlags = false;  // the optional trailing content/surface/value triple was present
    int contentFlags = 0;
    int surfaceFlags = 0;
    int value = 0;
    int line = 0;
};

struct MapBrush {
    std::vector<BrushFace> faces;
    bool brushPrimitive = false;  // written as brushDef { ... }
    int primitiveNum = 0;         // index among this entity's brushes and patches, in file order
    int line = 0;                 // line of the opening brace
};

struct PatchControl {
    Vec3 xyz;
    float st[2] = {0, 0};
};

struct MapPatch {
    std::string texture;  // as written, without "textures/"
    int width = 0;        // control points per row (odd, 3..kMaxPatchSize)
    int height = 0;       // control point rows (odd, 3..kMaxPatchSize)
    // Row-major: control[row * width + column]. The file lists `width` groups of `height` points;
    // group c holds column c (the same layout q3map2 builds).
    std::vector<PatchControl> control;
    int contentFlags = 0;
    int surfaceFlags = 0;
    int value = 0;
    bool patchDef3 = false;  // explicit subdivisions below are only meaningful then
    int subdivisions[2] = {0, 0};
    int primitiveNum = 0;
    int line = 0;

    const PatchControl& at(int column, int row) const { return control[size_t(row) * width + column]; }
};

constexpr int kMaxPatchSize = 31;  // q3map2 rejects larger control grids

struct MapEntity {
    std::vector<std::pair<std::string, std::string>> pairs;  // file order, duplicates kept
    std::vector<MapBrush> brushes;
    std::vector<MapPatch> patches;
    int number = 0;  // index in the file (0 = worldspawn normally)
    int line = 0;    // line of the opening brace

    // First value of a key (case-insensitive, as the engines compare keys), or nullptr.
    const std::string* find(std::string_view key) const;
    std::string value(std::string_view key, std::string_view fallback = {}) const;
    std::string_view classname() const;
    // "origin" parsed as three numbers; false when absent or malformed.
    bool origin(Vec3& out) const;
    int primitiveCount() const { return int(brushes.size() + patches.size()); }
};

struct MapFile {
    std::string name;                 // file name used in messages
    int version = 0;                  // value of a leading "Version N" line, 0 when absent
    std::vector<MapEntity> entities;  // file order
};

// Parses .map text. `name` is used in error messages ("<name>:<line>: ...").
MapFile parseMap(std::string_view text, const std::string& name);
// Reads and parses a file; FileError when it cannot be read, ScriptError when malformed.
MapFile loadMap(const std::filesystem::path& path);

// q3map2's -light rule: entities whose classname starts with "light" (case-insensitive), in file order.
bool isLightEntity(const MapEntity& entity);
std::vector<const MapEntity*> lightEntities(const MapFile& map);

// The shader name the compiler looks up for a brush face or patch texture ("textures/" + texture).
std::string shaderNameForTexture(std::string_view texture);

}  // namespace q3::map
