#include "microrelief/base/ReliefExtent.h"

#include <algorithm>

namespace microrelief {

ReliefExtent reliefExtent(int width, int height, double maxHeight, double heightScale,
                          const BaseShape& base) {
    const double top = heightScale * maxHeight;
    return {base.boxMin(width, height, top), base.boxMax(width, height, top), top};
}

ReliefExtent reliefExtent(const HeightMap& map, double heightScale, const BaseShape& base) {
    return reliefExtent(map.width, map.height, map.maxValue(), heightScale, base);
}

double sceneRadius(const ReliefExtent& e) {
    const glm::dvec3 corner = glm::max(glm::abs(e.min), glm::abs(e.max));
    return 2.0 * std::max({corner.x, corner.y, corner.z});
}

}  // namespace microrelief
