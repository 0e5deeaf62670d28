#include "microrelief/core/base/ReliefExtent.h"

#include <algorithm>
#include <cmath>

namespace microrelief {

ReliefExtent reliefExtent(int width, int height, double maxHeight, double heightScale,
                          const BaseShape& base) {
    const double top = heightScale * maxHeight;
    return {base.boxMin(width, height, top), base.boxMax(width, height, top), top};
}

ReliefExtent reliefExtent(const HeightMap& map, double heightScale, const BaseShape& base) {
    return reliefExtent(map.width, map.height, map.maxValue(), heightScale, base);
}

double sceneRadius(const ReliefExtent& e, const glm::dmat4& objectToWorld) {
    double radius = 0.0;
    for (int corner = 0; corner < 8; ++corner) {
        const glm::dvec3 object((corner & 1) ? e.max.x : e.min.x, (corner & 2) ? e.max.y : e.min.y,
                                (corner & 4) ? e.max.z : e.min.z);
        const glm::dvec3 world =
            glm::dvec3(objectToWorld * glm::dvec4(object, 1.0)) - sceneCentre(objectToWorld);
        radius = std::max({radius, std::abs(world.x), std::abs(world.y), std::abs(world.z)});
    }
    return 2.0 * radius;
}

}  // namespace microrelief
