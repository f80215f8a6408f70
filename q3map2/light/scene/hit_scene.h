// The nearest-hit view of the shadow-casting world that dirt mapping and floodlight need: they ask
// not only whether a ray is blocked but how far away the blocker is and whether it is sky. Built
// from the same surfaces and rules as TraceScene; surfaces that only filter light (alphashadow,
// lightfilter) do not stop these rays.
#pragma once

#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "trace_scene.h"
#include "vec3.h"

namespace q3::light {

struct RayHit {
    bool hit = false;  // something was met within [tnear, tfar]
    float distance = 0;
    bool sky = false;  // the surface met is a sky surface
};

// Whether a triangle has structural solid right behind it (see HitScene::nearestOpenMany).
using SolidBackedTest = std::function<bool(std::span<const Vec3, 3> triangle)>;

class HitScene {
public:
    // Throws CompileError when Embree cannot be initialised. With `solidBacked`, the triangles it
    // rejects also form a scene of their own for nearestOpenMany.
    HitScene(const std::vector<SceneSurface>& surfaces, const TraceSceneOptions& options,
             const SolidBackedTest& solidBacked = {});
    ~HitScene();
    HitScene(const HitScene&) = delete;
    HitScene& operator=(const HitScene&) = delete;

    // Nearest surface along `direction` (unit) from `from` between tnear and tfar.
    RayHit nearest(Vec3 from, Vec3 direction, float tnear, float tfar) const;
    // The same for many directions from one point (out[i] for directions[i]), traced together as an
    // Embree ray stream; each result equals what nearest() gives for that direction.
    void nearestMany(Vec3 from, std::span<const Vec3> directions, float tnear, float tfar,
                     std::span<RayHit> out) const;
    // nearestMany among the triangles `solidBacked` rejected (all of them without it). For rays whose
    // whole segment a BSP walk found clear of structural solid, these are the only surfaces they can
    // meet, but for a backed face grazed or touched at the very end (a few tenths of a unit).
    void nearestOpenMany(Vec3 from, std::span<const Vec3> directions, float tnear, float tfar,
                         std::span<RayHit> out) const;
    // Whether a sky surface lies along each direction between tnear and tfars[i] (out[i] = 1),
    // whatever lies nearer: a query on the sky surfaces alone, far fewer than the whole world.
    void skyAlongMany(Vec3 from, std::span<const Vec3> directions, float tnear, std::span<const float> tfars,
                      std::span<uint8_t> out) const;
    // The box of every sky triangle: a ray that comes within no such box meets no sky.
    std::span<const Bounds> skyTriangleBoxes() const { return skyTriangleBoxes_; }

private:
    struct EmbreeState;
    std::unique_ptr<EmbreeState> embree_;
    std::vector<uint8_t> skyGeometry_;      // per Embree geometry id: 1 = sky surface
    std::vector<Bounds> skyTriangleBoxes_;
    std::vector<uint8_t> openSkyGeometry_;  // the same for the scene of triangles not backed by solid
};

// Orthonormal (right, up) pair around `normal`, chosen as q3map2's dirt and floodlight code does so
// that ray patterns match: fixed axes for straight up/down normals, else built from world up.
void tangentFrame(Vec3 normal, Vec3& right, Vec3& up);

// q3map2's ordered cone of directions around +z: `azimuthSteps` azimuths from 0, and for each
// `elevationSteps` elevations centred in equal slices of `coneDegrees` (azimuth-major order).
std::vector<Vec3> coneDirections(int azimuthSteps, int elevationSteps, float coneDegrees);

// A cone direction (around +z) turned into the frame of `normal`.
inline Vec3 toFrame(Vec3 local, Vec3 right, Vec3 up, Vec3 normal) {
    return right * local.x + up * local.y + normal * local.z;
}

}  // namespace q3::light
