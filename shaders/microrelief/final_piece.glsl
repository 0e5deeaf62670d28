// final_piece.glsl: the first root over a final piece of subdivision, where the gap g
// between the surface and the ray is held to the parabola through g(0), g(1/2), g(1)
// (the leaves of leaf_walk.glsl and biquadratic_patch.glsl; C++: SurfacePatch.h,
// mr_parabolaFirstRoot).
#ifndef MICRORELIEF_FINAL_PIECE_GLSL
#define MICRORELIEF_FINAL_PIECE_GLSL

#include "precision.glsl"

// The first s in [0, 1] where the parabola through (0, ga), (1/2, gm), (1, gb) reaches 0
// (the ray on or under the surface), or -1. A sign change at the ends or the middle
// gives the root by interpolation; without one, a concave parabola that reaches 0 is a
// ray touching the surface: a hit in the closed solid, at its first root.
float mr_parabolaFirstRoot(float ga, float gm, float gb) {
    if (ga >= 0.0) return 0.0;
    if (gm >= 0.0) return 0.5 * ga / (ga - gm);
    if (gb >= 0.0) return 0.5 + 0.5 * gm / (gm - gb);
    // g(s) = ga + B s + A s^2.
    float A = 2.0 * (ga - 2.0 * gm + gb), B = -3.0 * ga + 4.0 * gm - gb;
    if (A < 0.0) {
        float vertex = -B / (2.0 * A), disc = B * B - 4.0 * A * ga;
        if (vertex > 0.0 && vertex < 1.0 && disc >= 0.0) return clamp((-B + sqrt(disc)) / (2.0 * A), 0.0, vertex);
    }
    return -1.0;
}

#endif
