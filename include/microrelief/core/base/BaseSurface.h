// The base-surface seam of the traversal, the C++ mirror of
// shaders/microrelief/base_surface.glsl: everything the multilevel traversal needs to know
// about the surface the height map is laid over, for the plane, a cylinder or an
// ellipsoid (core/base/BaseShape.h). One implementation per base, in a file of its own.
//
// The traversal works in the base's frame, where the ray is a straight line o + t d with
// the world's t: map space (X, Y, h) for the plane (map_space.glsl), the canonical frame q
// for the curved bases. The seam answers, for a segment [ta, tb] of that line:
//  * its footprint, a rectangle of map (X, Y) texel coordinates that holds the segment's
//    path on the map, and its lowest height h above the base (map units). Both are
//    bounds, never samples: on a curved base the path in (X, Y, h) is a curve, but the
//    angle about the axis is monotone along a line, the distance from the axis (cylinder)
//    or the centre (ellipsoid) is convex along it, and the latitude has at most one
//    interior extremum, so the extremes over the segment are at its ends or at one
//    interior point found in closed form. Every bound is widened by a margin that covers
//    the rounding of its own arithmetic (kFootprintMargin, kRadiusMargin), so that it is
//    never on the wrong side of the exact value;
//  * the ray's interval inside the bounding shell (the box over the plane, the cylinder
//    of radius 1 + s max h between the caps, the ball of that radius) and the face it
//    enters through;
//  * where the path crosses a cell boundary of the map (the leaf's walk), in closed form;
//  * the normal of the surface at a hit, from the map gradient.
#pragma once

#include <memory>
#include <optional>

#include <glm/glm.hpp>

#include "microrelief/core/base/BaseShape.h"
#include "microrelief/core/scene/Camera.h"

namespace microrelief {

// A ray in the base's frame; t is the world ray's parameter.
struct FrameRay {
    glm::dvec3 origin, dir;
    glm::dvec3 at(double t) const { return origin + t * dir; }
};

// A conservative footprint of a segment: every point of its path lies over
// [lo.x, hi.x] x [lo.y, hi.y] (texel coordinates) and no lower than `lowest` above the
// base. On a curved base hi.x may exceed W: the rectangle wraps across u = 0, and
// 0 <= lo.x < W there.
struct Footprint {
    glm::dvec2 lo{0.0}, hi{0.0};
    double lowest = 0.0;
    double drop = 0.0;  // |h(tb) - h(ta)|: how much the segment's height changes
    double extent() const { return std::max(hi.x - lo.x, hi.y - lo.y); }
};

// The face of the bounding shell a ray enters through: the top face of the plane's box or
// the curved shell itself (None: nothing to test there, the traversal starts), a side
// wall or the bottom of the plane's box, a cap of the cylinder.
enum class ShellFace { None, WallX, WallY, Bottom, CapTop, CapBottom };

struct ShellSpan {
    double tEnter = 0.0, tExit = -1.0;  // empty when tEnter > tExit
    ShellFace entry = ShellFace::None;
    // The plane: the ray leaves the box through the base plane going down, so it meets
    // h = 0 (in the solid) at tExit.
    bool floorExit = false;
    bool empty() const { return tEnter > tExit; }
};

class BaseSurface {
public:
    // `maxHeight` is the pyramid's top (the map's max, rounded up), in map units.
    static std::unique_ptr<BaseSurface> make(const BaseShape& shape, int mapWidth, int mapHeight,
                                             double heightScale, double maxHeight);
    virtual ~BaseSurface() = default;

    const BaseShape& shape() const { return shape_; }
    int mapWidth() const { return width_; }
    int mapHeight() const { return height_; }
    double heightScale() const { return heightScale_; }
    double maxHeight() const { return maxHeight_; }
    bool wrapsU() const { return shape_.wrapsU(); }

    virtual FrameRay frameRay(const Ray& world) const = 0;
    // The map point (X, Y, h) of a frame point: X in [0, W) on a curved base (wrapped),
    // any X on the plane.
    virtual glm::dvec3 mapPoint(const glm::dvec3& q) const = 0;
    virtual ShellSpan clip(const FrameRay& ray) const = 0;
    virtual Footprint footprint(const FrameRay& ray, double ta, double tb) const = 0;
    // footprint().lowest alone.
    virtual double lowest(const FrameRay& ray, double ta, double tb) const = 0;
    // The first t in [ta, tb] at which the ray is at or below height `h` (map units),
    // never later than the exact one; ta where it starts there or never gets that low.
    virtual double descendTo(const FrameRay& ray, double ta, double tb, double h) const = 0;
    // The outward normal (not unit) in the frame of the top surface at frame point q,
    // where the map's gradient is (dh/dX, dh/dY); of a shell face entry otherwise.
    virtual glm::dvec3 topNormal(const glm::dvec3& q, const glm::dvec2& gradient) const = 0;
    virtual glm::dvec3 faceNormal(ShellFace face, const FrameRay& ray) const = 0;
    // A frame normal in world space, unit.
    virtual glm::dvec3 worldNormal(const glm::dvec3& frameNormal) const = 0;

