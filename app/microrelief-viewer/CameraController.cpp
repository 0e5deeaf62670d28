#include "CameraController.h"

#include <algorithm>
#include <cmath>

namespace microrelief {

namespace {

constexpr glm::dvec3 kWorldUp{0.0, 1.0, 0.0};
// Radians per window pixel of drag: half a turn across a 1000-pixel drag, roughly.
constexpr double kRadiansPerPixel = 0.005;
// Zoom factor per scroll step.
constexpr double kZoomPerStep = 0.85;
// World units per scroll step once the target travels with the eye: a hundredth of the
// map's longer side.
constexpr double kDollyPerStep = 0.01;

glm::dvec3 direction(double yaw, double pitch) {
    return {std::cos(pitch) * std::cos(yaw), std::sin(pitch), std::cos(pitch) * std::sin(yaw)};
}

}  // namespace

CameraController::CameraController(const Camera& initial) : initial_(initial), camera_(initial) {}

double CameraController::distance() const {
    return glm::length(camera_.target - camera_.eye);
}

glm::dvec3 CameraController::forward() const {
    return glm::normalize(camera_.target - camera_.eye);
}

double CameraController::yawDegrees() const {
    const glm::dvec3 f = forward();
    return glm::degrees(std::atan2(f.z, f.x));
}

double CameraController::pitchDegrees() const {
    return glm::degrees(std::asin(std::clamp(forward().y, -1.0, 1.0)));
}

glm::dvec3 CameraController::turned(double yaw, double pitch) const {
    const glm::dvec3 f = forward();
    glm::dvec2 horizontal(f.x, f.z);
    if (glm::length(horizontal) < 1e-9) {
        // Straight up or down (a start camera may look so): the heading is the one that
        // keeps the screen's up where the start camera had it.
        const glm::dvec3 up = camera_.up;
        horizontal = f.y < 0.0 ? glm::dvec2(up.x, up.z) : glm::dvec2(-up.x, -up.z);
        if (glm::length(horizontal) < 1e-9) horizontal = {1.0, 0.0};
    }
    const double limit = glm::radians(kPitchLimitDegrees);
    const double newYaw = std::atan2(horizontal.y, horizontal.x) + yaw;
    const double newPitch =
        std::clamp(std::asin(std::clamp(f.y, -1.0, 1.0)) + pitch, -limit, limit);
    return direction(newYaw, newPitch);
}

void CameraController::screenAxes(glm::dvec3& right, glm::dvec3& up) const {
    const glm::dvec3 f = forward();
    right = glm::normalize(glm::cross(f, camera_.up));
    up = glm::cross(right, f);
}

void CameraController::orbit(double dx, double dy) {
    // Dragging right turns the relief to the right (the eye goes left around it);
    // dragging down raises the eye.
    const double d = distance();
    const glm::dvec3 f = turned(dx * kRadiansPerPixel, -dy * kRadiansPerPixel);
    camera_.up = kWorldUp;
    camera_.eye = camera_.target - d * f;
}

void CameraController::look(double dx, double dy) {
    const double d = distance();
    const glm::dvec3 f = turned(dx * kRadiansPerPixel, -dy * kRadiansPerPixel);
    camera_.up = kWorldUp;
    camera_.target = camera_.eye + d * f;
}

void CameraController::pan(double dx, double dy, double viewportHeight) {
    glm::dvec3 right, up;
    screenAxes(right, up);
    // The world height the viewport spans at the target's distance.
    const double span = 2.0 * distance() * std::tan(glm::radians(camera_.fovyDegrees) * 0.5);
    const glm::dvec3 shift = (-dx * right + dy * up) * (span / std::max(viewportHeight, 1.0));
    camera_.eye += shift;
    camera_.target += shift;
}

void CameraController::zoom(double steps) {
    const glm::dvec3 f = forward();
    const double d = distance();
    const double closer = d * std::pow(kZoomPerStep, steps);
    if (closer >= kMinDistance || steps <= 0.0) {
        camera_.eye = camera_.target - std::max(closer, kMinDistance) * f;
        return;
    }
    // Dolly: down to the minimum distance, then the target travels with the eye, so
    // the camera can pass through it (into the relief's box, say).
    const double travel = (d - kMinDistance) + kDollyPerStep * steps;
    camera_.eye += travel * f;
    camera_.target = camera_.eye + kMinDistance * f;
}

void CameraController::fly(const glm::dvec3& move) {
    glm::dvec3 right, up;
    screenAxes(right, up);
    const glm::dvec3 shift = move.x * right + move.y * kWorldUp + move.z * forward();
    camera_.eye += shift;
    camera_.target += shift;
}

void CameraController::setTarget(const glm::dvec3& point) {
    if (glm::length(point - camera_.eye) < kMinDistance) return;
    const glm::dvec3 f = glm::normalize(point - camera_.eye);
    // Keep the frame defined: a target straight above or below the eye is refused.
    if (glm::length(glm::cross(f, camera_.up)) < std::sin(glm::radians(90.0 - kPitchLimitDegrees)))
        return;
    camera_.target = point;
}

void CameraController::setFovy(double degrees) {
    camera_.fovyDegrees = std::clamp(degrees, 1.0, 170.0);
}

void CameraController::frame(const glm::dvec3& centre, double radius) {
    const double halfAngle = glm::radians(0.5 * camera_.fovyDegrees);
    const double distance = std::max(radius / std::sin(halfAngle), kMinDistance);
    camera_.eye = centre - forward() * distance;
    camera_.target = centre;
}

}  // namespace microrelief
