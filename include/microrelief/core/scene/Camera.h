// The pinhole camera of the spec: one ray through each pixel centre, row 0 at the top.
// The same frame feeds the shader (as uniforms) and the CPU tracers, so GPU and CPU
// cast bit-for-bit the same rays up to float conversion.
#pragma once

#include <glm/glm.hpp>

namespace microrelief {

struct Camera {
    glm::dvec3 eye{0.8, 0.5, 0.85};
    glm::dvec3 target{0.0, -0.03, 0.0};
    glm::dvec3 up{0.0, 1.0, 0.0};
    double fovyDegrees = 45.0;
};

struct Ray {
    glm::dvec3 origin;
    glm::dvec3 direction;  // not normalised: t is measured in its length
};

// The camera resolved for a picture size: a ray through normalised device
// coordinates (x, y) in [-1, 1]^2 is eye + t (forward + x right + y up).
struct CameraFrame {
    glm::dvec3 eye;
    glm::dvec3 forward;  // unit
    glm::dvec3 right;    // unit right scaled by tan(fovx / 2)
    glm::dvec3 up;       // unit up scaled by tan(fovy / 2)
    glm::dmat4 viewProjection;
    int width = 0, height = 0;

    // The ray through the centre of pixel (column, row), row 0 the top row.
    Ray pixelRay(int column, int row) const;
    // The centre pixel's width per unit of distance from the eye, 2 tan(fovy / 2) / height:
    // the unit of pixel errors (core/trace/Accuracy.h), as relief.frag's level-of-detail cone
    // has it.
    double pixelWidthPerUnit() const;
};

// Throws Error(BadInput) for a degenerate camera (eye at the target, up along the view
// direction, field of view outside (0, 180)). `sceneRadius` bounds the scene around
// `sceneCentre` (the world's origin, or the relief's: core/base/ReliefExtent.h) and sets
// the depth range.
CameraFrame resolveCamera(const Camera& camera, int width, int height, double sceneRadius,
                          const glm::dvec3& sceneCentre = glm::dvec3(0.0));

}  // namespace microrelief
