// Values that flow between the parts of the light stage.
#pragma once

#include "vec3.h"

namespace q3::light {

// Light arriving at a sample point from one light, after occlusion and filtering.
// Colours are in q3map2's float units (255 = full intensity before the colour pipeline).
struct LightContribution {
    Vec3 color;
    Vec3 direction;  // unit vector from the sample towards the light
    int style = 0;   // light style, 0 = always on
};

}  // namespace q3::light
