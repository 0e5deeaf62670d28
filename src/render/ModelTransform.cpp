#include "microrelief/render/ModelTransform.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "microrelief/core/Error.h"

namespace microrelief {

namespace {

// The largest and smallest singular values of a 3 x 3 matrix, from the eigenvalues of
// A^T A (symmetric, positive semi-definite) by the closed form for 3 x 3 symmetric ones.
std::pair<double, double> singularRange(const glm::dmat3& a) {
    const glm::dmat3 m = glm::transpose(a) * a;
    const double p1 = m[0][1] * m[0][1] + m[0][2] * m[0][2] + m[1][2] * m[1][2];
    const double q = (m[0][0] + m[1][1] + m[2][2]) / 3.0;
    if (p1 == 0.0) {
        const double lo = std::min({m[0][0], m[1][1], m[2][2]});
        const double hi = std::max({m[0][0], m[1][1], m[2][2]});
        return {std::sqrt(std::max(hi, 0.0)), std::sqrt(std::max(lo, 0.0))};
    }
    const double p2 = (m[0][0] - q) * (m[0][0] - q) + (m[1][1] - q) * (m[1][1] - q) +
                      (m[2][2] - q) * (m[2][2] - q) + 2.0 * p1;
    const double p = std::sqrt(p2 / 6.0);
    const glm::dmat3 b = (m - q * glm::dmat3(1.0)) / p;
    const double r = std::clamp(glm::determinant(b) / 2.0, -1.0, 1.0);
    const double phi = std::acos(r) / 3.0;
    const double e1 = q + 2.0 * p * std::cos(phi);
    const double e3 = q + 2.0 * p * std::cos(phi + 2.0 * 3.14159265358979323846 / 3.0);
    return {std::sqrt(std::max(e1, 0.0)), std::sqrt(std::max(e3, 0.0))};
}

}  // namespace

ModelTransform::ModelTransform(const glm::dmat4& objectToWorld) : objectToWorld_(objectToWorld) {
    for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) {
            if (!std::isfinite(objectToWorld[c][r]))
                throwBadInput("--model: the matrix holds a value that is not finite");
        }
    }
    if (objectToWorld[0][3] != 0.0 || objectToWorld[1][3] != 0.0 || objectToWorld[2][3] != 0.0 ||
        objectToWorld[3][3] != 1.0) {
        throwBadInput("--model: not an affine transform (its last row must be 0, 0, 0, 1)");
    }
    const auto [largest, smallest] = singularRange(glm::dmat3(objectToWorld));
    if (!(smallest > 1e-12 * largest)) {
        throwBadInput(
            "--model: the matrix is singular (it flattens the relief; its 3 x 3 part must "
            "be invertible)");
    }
    worldToObject_ = glm::inverse(objectToWorld);
}

ModelTransform ModelTransform::fromRows(const std::array<double, 12>& m) {
    glm::dmat4 matrix(1.0);
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 4; ++c) matrix[c][r] = m[static_cast<std::size_t>(4 * r + c)];
    }
    return ModelTransform(matrix);
}

std::array<double, 12> ModelTransform::rows() const {
    std::array<double, 12> m{};
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 4; ++c) m[static_cast<std::size_t>(4 * r + c)] = objectToWorld_[c][r];
    }
    return m;
}

Ray ModelTransform::toObject(const Ray& world) const {
    return {glm::dvec3(worldToObject_ * glm::dvec4(world.origin, 1.0)),
            glm::dmat3(worldToObject_) * world.direction};
}

glm::dvec3 ModelTransform::pointToWorld(const glm::dvec3& object) const {
    return glm::dvec3(objectToWorld_ * glm::dvec4(object, 1.0));
}

glm::dvec3 ModelTransform::pointToObject(const glm::dvec3& world) const {
    return glm::dvec3(worldToObject_ * glm::dvec4(world, 1.0));
}

glm::dvec3 ModelTransform::normalToWorld(const glm::dvec3& object) const {
    return glm::normalize(glm::transpose(glm::dmat3(worldToObject_)) * object);
}

}  // namespace microrelief
