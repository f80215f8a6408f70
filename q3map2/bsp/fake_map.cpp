#include "fake_map.h"

#include <cstdio>

namespace q3::bspstage {

std::string fakeMapText(const std::vector<Brush>& worldBrushes, const PlaneSet& planes) {
    std::string text = "{\n\"classname\" \"worldspawn\"\n";
    char line[256];
    for (const Brush& brush : worldBrushes) {
        text += "{\n";
        for (const BrushSide& side : brush.sides) {
            const Winding w = baseWindingForPlane(planes[side.planeNum].plane);
            for (int i = 0; i < 3; ++i) {
                // q3map2 casts the float coordinates to int (towards zero).
                const Vec3 p = w[size_t(i)].toFloat();
                std::snprintf(line, sizeof line, "( %i %i %i ) ", int(p.x), int(p.y), int(p.z));
                text += line;
            }
            text += "notexture 0 0 0 1 1\n";
        }
        text += "}\n";
    }
    text += "}\n";
    return text;
}

}  // namespace q3::bspstage
