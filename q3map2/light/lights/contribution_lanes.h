// Light contributions four points at a time, by SSE lanes (light_contribution.cpp): the scalar
// functions' float operations in their order, lane by lane, so that each lane's values are theirs
// to the bit (the build uses no fused multiply-add). Only light_contribution.cpp includes this.
#pragma once

#include <emmintrin.h>

#include <cstdint>

#include "form_factor.h"
#include "light_contribution.h"
#include "lights.h"

namespace q3::light::contribution {

constexpr float kLinearScale = 1.0f / 8000.0f;
constexpr float kMinDistance = 16.0f;  // q3map2 clamps distances to avoid hot spots

// A point light (not a spot) at four points at once, by SSE lanes: the scalar functions' float
// operations in their order, so that each lane's amount, direction and distance are theirs to the
// bit. The masks say which lanes face the light, lie within its reach with a positive distance,
// and carry light above the tolerances; a lane the lanes do not settle (a light on the point, a
// NaN) is left to the scalar code.
struct PointLightLanes {
    alignas(16) float dist[4], dirX[4], dirY[4], dirZ[4], add[4];
    int settled = 0;    // bit per lane: the lanes' answer holds (else the scalar code decides)
    int candidate = 0;  // bit per lane: a contribution (before PVS and occlusion)
};

[[gnu::always_inline]] inline __m128 dot3(__m128 ax, __m128 ay, __m128 az, __m128 bx, __m128 by, __m128 bz) {
    return _mm_add_ps(_mm_add_ps(_mm_mul_ps(ax, bx), _mm_mul_ps(ay, by)), _mm_mul_ps(az, bz));
}

// The light's distance and direction from four points (length and toLight / dist), and the
// distance clampedDistance makes of it.
struct DistanceLanes {
    __m128 dist, dirX, dirY, dirZ, clamped;
};
[[gnu::always_inline]] inline DistanceLanes distanceLanes(const Light& light, __m128 px, __m128 py, __m128 pz) {
    const __m128 tx = _mm_sub_ps(_mm_set1_ps(light.origin.x), px);
    const __m128 ty = _mm_sub_ps(_mm_set1_ps(light.origin.y), py);
    const __m128 tz = _mm_sub_ps(_mm_set1_ps(light.origin.z), pz);
    DistanceLanes d;
    d.dist = _mm_sqrt_ps(dot3(tx, ty, tz, tx, ty, tz));
    d.dirX = _mm_div_ps(tx, d.dist), d.dirY = _mm_div_ps(ty, d.dist), d.dirZ = _mm_div_ps(tz, d.dist);
    const __m128 extra = _mm_set1_ps(light.extraDist);
    d.clamped = _mm_max_ps(_mm_sqrt_ps(_mm_add_ps(_mm_mul_ps(d.dist, d.dist), _mm_mul_ps(extra, extra))),
                           _mm_set1_ps(kMinDistance));
    return d;
}

// The lanes' verdicts and values: `beyond` the lanes out of reach, `ordered` those free of NaNs.
[[gnu::always_inline]] inline void settleLanes(const Light& light, bool fast, const DistanceLanes& d, __m128 add,
                                               __m128 beyond, __m128 ordered, PointLightLanes& lanes) {
    const __m128 zero = _mm_setzero_ps();
    __m128 above = _mm_cmpnle_ps(add, zero);
    if (fast) above = _mm_and_ps(above, _mm_cmpnle_ps(add, _mm_set1_ps(light.falloffTolerance)));
    const __m128 positive = _mm_cmpgt_ps(d.dist, zero);
    lanes.settled = _mm_movemask_ps(_mm_or_ps(beyond, _mm_and_ps(positive, ordered)));
    lanes.candidate = _mm_movemask_ps(_mm_andnot_ps(beyond, _mm_and_ps(positive, above)));
    _mm_store_ps(lanes.dist, d.dist);
    _mm_store_ps(lanes.dirX, d.dirX);
    _mm_store_ps(lanes.dirY, d.dirY);
    _mm_store_ps(lanes.dirZ, d.dirZ);
    _mm_store_ps(lanes.add, add);
}

// Four sample points as lanes: origins, normals, two-sidedness (all bits), and which lanes face
// `lightOrigin` (lightToSamplesOf's test: behind a one-sided surface when dot(light, n) - dot(p, n)
// < 0).
struct SampleLanes {
    __m128 px, py, pz, nx, ny, nz, twoSided, facing;
};
[[gnu::always_inline]] inline SampleLanes sampleLanes(const SamplePoint* const* samples, Vec3 lightOrigin) {
    alignas(16) float px[4], py[4], pz[4], nx[4], ny[4], nz[4];
    alignas(16) uint32_t twoSided[4];
    for (int l = 0; l < 4; ++l) {
        const SamplePoint& s = *samples[l];
        px[l] = s.origin.x, py[l] = s.origin.y, pz[l] = s.origin.z;
        nx[l] = s.normal.x, ny[l] = s.normal.y, nz[l] = s.normal.z;
        twoSided[l] = s.twoSided ? ~0u : 0u;
    }
    SampleLanes sl;
    sl.px = _mm_load_ps(px), sl.py = _mm_load_ps(py), sl.pz = _mm_load_ps(pz);
    sl.nx = _mm_load_ps(nx), sl.ny = _mm_load_ps(ny), sl.nz = _mm_load_ps(nz);
    sl.twoSided = _mm_castsi128_ps(_mm_load_si128(reinterpret_cast<const __m128i*>(twoSided)));
    const __m128 lx = _mm_set1_ps(lightOrigin.x), ly = _mm_set1_ps(lightOrigin.y), lz = _mm_set1_ps(lightOrigin.z);
    const __m128 behind = _mm_cmplt_ps(
        _mm_sub_ps(dot3(lx, ly, lz, sl.nx, sl.ny, sl.nz), dot3(sl.px, sl.py, sl.pz, sl.nx, sl.ny, sl.nz)), _mm_setzero_ps());
    sl.facing = _mm_or_ps(sl.twoSided, _mm_andnot_ps(behind, _mm_castsi128_ps(_mm_set1_epi32(-1))));
    return sl;
}

// pointLightAdd at four sample points.
[[gnu::always_inline]] inline void pointLightLanes(const Light& light, const ContributionSettings& settings,
                                                   float envelope, const SamplePoint* const* samples,
                                                   PointLightLanes& lanes) {
    const SampleLanes sl = sampleLanes(samples, light.origin);
    const __m128 Px = sl.px, Py = sl.py, Pz = sl.pz, Nx = sl.nx, Ny = sl.ny, Nz = sl.nz, both = sl.twoSided;
    const __m128 zero = _mm_setzero_ps(), one = _mm_set1_ps(1.0f);

    const DistanceLanes d = distanceLanes(light, Px, Py, Pz);
    const __m128 beyond = _mm_cmpge_ps(d.dist, _mm_set1_ps(envelope));  // dist >= envelope: no light
    const __m128 incidence = dot3(Nx, Ny, Nz, d.dirX, d.dirY, d.dirZ);
    __m128 angle = one;
    if (light.angleAttenuation) {
        angle = incidence;
        const __m128 flip = _mm_and_ps(both, _mm_cmplt_ps(angle, zero));
        angle = _mm_or_ps(_mm_and_ps(flip, _mm_sub_ps(zero, angle)), _mm_andnot_ps(flip, angle));
        if (settings.lightAngleHL) {
            const __m128 half = _mm_set1_ps(0.5f);
            __m128 hl = _mm_add_ps(_mm_mul_ps(_mm_min_ps(angle, one), half), half);
            hl = _mm_mul_ps(hl, hl);
            angle = _mm_and_ps(_mm_cmpgt_ps(angle, _mm_set1_ps(0.001f)), hl);
        }
    }
    if (light.angleScale != 0) angle = _mm_min_ps(_mm_div_ps(angle, _mm_set1_ps(light.angleScale)), one);
    const __m128 photons = _mm_set1_ps(light.photons);
    const __m128 add =
        light.linear
            ? _mm_max_ps(_mm_sub_ps(_mm_mul_ps(_mm_mul_ps(angle, photons), _mm_set1_ps(kLinearScale)),
                                    _mm_mul_ps(d.clamped, _mm_set1_ps(light.fade))),
                         zero)
            : _mm_max_ps(_mm_mul_ps(_mm_div_ps(photons, _mm_mul_ps(d.clamped, d.clamped)), angle), zero);
    // std::min / std::max keep a NaN where the SSE forms drop it: lanes with one go to the scalar code.
    const __m128 ordered = _mm_and_ps(_mm_cmpord_ps(incidence, add), _mm_cmpord_ps(d.clamped, angle));
    settleLanes(light, light.fast || settings.forceFast, d, add, beyond, ordered, lanes);
    // A lane facing away is settled (dark) whatever its values.
    const int facing = _mm_movemask_ps(sl.facing);
    lanes.settled |= ~facing & 0xF;
    lanes.candidate &= facing;
}

// surelyBelowFastTolerance at four points (px, py, pz) with normals (nx, ny, nz): the lanes where
// formFactorUpperBound, as form_factor.h takes it, keeps the light at or below the -fast tolerance.
[[gnu::always_inline]] inline __m128 surelyBelowFastToleranceLanes(const Light& light, const LightingEnv& env,
                                                                    __m128 Qx, __m128 Qy, __m128 Qz, __m128 Nx,
                                                                    __m128 Ny, __m128 Nz) {
    const EmitterBounds& b = light.emitter;
    const __m128 zero = _mm_setzero_ps(), one = _mm_set1_ps(1.0f);
    if (!(light.fast || env.settings.forceFast) || !(light.add > 0) || b.radius < 0) return zero;
    const __m128 Q[3] = {Qx, Qy, Qz}, N[3] = {Nx, Ny, Nz};
    __m128 lo = zero, hi = zero, nearest[3];
    for (int k = 0; k < 3; ++k) {
        const __m128 mins = _mm_set1_ps(b.box.mins[k]), maxs = _mm_set1_ps(b.box.maxs[k]);
        nearest[k] = _mm_sub_ps(_mm_min_ps(_mm_max_ps(Q[k], mins), maxs), Q[k]);
        const __m128 a = _mm_mul_ps(N[k], _mm_sub_ps(mins, Q[k])), c = _mm_mul_ps(N[k], _mm_sub_ps(maxs, Q[k]));
        lo = _mm_add_ps(lo, _mm_min_ps(a, c));
        hi = _mm_add_ps(hi, _mm_max_ps(a, c));
    }
    const __m128 absMask = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff));
    const __m128 reach = _mm_max_ps(_mm_and_ps(lo, absMask), _mm_and_ps(hi, absMask));
    const __m128 dist = _mm_sqrt_ps(dot3(nearest[0], nearest[1], nearest[2], nearest[0], nearest[1], nearest[2]));
    const __m128 receiver = _mm_min_ps(_mm_div_ps(reach, dist), one);
    __m128 emitter = one;
    if (b.flat) {
        const __m128 cx = _mm_sub_ps(_mm_set1_ps(b.center.x), Qx), cy = _mm_sub_ps(_mm_set1_ps(b.center.y), Qy),
                     cz = _mm_sub_ps(_mm_set1_ps(b.center.z), Qz);
        const __m128 offPlane = _mm_and_ps(
            dot3(cx, cy, cz, _mm_set1_ps(b.planeNormal.x), _mm_set1_ps(b.planeNormal.y), _mm_set1_ps(b.planeNormal.z)),
            absMask);
        emitter = _mm_min_ps(_mm_div_ps(_mm_add_ps(offPlane, _mm_set1_ps(b.flatness)), dist), one);
    }
    const __m128 bound = _mm_div_ps(_mm_mul_ps(_mm_mul_ps(_mm_set1_ps(b.area), receiver), emitter),
                                    _mm_mul_ps(_mm_mul_ps(_mm_set1_ps(kPi), dist), dist));
    const __m128 scaled = _mm_add_ps(_mm_mul_ps(bound, _mm_set1_ps(1.02f)), _mm_set1_ps(1e-5f));
    // Only where the bound is finite: closer than one unit it is unbounded.
    return _mm_and_ps(_mm_cmpgt_ps(dist, one),
                      _mm_cmple_ps(_mm_mul_ps(scaled, _mm_set1_ps(light.add)), _mm_set1_ps(light.falloffTolerance)));
}

