// Shader-indexed terrain (q3map2 LoadEntityIndexMap, GetShaderIndexForPoint): an entity with an
// _indexmap image, a layer count and a base shader name re-shades the faces and patches of its
// q3map_indexed / q3map_terrain shaders. Each vertex takes the layer of the image pixel above it
// (the image spans the entity's x/y bounds, its top row at the largest y) and that layer's height
// offset; a surface takes the shader "textures/<base>_<n>" when all its vertices share layer n, else
// "textures/<base>_<lowest>to<highest>", and its vertices of the highest layer are opaque, the
// others transparent, so that the two layers blend.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "vec3.h"

namespace q3 {
class Log;
class Vfs;
namespace map {
struct MapFile;
}
}  // namespace q3

namespace q3::bspstage {

struct LoadedMap;

// The most layers an index map can name: a pixel holds one byte and offsets are kept for 256.
inline constexpr int kMaxIndexMapLayers = 256;

// One surface's vertices laid over an index map.
struct LayeredVertices {
    std::vector<uint8_t> alpha;   // per vertex: 255 on the surface's highest layer, else 0
    std::vector<float> zOffset;   // per vertex: its layer's height offset
    int lowest = 0;
    int highest = 0;
};

struct IndexMap {
    std::string file;        // as the entity names it
    std::string baseShader;  // _shader / shader, without "textures/"
    int layers = 1;
    int width = 0;
    int height = 0;
    std::vector<uint8_t> pixels;              // layer per pixel, rows top to bottom
    std::array<float, kMaxIndexMapLayers> offsets{};  // _offsets / offsets, by layer
    Bounds bounds;           // the entity's brushes and patch control points, or its min / max keys

    // The layer of the pixel `point` falls on (points outside the bounds take the edge pixel).
    uint8_t layerAt(const Vec3& point) const;
    LayeredVertices layer(std::span<const Vec3> points) const;
    // "textures/<base>_<lowest>" or "textures/<base>_<lowest>to<highest>".
    std::string layerShaderName(const LayeredVertices& v) const;
};

// Index maps by .map entity number (nullptr for entities without one). A .tga or .png gives the
// layer of a pixel from its red channel, a .pcx or .bmp (8-bit) from its palette index. A missing
// or unreadable image stops the compile (as in q3map2); missing or bad keys, another image format
// (.lbm) and an image under 2x2 pixels are warnings naming the entity, which is left unlayered.
std::vector<std::unique_ptr<IndexMap>> loadIndexMaps(const map::MapFile& file, const LoadedMap& map, const Vfs* vfs,
                                                     Log& log);

}  // namespace q3::bspstage
