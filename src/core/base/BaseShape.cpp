#include "microrelief/core/base/BaseShape.h"

#include <algorithm>
#include <cmath>

#include "microrelief/core/Error.h"
#include "microrelief/core/base/BaseType.h"

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
    return baseType(*this).frameScale(*this);
}

glm::dvec3 BaseShape::boxMin(int mapWidth, int mapHeight, double topHeight) const {
    const BaseType& type = baseType(*this);
    const glm::dvec3 high = type.boxMax(*this, mapWidth, mapHeight, topHeight);
    return type.boxIsSymmetric ? -high : glm::dvec3(-high.x, 0.0, -high.z);
}

glm::dvec3 BaseShape::boxMax(int mapWidth, int mapHeight, double topHeight) const {
    return baseType(*this).boxMax(*this, mapWidth, mapHeight, topHeight);
}

double BaseShape::texelSize(int mapWidth, int mapHeight) const {
    return baseType(*this).texelSize(*this, mapWidth, mapHeight);
}

BaseKind parseBaseKind(const std::string& name) {
    return baseType(name).kind;
}

std::string baseName(const BaseShape& shape) {
    return baseType(shape).name;
}

void validateBaseShape(const BaseShape& shape) {
    const auto& table = baseTypes();
    if (std::none_of(table.begin(), table.end(),
                     [&](const BaseType& type) { return type.kind == shape.kind; })) {
        throwBadInput("{base} of kind " + std::to_string(static_cast<int>(shape.kind)) +
                      " is none of the table of bases'");
    }
    for (const BaseSize& size : baseType(shape).sizes) {
        double numbers[3] = {};
        size.read(shape, numbers);
        for (int i = 0; i < size.count; ++i) {
            if (!(numbers[i] > 0.0) || !std::isfinite(numbers[i]))
                throwBadInput(std::string("{") + size.field + "} must be a positive finite number");
        }
    }
}

}  // namespace microrelief