// Points within 8 units of the emitter's plane (`d` from it) pushed to 8 in front of it, as
// areaLightAdd does: p + normal * (8 - d).
[[gnu::always_inline]] inline void pushOffEmitter(const Light& light, __m128 d, __m128 Px, __m128 Py, __m128 Pz,
                                                  __m128& Qx, __m128& Qy, __m128& Qz) {
    const __m128 pushes = _mm_and_ps(_mm_cmpgt_ps(d, _mm_set1_ps(-8.0f)), _mm_cmplt_ps(d, _mm_set1_ps(8.0f)));
    const __m128 by = _mm_sub_ps(_mm_set1_ps(8.0f), d);
    const __m128 push[3] = {_mm_mul_ps(_mm_set1_ps(light.normal.x), by), _mm_mul_ps(_mm_set1_ps(light.normal.y), by),
                            _mm_mul_ps(_mm_set1_ps(light.normal.z), by)};
    Qx = _mm_or_ps(_mm_and_ps(pushes, _mm_add_ps(Px, push[0])), _mm_andnot_ps(pushes, Px));
    Qy = _mm_or_ps(_mm_and_ps(pushes, _mm_add_ps(Py, push[1])), _mm_andnot_ps(pushes, Py));
    Qz = _mm_or_ps(_mm_and_ps(pushes, _mm_add_ps(Pz, push[2])), _mm_andnot_ps(pushes, Pz));
}

