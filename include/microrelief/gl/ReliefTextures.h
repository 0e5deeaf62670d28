// The map's data on the GPU, as the relief shaders read it (docs/engine.md, "Textures"):
// the samples, R32F with nearest filtering, clamped (repeating in s on a curved base, whose
// u wraps, and in both directions tiled: relief_map.glsl's MICRORELIEF_TILING), and both
// max pyramids (heightmap/MaxPyramid.h), R32F mip chains of W and H
// rounded up to powers of two down to 1 x 1, nearest-mipmap-nearest, clamped: the aligned
// levels (the maxmip peer's quadtree) and the overlapping windows (the multilevel
// method's). With them, the numbers mr_ReliefMap (relief_map.glsl) holds about them.
#pragma once

#include <string>

#include <glm/glm.hpp>

#include "microrelief/gl/Objects.h"
#include "microrelief/heightmap/HeightMap.h"
#include "microrelief/heightmap/MaxPyramid.h"

namespace microrelief {

// mr_ReliefMap's members, in the order of its constructor.
struct ReliefMapShape {
    glm::ivec2 size{0};         // W, H of the whole map: N W, M H tiled N x M
    glm::ivec2 pyramidSize{0};  // the finest pyramid level's size
    int levelCount = 0;         // levels down to 1 x 1
    float maxHeight = 0.0f;     // the pyramid's top texel: the surface's max, map units
    glm::ivec2 tiles{1, 1};     // N, M: the textures hold one tile
};

class ReliefTextures {
public:
    // Builds the max pyramid of `map` for the surface `interpolation` makes of it (wrapped
    // in u when `wrapU`: a curved base) and uploads it with the samples. Throws
    // Error(BadInput) naming `source` when the map exceeds GL_MAX_TEXTURE_SIZE,
    // Error(Runtime) when memory runs out. The GL state it changes (texture bindings,
    // unpack alignment) is restored.
    ReliefTextures(const GL& gl, const HeightMap& map, const std::string& source, bool wrapU,
                   Interpolation interpolation, glm::ivec2 tiles = {1, 1});
    // The same from a pyramid the caller built of `map`.
    ReliefTextures(const GL& gl, const HeightMap& map, const MaxPyramid& pyramid,
                   Interpolation interpolation);

    GLuint samples() const { return samples_.id(); }
    GLuint windowPyramid() const { return windows_.id(); }
    GLuint maxPyramid() const { return aligned_.id(); }

    const ReliefMapShape& shape() const { return shape_; }
    bool wrapsU() const { return wrapU_; }
    glm::ivec2 tiles() const { return shape_.tiles; }
    Interpolation interpolation() const { return interpolation_; }

private:
    void upload(const GL& gl, const HeightMap& map, const MaxPyramid& pyramid);

    gl::Texture samples_, windows_, aligned_;
    ReliefMapShape shape_;
    bool wrapU_ = false;
    Interpolation interpolation_ = Interpolation::Bilinear;
};

}  // namespace microrelief
