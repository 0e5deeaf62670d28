// The viewer's camera: a turntable orbit around a target (yaw about the world's y axis,
// pitch clamped short of the poles, so the picture never flips or rolls), pan, zoom that
// dollies through the target when it gets close, and a fly mode that turns about the eye
// and moves it freely, into the relief's box and down to grazing angles.
//
// The camera given at start (--eye --target --up --fovy) is kept exactly until the first
// rotation: the viewer's first frame is bit for bit microrelief-render's. A rotation
// switches the up direction to world y.
#pragma once

#include <glm/glm.hpp>

#include "microrelief/core/scene/Camera.h"

namespace microrelief {

class CameraController {
public:
    explicit CameraController(const Camera& initial);

    const Camera& camera() const { return camera_; }
    double distance() const;  // eye to target

    // Mouse drags, in window pixels. Orbit turns the eye about the target; look turns
    // the view about the eye (fly mode). Right and down are positive.
    void orbit(double dx, double dy);
    void look(double dx, double dy);
    // Moves eye and target so the point under the cursor follows it; `viewportHeight`
    // in the same pixels as dx, dy.
    void pan(double dx, double dy, double viewportHeight);
    // Scroll steps, positive towards the target. Closer than a minimum distance the
    // target moves along with the eye, so the camera can pass through it.
    void zoom(double steps);
    // Fly mode: `move` in the camera's own axes (x right, y world up, z forward), in
    // world units; the target travels along.
    void fly(const glm::dvec3& move);
    // Orbit about `point` from now on; the eye stays where it is.
    void setTarget(const glm::dvec3& point);
    void setFovy(double degrees);
    // Looks at `centre` along the current view direction from just far enough that a
    // sphere of `radius` about it fills the view.
    void frame(const glm::dvec3& centre, double radius);
    void reset() { camera_ = initial_; }

    // Yaw (about +y, from +x towards +z) and pitch (above the horizon) of the view, degrees.
    double yawDegrees() const;
    double pitchDegrees() const;

    // How close to the poles the pitch may come: the up vector and the view direction
    // never become parallel, so the frame stays defined and the picture never flips.
    static constexpr double kPitchLimitDegrees = 89.5;
    static constexpr double kMinDistance = 1e-3;

private:
    glm::dvec3 forward() const;
    // The view direction rotated by yaw and pitch increments (radians), pitch clamped.
    glm::dvec3 turned(double yaw, double pitch) const;
    // Unit right and screen-up vectors of the current view.
    void screenAxes(glm::dvec3& right, glm::dvec3& up) const;

    Camera initial_;
    Camera camera_;
};

}  // namespace microrelief