// An area light at four sample points without -faster: areaLightAdd up to its exact form factor
// (the facing test, the emitter plane's tests, the push off it, the distance, the direction and
// the -fast bound) by SSE lanes, in its float operations and order. `candidate` marks the lanes
// left for the form factor (areaLightAddFromFactor), `settled` those the lanes decide.
struct AreaLightLanes {
    FormFactorPoints pushed;  // the pushed points, with the normals their form factors take
    alignas(16) float dist[4], dirX[4], dirY[4], dirZ[4];
    alignas(16) float factor[4];  // the form factors, once the lanes lit after the PVS ask for them
    int candidate = 0;
    int settled = 0;
};

// The area lanes' verdicts (`keep`: past every test, `open`: a direction to take) and values.
// `Nx`, `Ny`, `Nz`: the normals the form factors take.
[[gnu::always_inline]] inline void storeAreaLanes(__m128 keep, __m128 open, __m128 Qx, __m128 Qy, __m128 Qz,
                                                  __m128 Nx, __m128 Ny, __m128 Nz, const DistanceLanes& dl,
                                                  AreaLightLanes& lanes) {
    const __m128 all = _mm_castsi128_ps(_mm_set1_epi32(-1));
    // A lane that is not kept is settled whatever its values; a kept one needs a direction.
    lanes.settled = _mm_movemask_ps(_mm_or_ps(_mm_andnot_ps(keep, all), open));
    lanes.candidate = _mm_movemask_ps(_mm_and_ps(keep, open));
    _mm_store_ps(lanes.pushed.x, Qx);
    _mm_store_ps(lanes.pushed.y, Qy);
    _mm_store_ps(lanes.pushed.z, Qz);
    _mm_store_ps(lanes.pushed.nx, Nx);
    _mm_store_ps(lanes.pushed.ny, Ny);
    _mm_store_ps(lanes.pushed.nz, Nz);
    _mm_store_ps(lanes.dist, dl.dist);
    _mm_store_ps(lanes.dirX, dl.dirX);
    _mm_store_ps(lanes.dirY, dl.dirY);
    _mm_store_ps(lanes.dirZ, dl.dirZ);
}