    // The leaf's walk over cells (leaf_walk.glsl, mr_walkLeafCells). The t at which the path
    // crosses the cell boundary X = boundary, any t (each is crossed once along a line: a
    // walk at t = `after` that finds it behind that has rounded past it; a curved base's
    // line through its axis meets every boundary there, no crossing: base_curved.glsl,
    // mr_curvedCrossX), or nullopt.
    virtual std::optional<double> crossX(const FrameRay& ray, double boundary,
                                         double after) const = 0;
    // Whether X grows along the ray (monotone along a line on every base).
    virtual bool xIncreases(const FrameRay& ray) const = 0;
    // Y of a frame point.
    virtual double mapY(const glm::dvec3& q) const = 0;
    // Where Y turns (its one interior extremum along the line), or nullopt.
    virtual std::optional<double> turnY(const FrameRay& ray) const = 0;
    // The t at which the path crosses Y = boundary, Y being monotone on [from, to]: where
    // the line crosses that boundary only once (planes), that crossing at any t, like
    // crossX; where it may cross twice (the ellipsoid's cones), the one crossing in
    // [from, to]. nullopt if none.
    virtual std::optional<double> crossY(const FrameRay& ray, double boundary, double from,
                                         double to) const = 0;
    // A piece of a cell's stretch at most this long (frame units) is final: the curved
    // bases' curvature is then below float precision (base_surface.glsl:
    // kCurvedFinalLength); the plane has no curvature.
    virtual double finalLength() const = 0;

    // For the implementations; make() is how a surface is made.
    BaseSurface(const BaseShape& shape, int mapWidth, int mapHeight, double heightScale,
                double maxHeight)
        : shape_(shape),
          width_(mapWidth),
          height_(mapHeight),
          heightScale_(heightScale),
          maxHeight_(maxHeight) {}

protected:
    BaseShape shape_;
    int width_, height_;
    double heightScale_, maxHeight_;
};

// The curved bases share the angle about the y axis (u) and the leaf's walk over cells;
// they differ in the distance that sets the height (from the axis or the centre) and in
// v (along the axis or the latitude).
class CurvedSurface : public BaseSurface {
public:
    CurvedSurface(const BaseShape& shape, int mapWidth, int mapHeight, double heightScale,
                  double maxHeight)
        : BaseSurface(shape, mapWidth, mapHeight, heightScale, maxHeight),
          frameScale_(shape.frameScale()) {}
    FrameRay frameRay(const Ray& world) const override;
    glm::dvec3 worldNormal(const glm::dvec3& frameNormal) const override;
    Footprint footprint(const FrameRay& ray, double ta, double tb) const override;
    double lowest(const FrameRay& ray, double ta, double tb) const override;
    double descendTo(const FrameRay& ray, double ta, double tb, double h) const override;
    glm::dvec3 mapPoint(const glm::dvec3& q) const override {
        return {mapX(q), mapY(q), (radial(q) - 1.0) / heightScale_};
    }

    // X of frame point q, in [0, W).
    double mapX(const glm::dvec3& q) const;
    std::optional<double> crossX(const FrameRay& ray, double boundary, double after) const override;
    bool xIncreases(const FrameRay& ray) const override;
    double finalLength() const override;

    // The distance that sets the height: from the axis (cylinder) or the centre.
    virtual double radial(const glm::dvec3& q) const = 0;
    // The exact minimum of `radial` over [ta, tb] (it is convex along a line).
    virtual double lowestRadial(const FrameRay& ray, double ta, double tb) const = 0;
    // The interval of t where radial <= r (empty, x > y, if none).
    virtual glm::dvec2 insideRadial(const FrameRay& ray, double r) const = 0;
    // The range of Y over [ta, tb]: the ends, and the one interior extremum if any.
    virtual glm::dvec2 rangeY(const FrameRay& ray, double ta, double tb) const = 0;

protected:
    // The radial distance of the shell, 1 + s max h.
    double shellRadius() const { return 1.0 + heightScale_ * maxHeight_; }

    glm::dvec3 frameScale_;  // the shape's (BaseShape::frameScale), looked up once
};

// Conservative margins of the footprint, in texels, and of the radial distance, in
// canonical units: far above double rounding of the few operations that compute them
// (relative 1e-16 of values of order 1 and of W), far below anything that could loosen
// a bound measurably. The shader's float margins are larger (base_curved.glsl).
constexpr double kFootprintMargin = 1e-9;
constexpr double kRadiusMargin = 1e-12;

}  // namespace microrelief
