#include "microrelief/core/trace/MultilevelTracer.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "microrelief/core/GlslConstants.h"
#include "microrelief/core/trace/SegmentWalk.h"

namespace microrelief {

namespace {

using glsl::kBiquadraticFinalFootprint;
using glsl::kCellDepth;

// bilinear_patch.glsl: mr_intersectPatch.
double intersectPatch(const SurfacePatch& c, const glm::dvec3& start, const glm::dvec3& dir,
                      double tauMax) {
    const double fx = start.x - (c.i + 0.5), fy = start.y - (c.j + 0.5);
    const double b = c.h10 - c.h00, cc = c.h01 - c.h00, d = c.h00 - c.h10 - c.h01 + c.h11;
    // g(tau) = patch height - ray height: the hit is the first tau with g >= 0.
    const double C = c.h00 + b * fx + cc * fy + d * fx * fy - start.z;
    if (C >= 0.0) return 0.0;
    const double B = b * dir.x + cc * dir.y + d * (fx * dir.y + fy * dir.x) - dir.z;
    const double A = d * dir.x * dir.y;
    double root = -1.0;
    if (std::abs(A) * tauMax <= 1e-12 * std::abs(B)) {
        if (B > 0.0) root = -C / B;
    } else {
        const double disc = B * B - 4.0 * A * C;
        if (disc >= 0.0) {
            const double q = -0.5 * (B + (B >= 0.0 ? 1.0 : -1.0) * std::sqrt(disc));
            const double r1 = q / A, r2 = q != 0.0 ? C / q : -1.0;
            const double lo = std::min(r1, r2), hi = std::max(r1, r2);
            root = lo >= 0.0 ? lo : hi;
        }
    }
    return (root >= 0.0 && root <= tauMax) ? root : -1.0;
}

}  // namespace

int traversalBudget(int width, int height) {
    return glsl::kBudgetPerTexel * (width + height) + glsl::kBudgetBase;
}

MultilevelTracer::MultilevelTracer(HeightMap map, double heightScale, const BaseShape& base,
                                   Interpolation interpolation, glm::ivec2 tiles)
    : map_(std::move(map)),
      interpolation_(interpolation),
      addressing_{base.wrapsU(), tiles.x, tiles.y},
      width_(map_.width * tiles.x),
      height_(map_.height * tiles.y),
      // The bounds the shader reads: the GPU's half floats (MaxPyramid.h).
      pyramid_(map_, addressing_, BoundPrecision::Half),
      heightScale_(heightScale),
      base_(BaseSurface::make(base, width_, height_, heightScale, pyramid_.maxHeight())),
      maxIterations_(traversalBudget(width_, height_)) {}

void MultilevelTracer::mapChanged(const HeightMap& map, const TexelRect& changed) {
    const TexelRect c{std::max(changed.x0, 0), std::max(changed.y0, 0),
                      std::min(changed.x1, map_.width), std::min(changed.y1, map_.height)};
    for (int j = c.y0; j < c.y1; ++j)
        for (int i = c.x0; i < c.x1; ++i) map_.at(i, j) = map.at(i, j);
    pyramid_.update(map_, c);
    const double top = pyramid_.maxHeight();
    if (top != base_->maxHeight())
        base_ = BaseSurface::make(base_->shape(), width_, height_, heightScale_, top);
}

// Fetches are counted as the shader's GLSL 4.00 variant counts them: one textureGather
// per bilinear patch and four per biquadratic one (relief_patch.glsl), one texel per
// pyramid read (BoundRead). Cells lie between samples i..i+1 (bilinear) or over texel
// square i (its samples i-1..i+1), wrapped in i on a curved base, clamped otherwise.
// The walk's steps take the ray's TraversalStats and add to them where they read, so a
// new figure is a field there and a line where it is counted.
SurfacePatch MultilevelTracer::patchAt(int i, int j, TraversalStats& stats) const {
    stats.fetches += interpolation_ == Interpolation::Biquadratic ? 4 : 1;
    return SurfacePatch::at(map_, i, j, addressing_, interpolation_);
}

// relief_hit.glsl: mr_setTopHit's normal, in the base's frame.
glm::dvec3 MultilevelTracer::topNormal(const SurfacePatch& patch,
                                       const glm::dvec3& framePoint) const {
    const glm::dvec3 m = base_->mapPoint(framePoint);
    const double offset = SurfacePatch::offset(interpolation_);
    double fx = m.x - (patch.i + offset);
    if (base_->wrapsU()) fx -= width_ * std::round(fx / width_);
    const glm::dvec2 f(std::clamp(fx, 0.0, 1.0), std::clamp(m.y - (patch.j + offset), 0.0, 1.0));
    glm::dvec2 g = patch.gradient(f);
    // Clamped bilinear border cells are flat across the edge (in u only where it does not
    // wrap); the biquadratic surface is flat at the edge by itself.
    if (interpolation_ == Interpolation::Bilinear) {
        if (!base_->wrapsU() && (patch.i < 0 || patch.i >= width_ - 1)) g.x = 0.0;
        if (patch.j < 0 || patch.j >= height_ - 1) g.y = 0.0;
    }
    return base_->topNormal(framePoint, g);
}

// leaf_walk.glsl: mr_intersectStraightLeaf, on the plane. The cells the segment crosses, in
// ray order, each solved exactly; from a cell to the neighbour across the boundary the
// ray meets first.
auto MultilevelTracer::intersectLeaf(const FrameRay& ray, double ta, double tb,
                                     TraversalStats& stats) const -> std::optional<LeafHit> {
    const glm::dvec3 pa = ray.at(ta), pb = ray.at(tb);
    glm::ivec2 at(std::floor(pa.x - 0.5), std::floor(pa.y - 0.5));  // the cell's origin sample
    const glm::ivec2 last(std::floor(pb.x - 0.5), std::floor(pb.y - 0.5));
    const glm::ivec2 toward(last.x > at.x   ? 1
                            : last.x < at.x ? -1
                                            : 0,
                            last.y > at.y   ? 1
                            : last.y < at.y ? -1
                                            : 0);
    const int pieces = std::abs(last.x - at.x) + std::abs(last.y - at.y) + 1;
    SurfacePatch cell = patchAt(at.x, at.y, stats);
    double t0 = ta;
    for (int piece = 0; piece < pieces; ++piece) {
        double exits[2] = {tb, tb};
        for (int axis = 0; axis < 2; ++axis) {
            if (at[axis] != last[axis] && ray.dir[axis] != 0.0) {
                const double boundary = at[axis] + std::max(toward[axis], 0) + 0.5;
                exits[axis] = std::clamp((boundary - ray.origin[axis]) / ray.dir[axis], t0, tb);
            }
        }
        const double t1 = std::min(exits[0], exits[1]);
        const double tau = intersectPatch(cell, ray.at(t0), ray.dir, t1 - t0);
        if (tau >= 0.0) return LeafHit{t0 + tau, topNormal(cell, ray.at(t0 + tau))};
        if (t1 >= tb) break;
        const int axis = exits[0] <= exits[1] ? 0 : 1;
        at[axis] += toward[axis];
        cell = patchAt(at.x, at.y, stats);
        t0 = t1;
    }
    return std::nullopt;
}

// leaf_walk.glsl: mr_intersectLeafCells. The latitude turns at most once along a line:
// split there, so that on each piece X and Y are both monotone and the cells the path
// crosses are walked in order.
auto MultilevelTracer::intersectLeafCells(const FrameRay& ray, double ta, double tb,
                                          TraversalStats& stats) const -> std::optional<LeafHit> {
    const std::optional<double> turn = base_->turnY(ray);
    constexpr double kAll = std::numeric_limits<double>::infinity();
    // The branches of the line before and after the turn, on each of which Y is monotone.
    const glm::dvec2 before(-kAll, turn ? *turn : kAll), after(turn ? *turn : -kAll, kAll);
    if (turn && *turn > ta && *turn < tb) {
        if (auto hit = walkLeafCells(ray, ta, *turn, before, stats)) return hit;
        return walkLeafCells(ray, *turn, tb, after, stats);
    }
    return walkLeafCells(ray, ta, tb, turn && *turn <= ta ? after : before, stats);
}

// leaf_walk.glsl: mr_walkLeafCells. A DDA over the cells of a path whose X and Y are
// monotone on [from, to]: each cell's stretch ends where the path crosses the cell's
// boundary ahead in X (a half-plane through the axis, a plane on the plane) or in Y (a
// plane or a cone), found in closed form. `branch` is the branch of the line holding
// [from, to] on which Y is monotone, where each boundary is crossed once: a crossing found
// on it behind the current t means rounding put the walk's start just past it, and the
// walk steps on. (The shader splits the walk in two loops, cells tested in the inner one and
// solved in the outer; it visits and reads the same cells in the same order.)
auto MultilevelTracer::walkLeafCells(const FrameRay& ray, double from, double to, glm::dvec2 branch,
                                     TraversalStats& stats) const -> std::optional<LeafHit> {
    const BaseSurface& base = *base_;
    const int w = width_, h = height_;
    const double offset = SurfacePatch::offset(interpolation_);
    const int firstCell = offset > 0.0 ? -1 : 0;  // bilinear border cells at -1
    const glm::dvec3 start = base.mapPoint(ray.at(from));
    int i = static_cast<int>(std::floor(start.x - offset)),
        j = static_cast<int>(std::floor(start.y - offset));
    if (base.wrapsU()) {
        i = (i % w + w) % w;
    } else {
        i = std::clamp(i, firstCell, w - 1);
    }
    j = std::clamp(j, firstCell, h - 1);
    const bool xUp = base.xIncreases(ray);
    const double yFrom = start.y, yTo = base.mapY(ray.at(to));
    const bool yMoves = yTo != yFrom, yUp = yTo > yFrom;
    double t0 = from;
    for (int piece = 0; piece < w + h + 4; ++piece) {
        double t1 = to;
        bool stepX = false, stepY = false;
        // A curved map one sample wide has no boundary in X: its one cell goes all the way round.
        const std::optional<double> tx = !base.wrapsU() || w > 1
                                             ? base.crossX(ray, i + offset + (xUp ? 1.0 : 0.0), t0)
                                             : std::nullopt;
        if (tx && *tx <= t1) {
            t1 = std::max(*tx, t0);
            stepX = true;
        }
        const double yBoundary = j + offset + (yUp ? 1.0 : 0.0);
        if (yMoves && yBoundary > 0.0 && yBoundary < h) {
            if (const auto ty = base.crossY(ray, yBoundary, branch.x, branch.y); ty && *ty <= t1) {
                const double t = std::max(*ty, t0);
                stepX = stepX && t == t1;
                t1 = t;
                stepY = true;
            }
        }
        const SurfacePatch patch = patchAt(i, j, stats);
        if (const auto root = cellStretchHit(ray, patch, t0, t1))
            return LeafHit{*root, topNormal(patch, ray.at(*root))};
        if (!stepX && !stepY) break;  // the stretch ended at `to`
        if (stepX) i = base.wrapsU() ? (i + (xUp ? 1 : w - 1)) % w : i + (xUp ? 1 : -1);
        if (stepY) j += yUp ? 1 : -1;
        t0 = t1;
    }
    return std::nullopt;
}

// leaf_walk.glsl: mr_cellStretchHit (MICRORELIEF_CELL_DEPTH, MR_BIQUADRATIC_FINAL_FOOTPRINT,
// the base's final length): down to pieces 2^-7 long in the frame on a curved base and 2^-6
// texel wide for the biquadratic surface, or 2^-10 of the stretch, then a quadratic model
// of the gap. The first t in [c0, c1] where the ray is on or under
// the cell's patch, g(t) = patch(X(t), Y(t)) - h(t) >= 0. Along a curved path, or for the
// biquadratic surface, g is not a quadratic, so the stretch is subdivided as the traversal
// subdivides the ray, near half first, each piece discarded when its lowest height (exact:
// the ends on the plane, the convexity of the radial distance on a curved base) lies above
// the patch's max over its footprint (exact: X and Y are monotone here, SurfacePatch::
// maxOver). Neither bound is ever on the wrong side, so no contact is lost. Final pieces
// (short in the frame on a curved base, narrow for the biquadratic surface, or 2^-10 of
// the stretch) hold g to a parabola to float precision: a sign change at their ends or
// middle gives the root by interpolation, and without one a concave parabola through the
// three values that reaches 0 is a touching ray (a hit in the closed solid).
std::optional<double> MultilevelTracer::cellStretchHit(const FrameRay& ray,
                                                       const SurfacePatch& patch, double c0,
                                                       double c1) const {
    const BaseSurface& base = *base_;
    const int w = width_;
    const double offset = SurfacePatch::offset(interpolation_);
    const double finalFootprint = interpolation_ == Interpolation::Biquadratic
                                      ? kBiquadraticFinalFootprint
                                      : std::numeric_limits<double>::infinity();
    const auto local = [&](double t) {
        const glm::dvec3 m = base.mapPoint(ray.at(t));
        double fx = m.x - (patch.i + offset);
        // Round the base into the turn centred on the cell (map_addressing.glsl:
        // mr_wrapLocalX), which holds the whole cell for every w >= 2.
        if (base.wrapsU()) fx -= w * std::floor((fx - 0.5) / w + 0.5);
        return glm::dvec3(fx, m.y - (patch.j + offset), m.z);
    };
    const auto gap = [&](double t) {
        const glm::dvec3 f = local(t);
        return patch.height(glm::clamp(glm::dvec2(f), 0.0, 1.0)) - f.z;
    };
    if (!base.shape().curved() && interpolation_ == Interpolation::Biquadratic) {
        // The plane's path is straight: the gap is one quartic (SurfacePatch::pathGap).
        const glm::dvec3 fa = local(c0), fb = local(c1);
        const double footprint = std::max(std::abs(fb.x - fa.x), std::abs(fb.y - fa.y));
        const auto s = quarticFirstHit(patch.pathGap(fa, fb),
                                       kBiquadraticFinalFootprint / std::max(footprint, 1e-300),
                                       kFootprintMargin * base.maxHeight());
        if (!s) return std::nullopt;
        return c0 + *s * (c1 - c0);
    }
    const double finalLength = base.finalLength() / glm::length(ray.dir);
    int depth = 0;
    std::uint32_t index = 0;
    for (;;) {
        const double width = (c1 - c0) / static_cast<double>(1u << depth);
        const double a = c0 + index * width;
        const double b = index + 1 == (1u << depth) ? c1 : a + width;
        const glm::dvec3 fa = local(a), fb = local(b);
        const glm::dvec2 lo = glm::min(glm::dvec2(fa), glm::dvec2(fb)),
                         hi = glm::max(glm::dvec2(fa), glm::dvec2(fb));
        const double top = patch.maxOver(lo - kFootprintMargin, hi + kFootprintMargin);
        const bool may = base.lowest(ray, a, b) <= top;
        const bool last =
            depth == kCellDepth ||
            (b - a <= finalLength && std::max(hi.x - lo.x, hi.y - lo.y) <= finalFootprint);
        if (may && !last) {
            ++depth;
            index *= 2u;
            continue;
        }
        if (may) {
            const double m = 0.5 * (a + b);
            const double ga = gap(a), gm = gap(m), gb = gap(b);
            if (const auto s = parabolaFirstRoot(ga, gm, gb)) return a + *s * (b - a);
        }
        // Past this piece: to its successor in order, as high up as it is unvisited.
        ++index;
        while (depth > 0 && (index & 1u) == 0u) {
            index >>= 1;
            --depth;
        }
        if (depth == 0) return std::nullopt;
    }
}

// The frame ray from the shell's entry, origin + t dir with t in [0, span], as the segment
// walk's path (SegmentWalk.h): the base-surface seam answers for its segments (BaseSurface.h
// says why each answer is a bound), the pyramid's one window (two across a curved base's seam)
// bounds a footprint, and the leaf is the plane's bilinear quadratic per cell or the cell walk.
class MultilevelTracer::FramePath {
public:
    using Hit = LeafHit;

