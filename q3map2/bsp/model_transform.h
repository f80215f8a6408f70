// The placement of a misc_model (q3map2 model.cpp AddTriangleModels, InsertModel): origin, euler
// angles and scale combined into one 4x4 matrix of floats, and the matrix for normals (the
// transpose of its affine inverse), with q3map2's arithmetic step for step (float products, a
// determinant and inverse scaled in doubles), so that transformed vertices and normals carry the
// same bits as q3map2's.
#pragma once

#include "dvec3.h"
#include "vec3.h"

namespace q3::bspstage {

class ModelTransform {
public:
    ModelTransform();  // identity

    // Translation, then rotations about X (roll), Y (pitch), Z (yaw) in degrees, then scale.
    static ModelTransform place(const Vec3& origin, float pitch, float yaw, float roll, const Vec3& scale);
    // A _skybox room into the sky: moved from `origin` to the world origin, then turned and scaled.
    static ModelTransform skybox(const Vec3& origin, float pitch, float yaw, float roll, const Vec3& scale);

    Vec3 point(const Vec3& p) const;
    // The same product in doubles (the float matrix times a double point), as autoclip takes it.
    DVec3 pointInDoubles(const Vec3& p) const;
    Vec3 normal(const Vec3& n) const;  // by the inverse transpose, not normalised
    bool leftHanded() const;           // mirrors: triangle corners must be swapped

private:
    // Column-major, as q3map2's: [0..2] the image of X, [12..14] the translation.
    float m_[16];
    float n_[16];  // the normal matrix
};

}  // namespace q3::bspstage
