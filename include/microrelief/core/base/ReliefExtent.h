// The world-space box a relief occupies over its base: the proxy geometry the renderer
// rasterises, and the scene radius the camera's depth range is made from.
#pragma once

#include <glm/glm.hpp>

#include "microrelief/core/base/BaseShape.h"
#include "microrelief/core/heightmap/HeightMap.h"

namespace microrelief {

// World-space extent of a map's relief: its bounding box, the proxy geometry (spec: on
// the plane x in [-a/2, a/2], z in [-b/2, b/2], y in [0, s max h]; BaseShape::boxMax).
struct ReliefExtent {
    glm::dvec3 min{-0.5, 0.0, -0.5}, max{0.5, 0.0, 0.5};
    double topHeight = 0.0;  // s * max h: world units on the plane, canonical on a curved base
};
ReliefExtent reliefExtent(int width, int height, double maxHeight, double heightScale,
                          const BaseShape& base = {});
// Scans the map for its max.
ReliefExtent reliefExtent(const HeightMap& map, double heightScale, const BaseShape& base = {});
// The radius resolveCamera gets for this relief (it sets the depth range only): about
// sceneCentre (the model's translation: the world's origin for the identity), of the box
// placed by `objectToWorld` (the model transform), so that a relief far from the origin
// gets the depth range of one at it.
double sceneRadius(const ReliefExtent& extent, const glm::dmat4& objectToWorld = glm::dmat4(1.0));
inline glm::dvec3 sceneCentre(const glm::dmat4& objectToWorld) {
    return glm::dvec3(objectToWorld[3]);
}

}  // namespace microrelief
