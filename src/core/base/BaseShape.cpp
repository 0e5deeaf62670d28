#include "microrelief/core/base/BaseShape.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "microrelief/core/Error.h"

namespace microrelief {

BaseShape BaseShape::cylinder(double radius, double length) {
    BaseShape shape;
    shape.kind = BaseKind::Cylinder;
    shape.radius = radius;
    shape.length = length;
    return shape;
}

BaseShape BaseShape::ellipsoid(const glm::dvec3& radii) {
    BaseShape shape;
    shape.kind = BaseKind::Ellipsoid;
    shape.radii = radii;
    return shape;
}

glm::dvec3 BaseShape::frameScale() const {
    switch (kind) {
        case BaseKind::Cylinder:
            return {radius, 0.5 * length, radius};
        case BaseKind::Ellipsoid:
            return radii;
        case BaseKind::Plane:
            break;
    }
    return glm::dvec3(1.0);
}

glm::dvec3 BaseShape::boxMin(int mapWidth, int mapHeight, double topHeight) const {
    const glm::dvec3 high = boxMax(mapWidth, mapHeight, topHeight);
    return kind == BaseKind::Plane ? glm::dvec3(-high.x, 0.0, -high.z) : -high;
}

glm::dvec3 BaseShape::boxMax(int mapWidth, int mapHeight, double topHeight) const {
    switch (kind) {
        case BaseKind::Cylinder:
            return frameScale() * glm::dvec3(1.0 + topHeight, 1.0, 1.0 + topHeight);
        case BaseKind::Ellipsoid:
            return frameScale() * (1.0 + topHeight);
        case BaseKind::Plane:
            break;
    }
    const double longer = std::max(mapWidth, mapHeight);
    return {0.5 * mapWidth / longer, topHeight, 0.5 * mapHeight / longer};
}

double BaseShape::texelSize(int mapWidth, int mapHeight) const {
    constexpr double pi = std::numbers::pi;
    switch (kind) {
        case BaseKind::Cylinder:
            return std::sqrt(2.0 * pi * radius / mapWidth * length / mapHeight);
        case BaseKind::Ellipsoid: {
            const double r = (radii.x + radii.y + radii.z) / 3.0;
            return std::sqrt(2.0 * pi * r / mapWidth * pi * r / mapHeight);
        }
        case BaseKind::Plane:
            break;
    }
    return 1.0 / std::max(mapWidth, mapHeight);
}

BaseKind parseBaseKind(const std::string& name) {
    if (name == "plane") return BaseKind::Plane;
    if (name == "cylinder") return BaseKind::Cylinder;
    if (name == "ellipsoid" || name == "sphere") return BaseKind::Ellipsoid;
    throwBadInput("unknown {base} '" + name + "' (expected plane, cylinder, ellipsoid or sphere)");
}

std::string baseName(const BaseShape& shape) {
    switch (shape.kind) {
        case BaseKind::Cylinder:
            return "cylinder";
        case BaseKind::Ellipsoid:
            return shape.radii.x == shape.radii.y && shape.radii.y == shape.radii.z ? "sphere"
                                                                                    : "ellipsoid";
        case BaseKind::Plane:
            break;
    }
    return "plane";
}

void validateBaseShape(const BaseShape& shape) {
    const auto positive = [](double value, const char* flag) {
        if (!(value > 0.0) || !std::isfinite(value))
            throwBadInput(std::string(flag) + " must be a positive finite number");
    };
    switch (shape.kind) {
        case BaseKind::Cylinder:
            positive(shape.radius, "{base.radius}");
            positive(shape.length, "{base.length}");
            break;
        case BaseKind::Ellipsoid:
            for (int axis = 0; axis < 3; ++axis) positive(shape.radii[axis], "{base.radii}");
            break;
        case BaseKind::Plane:
            break;
    }
}

}  // namespace microrelief