    FramePath(const MultilevelTracer& tracer, const FrameRay& ray, double span, bool floorExit)
        : tracer_(tracer),
          base_(*tracer.base_),
          ray_(ray),
          span_(span),
          floorExit_(floorExit),
          // The plane's bilinear leaf is a quadratic per cell; every other leaf walks its cells.
          cellWalk_(base_.shape().curved() || tracer.interpolation_ == Interpolation::Biquadratic) {}

    double span() const { return span_; }
    bool floorExit() const { return floorExit_; }
    Footprint footprint(double ta, double tb) const { return base_.footprint(ray_, ta, tb); }
    double lowest(double ta, double tb) const { return base_.lowest(ray_, ta, tb); }
    double bound(const Footprint& footprint, TraversalStats& stats) const {
        const BoundRead read = tracer_.pyramid_.footprintBound(footprint.lo, footprint.hi);
        stats.fetches += read.fetches;
        stats.stopLevel = read.level;
        return read.bound;
    }
    double descendTo(double ta, double tb, double h) const {
        return base_.descendTo(ray_, ta, tb, h);
    }
    std::optional<LeafHit> leaf(double from, double to, TraversalStats& stats) const {
        return cellWalk_ ? tracer_.intersectLeafCells(ray_, from, to, stats)
                         : tracer_.intersectLeaf(ray_, from, to, stats);
    }
    // The plane's: the ray leaves the box through h = 0 going down at span, in the solid.
    std::optional<LeafHit> floorHit(TraversalStats& stats) const {
        const glm::dvec3 exit = ray_.at(span_);
        const double offset = SurfacePatch::offset(tracer_.interpolation_);
        const SurfacePatch patch =
            tracer_.patchAt(static_cast<int>(std::floor(exit.x - offset)),
                            static_cast<int>(std::floor(exit.y - offset)), stats);
        return LeafHit{span_, tracer_.topNormal(patch, exit)};
    }

private:
    const MultilevelTracer& tracer_;
    const BaseSurface& base_;
    FrameRay ray_;
    double span_;
    bool floorExit_, cellWalk_;
};

std::optional<ReliefHit> MultilevelTracer::intersect(const Ray& objectRay, const RayQuery& query,
                                                     TraversalStats* statsOut) const {
    TraversalStats stats;
    const FrameRay ray = base_->frameRay(objectRay);
    auto finish = [&](std::optional<ReliefHit> hit) {
        if (statsOut) *statsOut = stats;
        return hit;
    };
    auto makeHit = [&](HitFace face, double t, const glm::dvec3& frameNormal) {
        ReliefHit hit;
        hit.face = face;
        hit.t = t;
        hit.position = objectRay.origin + t * objectRay.direction;
        hit.normal = base_->worldNormal(frameNormal);
        const glm::dvec3 m = base_->mapPoint(ray.at(t));
        hit.uv = {m.x / width_, m.y / height_};
        hit.height = m.z;
        return hit;
    };

    // relief_hit.glsl: mr_enterReliefShell, with the query's range.
    const ShellSpan span = base_->clip(ray);
    const double tNear = std::max(span.tEnter, query.tMin);
    const double tFar = std::min(span.tExit, query.tMax);
    if (span.empty() || tNear > tFar) return finish(std::nullopt);
    const int surfaceFetches = interpolation_ == Interpolation::Biquadratic ? 4 : 1;
    if (span.tEnter >= query.tMin && span.entry != ShellFace::None) {
        // Through a wall, a cap or the bottom: a hit right there when below the surface.
        const glm::dvec3 m = base_->mapPoint(ray.at(tNear));
        const bool bottom = span.entry == ShellFace::Bottom;  // h = 0: always in the solid
        if (bottom || (stats.fetches += surfaceFetches,
                       m.z <= map_.surface(m.x, m.y, addressing_, interpolation_))) {
            stats.stopLevel = 0;
            const HitFace face = span.entry == ShellFace::WallX   ? HitFace::WallX
                                 : span.entry == ShellFace::WallY ? HitFace::WallZ
                                 : bottom                         ? HitFace::Bottom
                                                                  : HitFace::Cap;
            return finish(makeHit(face, tNear, base_->faceNormal(span.entry, ray)));
        }
    }
    // From the range's start on, as the shader works (relief_hit.glsl: mr_enterReliefShell).
    const FrameRay fromEntry{ray.at(tNear), ray.dir};
    const bool floorExit = span.floorExit && tFar == span.tExit;
    const FramePath path(*this, fromEntry, tFar - tNear, floorExit);
    if (auto hit = walkSegments(path, maxIterations_, stats)) {
        return finish(makeHit(HitFace::Top, tNear + hit->t, hit->normal));
    }
    return finish(std::nullopt);
}

}  // namespace microrelief