[[gnu::always_inline]] inline void areaLightLanes(const Light& light, const LightingEnv& env, float envelope,
                                                  const SamplePoint* const* samples, AreaLightLanes& lanes) {
    const SampleLanes sl = sampleLanes(samples, light.origin);
    const __m128 Px = sl.px, Py = sl.py, Pz = sl.pz, Nx = sl.nx, Ny = sl.ny, Nz = sl.nz;
    const __m128 zero = _mm_setzero_ps();
    const __m128 Ex = _mm_set1_ps(light.normal.x), Ey = _mm_set1_ps(light.normal.y), Ez = _mm_set1_ps(light.normal.z);
    // lightToSamplesOf's facing test, then the emitter plane's.
    __m128 keep = sl.facing;
    const __m128 d = _mm_sub_ps(dot3(Px, Py, Pz, Ex, Ey, Ez), _mm_set1_ps(light.planeDist));
    const __m128 near3 = _mm_cmplt_ps(d, _mm_set1_ps(3.0f));
    if (!light.twoSided) keep = _mm_andnot_ps(_mm_and_ps(near3, _mm_cmplt_ps(d, _mm_set1_ps(-1.0f))), keep);
    const __m128 coplanar = _mm_and_ps(_mm_cmpgt_ps(d, _mm_set1_ps(-3.0f)),
                                       _mm_cmpgt_ps(dot3(Nx, Ny, Nz, Ex, Ey, Ez), _mm_set1_ps(0.9f)));
    keep = _mm_andnot_ps(_mm_and_ps(near3, coplanar), keep);
    // The push off the emitter's plane.
    __m128 Qx, Qy, Qz;
    pushOffEmitter(light, d, Px, Py, Pz, Qx, Qy, Qz);
    const DistanceLanes dl = distanceLanes(light, Px, Py, Pz);
    keep = _mm_andnot_ps(_mm_cmpge_ps(dl.dist, _mm_set1_ps(envelope)), keep);
    const __m128 positive = _mm_cmpgt_ps(dl.dist, zero);
    // A lane at the emitter's origin (no direction) or with a NaN goes to the scalar code.
    const __m128 ordered = _mm_and_ps(_mm_and_ps(_mm_cmpord_ps(d, dl.dirX), _mm_cmpord_ps(dl.dirY, dl.dirZ)),
                                      _mm_and_ps(_mm_cmpord_ps(Nx, Ny), _mm_cmpord_ps(Nz, Nz)));
    const __m128 open = _mm_and_ps(positive, ordered);
    // surelyBelowFastTolerance at the pushed point.
    keep = _mm_andnot_ps(surelyBelowFastToleranceLanes(light, env, Qx, Qy, Qz, Nx, Ny, Nz), keep);
    storeAreaLanes(keep, open, Qx, Qy, Qz, Nx, Ny, Nz, dl, lanes);
}

