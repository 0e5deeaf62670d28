#include "microrelief/core/scene/Camera.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "microrelief/core/Error.h"

namespace microrelief {

Ray CameraFrame::pixelRay(int column, int row) const {
    const double x = (column + 0.5) / width * 2.0 - 1.0;
    const double y = 1.0 - (row + 0.5) / height * 2.0;
    return {eye, forward + x * right + y * up};
}

double CameraFrame::pixelWidthPerUnit() const {
    return 2.0 * glm::length(up) / height;  // `up` is scaled by tan(fovy / 2)
}

CameraFrame resolveCamera(const Camera& camera, int width, int height, double sceneRadius,
                          const glm::dvec3& sceneCentre) {
    if (width <= 0 || height <= 0) throwBadInput("the picture size must be positive");
    if (!(camera.fovyDegrees > 0.0 && camera.fovyDegrees < 180.0)) {
        throwBadInput("{camera.fovyDegrees} must lie strictly between 0 and 180 degrees");
    }
    const glm::dvec3 view = camera.target - camera.eye;
    const double distance = glm::length(view);
    if (!(distance > 0.0) || !std::isfinite(distance))
        throwBadInput("{camera.eye} and {camera.target} must differ");
    const glm::dvec3 forward = view / distance;
    const glm::dvec3 side = glm::cross(forward, camera.up);
    if (!(glm::length(side) > 1e-9 * glm::length(camera.up))) {
        throwBadInput("{camera.up} must not be parallel to the view direction");
    }
    const glm::dvec3 right = glm::normalize(side);
    const glm::dvec3 up = glm::cross(right, forward);
    const double tanY = std::tan(glm::radians(camera.fovyDegrees) * 0.5);
    const double aspect = static_cast<double>(width) / height;

    CameraFrame frame;
    frame.eye = camera.eye;
    frame.forward = forward;
    frame.right = right * (tanY * aspect);
    frame.up = up * tanY;
    frame.width = width;
    frame.height = height;

    // Depth range around the scene; depth clamping in the renderer makes near/far
    // clipping harmless, so these only set the depth buffer's precision.
    const double centre = glm::length(camera.eye - sceneCentre);
    const double zFar = centre + 2.0 * sceneRadius;
    const double zNear = std::max(1e-4 * zFar, centre - 2.0 * sceneRadius);
    const glm::dmat4 projection =
        glm::perspective(glm::radians(camera.fovyDegrees), aspect, zNear, zFar);
    frame.viewProjection = projection * glm::lookAt(camera.eye, camera.eye + forward, up);
    return frame;
}

}  // namespace microrelief
