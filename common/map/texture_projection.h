// World-to-texture mapping of brush faces, from the projection kept in its source form:
//   Standard        id's axis-aligned projection (the best of six base axes, then rotate, scale, shift)
//   Valve220        explicit axes divided by the scale, plus the offsets
//   BrushPrimitive  the 2x3 matrix applied in the face's own plane basis (texture-size independent)
// The result maps a point to texture coordinates: st[i] = dot(vecs[i].xyz, p) + vecs[i][3].
#pragma once

#include "map_file.h"

namespace q3::map {

struct TextureVecs {
    double vecs[2][4] = {{0, 0, 0, 0}, {0, 0, 0, 0}};

    double s(const Vec3& p) const { return vecs[0][0] * p.x + vecs[0][1] * p.y + vecs[0][2] * p.z + vecs[0][3]; }
    double t(const Vec3& p) const { return vecs[1][0] * p.x + vecs[1][1] * p.y + vecs[1][2] * p.z + vecs[1][3]; }
};

struct TextureImage {
    int width = 0;   // pixel size of the shader's image; must be positive for Standard and Valve220
    int height = 0;
    // Shaders with q3map_globalTexture keep their shifts as written; others have the shift reduced
    // modulo the image size (same mapping, smaller coordinates), as q3map2 does.
    bool globalTexture = false;
    // The size shifts are reduced modulo when it is not the image's (0: the image's): q3map2 reduces
    // them with the face's own shader as it reads the map, and a layer shader of indexed terrain may
    // have another image size.
    int shiftWidth = 0;
    int shiftHeight = 0;
};

// The base axes q3map2 projects a Standard face onto: the first of floor, ceiling, west, east,
// south, north whose normal is closest to `normal` (ties keep the earlier one).
void textureAxisFromPlane(const double normal[3], Vec3& sAxis, Vec3& tAxis);
// The plane basis brush primitives are written in (Radiant's ComputeAxisBase).
void brushPrimitiveAxisBase(const double normal[3], double texS[3], double texT[3]);

// Mapping of `face` on `plane` (normally face.plane, or the snapped plane the -bsp stage chose).
// Throws std::invalid_argument when a Standard or Valve220 face gets a non-positive image size.
TextureVecs textureVectors(const BrushFace& face, const MapPlane& plane, const TextureImage& image);

}  // namespace q3::map
