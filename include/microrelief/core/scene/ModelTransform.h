// The relief as an object in a scene: the model transform M (the paper's own M) that
// takes its object space, where the spec puts the relief over its base, into the world.
// Any invertible affine map: moved, rotated, scaled (unevenly too) or sheared. A ray keeps
// its parameter t through it, so a hit's t and world position are the object-space
// trace's; normals go through the inverse transpose.
#pragma once

#include <array>

#include <glm/glm.hpp>

#include "microrelief/core/scene/Camera.h"

namespace microrelief {

// The largest condition number (largest over smallest scale of the linear part) a model
// may have.
inline constexpr double kMaxModelCondition = 1e12;

class ModelTransform {
public:
    ModelTransform() = default;  // the identity
    // Throws Error(BadInput) when `objectToWorld` is not affine (its last row is not
    // 0, 0, 0, 1), holds a value that is not finite, is singular (not invertible), or is
    // ill-conditioned (its linear part's condition number beyond kMaxModelCondition; the
    // message gives it). How large or small it may scale the relief depends on the map
    // and the camera: core/scene/FloatLimits.h.
    explicit ModelTransform(const glm::dmat4& objectToWorld);
    // A 3 x 4 matrix in rows (--model: 12 numbers, row-major, the last row of the 4 x 4
    // implied): x' = m0 x + m1 y + m2 z + m3, and so on.
    static ModelTransform fromRows(const std::array<double, 12>& rows);
    std::array<double, 12> rows() const;

    const glm::dmat4& objectToWorld() const { return objectToWorld_; }
    const glm::dmat4& worldToObject() const { return worldToObject_; }
    bool isIdentity() const { return objectToWorld_ == glm::dmat4(1.0); }
    // The most and the least the linear part stretches a vector: its largest and smallest
    // singular values (1 and 1 for the identity, exactly).
    double largestScale() const { return largestScale_; }
    double smallestScale() const { return smallestScale_; }

    // The ray in object space, with the same t.
    Ray toObject(const Ray& world) const;
    glm::dvec3 pointToWorld(const glm::dvec3& object) const;
    glm::dvec3 pointToObject(const glm::dvec3& world) const;
    // An object-space normal in the world, unit.
    glm::dvec3 normalToWorld(const glm::dvec3& object) const;

private:
    glm::dmat4 objectToWorld_{1.0};
    glm::dmat4 worldToObject_{1.0};
    double largestScale_ = 1.0, smallestScale_ = 1.0;
};

}  // namespace microrelief
