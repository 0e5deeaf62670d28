#include "microrelief/core/scene/ModelTransform.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "microrelief/core/Error.h"

namespace microrelief {

namespace {

// The largest singular value of a 3 x 3 matrix: the square root of the largest eigenvalue
// of A^T A (symmetric, positive semi-definite), by the closed form for 3 x 3 symmetric
// ones. The largest is accurate however ill-conditioned the matrix (the smallest is not:
// take it as 1 / the inverse's largest).
double largestSingularValue(const glm::dmat3& a) {
    const glm::dmat3 m = glm::transpose(a) * a;
    const double p1 = m[0][1] * m[0][1] + m[0][2] * m[0][2] + m[1][2] * m[1][2];
    const double q = (m[0][0] + m[1][1] + m[2][2]) / 3.0;
    if (p1 == 0.0) return std::sqrt(std::max({m[0][0], m[1][1], m[2][2], 0.0}));
    const double p2 = (m[0][0] - q) * (m[0][0] - q) + (m[1][1] - q) * (m[1][1] - q) +
                      (m[2][2] - q) * (m[2][2] - q) + 2.0 * p1;
    const double p = std::sqrt(p2 / 6.0);
    const glm::dmat3 b = (m - q * glm::dmat3(1.0)) / p;
    const double r = std::clamp(glm::determinant(b) / 2.0, -1.0, 1.0);
    return std::sqrt(std::max(q + 2.0 * p * std::cos(std::acos(r) / 3.0), 0.0));
}

std::string number(double value) {
    std::ostringstream text;
    text.precision(3);
    text << value;
    return text.str();
}

}  // namespace

ModelTransform::ModelTransform(const glm::dmat4& objectToWorld) : objectToWorld_(objectToWorld) {
    for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) {
            if (!std::isfinite(objectToWorld[c][r]))
                throwBadInput("{model}: the matrix holds a value that is not finite");
        }
    }
    if (objectToWorld[0][3] != 0.0 || objectToWorld[1][3] != 0.0 || objectToWorld[2][3] != 0.0 ||
        objectToWorld[3][3] != 1.0) {
        throwBadInput("{model}: not an affine transform (its last row must be 0, 0, 0, 1)");
    }
    const glm::dmat3 linear(objectToWorld);
    const glm::dmat3 inverse = glm::inverse(linear);
    const double determinant = glm::determinant(linear);
    bool finiteInverse = true;
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) finiteInverse = finiteInverse && std::isfinite(inverse[c][r]);
    if (determinant == 0.0 || !finiteInverse) {
        throwBadInput(
            "{model}: the matrix is singular (it flattens the relief; its 3 x 3 part must "
            "be invertible)");
    }
    largestScale_ = largestSingularValue(linear);
    smallestScale_ = 1.0 / largestSingularValue(inverse);
    // Invertible, but so unevenly scaled that the inverse the shader carries in float
    // loses the relief: not "singular" (its determinant may be 1).
    const double condition = largestScale_ / smallestScale_;
    if (!(condition <= kMaxModelCondition)) {
        throwBadInput("{model}: the matrix is ill-conditioned (condition number " +
                      number(condition) + ": it scales one direction " + number(condition) +
                      " times more than another; at most " + number(kMaxModelCondition) +
                      ", beyond which its inverse loses the relief to rounding)");
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
