// Filling Embree rays for the light stage's scenes.
#pragma once

#include <embree3/rtcore.h>

#include <cstdint>

#include "vec3.h"

namespace q3::light {

// Fills `ray` in place: building a whole ray elsewhere and copying it in stores it in small pieces
// and reloads it in large ones, which stalls the batch loops on store forwarding.
inline void setRay(RTCRay& ray, Vec3 from, Vec3 direction, float tnear, float tfar, unsigned id = 0,
                   uint32_t mask = 0xFFFFFFFFu) {
    ray.org_x = from.x;
    ray.org_y = from.y;
    ray.org_z = from.z;
    ray.tnear = tnear;
    ray.dir_x = direction.x;
    ray.dir_y = direction.y;
    ray.dir_z = direction.z;
    ray.time = 0;
    ray.tfar = tfar;
    ray.mask = mask;
    ray.id = id;
    ray.flags = 0;
}

// setRay, with the hit marked empty as Embree expects it before an intersection query.
inline void setRayHit(RTCRayHit& rh, Vec3 from, Vec3 direction, float tnear, float tfar, unsigned id = 0,
                      uint32_t mask = 0xFFFFFFFFu) {
    setRay(rh.ray, from, direction, tnear, tfar, id, mask);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
}

}  // namespace q3::light