// Four grid points as lanes of x, y and z.
struct GridPointLanes {
    __m128 x, y, z;
};
[[gnu::always_inline]] inline GridPointLanes gridPointLanes(const Vec3* const* origins) {
    alignas(16) float x[4], y[4], z[4];
    for (int l = 0; l < 4; ++l) x[l] = origins[l]->x, y[l] = origins[l]->y, z[l] = origins[l]->z;
    return {_mm_load_ps(x), _mm_load_ps(y), _mm_load_ps(z)};
}

// lightToGridPointsOf's area light without -faster (areaLightAtGridPoint up to its exact form
// factor, the grid point's normal being its direction to the light) at four grid points.
[[gnu::always_inline]] inline void areaLightGridLanes(const Light& light, const LightingEnv& env, float envelope,
                                                      const Vec3* const* origins, AreaLightLanes& lanes) {
    const auto [Px, Py, Pz] = gridPointLanes(origins);
    const __m128 zero = _mm_setzero_ps(), all = _mm_castsi128_ps(_mm_set1_epi32(-1));
    const __m128 Ex = _mm_set1_ps(light.normal.x), Ey = _mm_set1_ps(light.normal.y), Ez = _mm_set1_ps(light.normal.z);
    const DistanceLanes dl = distanceLanes(light, Px, Py, Pz);
    __m128 keep = _mm_andnot_ps(_mm_cmpgt_ps(dl.dist, _mm_set1_ps(envelope)), all);  // dist > envelope: none
    const __m128 d = _mm_sub_ps(dot3(Px, Py, Pz, Ex, Ey, Ez), _mm_set1_ps(light.planeDist));
    if (!light.twoSided) keep = _mm_andnot_ps(_mm_cmplt_ps(d, _mm_set1_ps(-1.0f)), keep);
    __m128 Qx, Qy, Qz;
    pushOffEmitter(light, d, Px, Py, Pz, Qx, Qy, Qz);
    const __m128 positive = _mm_cmpgt_ps(dl.dist, zero);
    const __m128 ordered = _mm_and_ps(_mm_cmpord_ps(d, dl.dirX), _mm_cmpord_ps(dl.dirY, dl.dirZ));
    const __m128 open = _mm_and_ps(positive, ordered);
    keep = _mm_andnot_ps(surelyBelowFastToleranceLanes(light, env, Qx, Qy, Qz, dl.dirX, dl.dirY, dl.dirZ), keep);
    storeAreaLanes(keep, open, Qx, Qy, Qz, dl.dirX, dl.dirY, dl.dirZ, dl, lanes);
}

// lightToGridPointsOf's point light (pointLightAtGridPoint) at four grid points.
[[gnu::always_inline]] inline void pointLightGridLanes(const Light& light, float envelope, bool fast,
                                                       const Vec3* const* origins, PointLightLanes& lanes) {
    const auto [Px, Py, Pz] = gridPointLanes(origins);
    const __m128 zero = _mm_setzero_ps();
    const DistanceLanes d = distanceLanes(light, Px, Py, Pz);
    const __m128 beyond = _mm_cmpgt_ps(d.dist, _mm_set1_ps(envelope));  // dist > envelope: no light
    const __m128 add = light.linear ? _mm_max_ps(_mm_sub_ps(_mm_set1_ps(light.photons * kLinearScale),
                                                            _mm_mul_ps(d.clamped, _mm_set1_ps(light.fade))),
                                                 zero)
                                    : _mm_div_ps(_mm_set1_ps(light.photons), _mm_mul_ps(d.clamped, d.clamped));
    const __m128 ordered = _mm_and_ps(_mm_cmpord_ps(d.dirX, d.dirY), _mm_cmpord_ps(d.dirZ, d.clamped));
    settleLanes(light, fast, d, add, beyond, ordered, lanes);
}

}  // namespace q3::light::contribution
