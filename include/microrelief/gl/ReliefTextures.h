// The map's data on the GPU, as the relief shaders read it (docs/engine.md, "Textures"):
// the samples, R32F with nearest filtering, clamped (repeating in s on a curved base, whose
// u wraps), and both max pyramids (heightmap/MaxPyramid.h), R32F mip chains of W and H
// rounded up to powers of two down to 1 x 1, nearest-mipmap-nearest, clamped: the aligned
// levels (the maxmip peer's quadtree) and the overlapping windows (the multilevel
// method's). With them, the numbers mr_ReliefMap (relief_map.glsl) holds about them.
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "microrelief/gl/Objects.h"
#include "microrelief/heightmap/HeightMap.h"
#include "microrelief/heightmap/MaxPyramid.h"

namespace microrelief {

// mr_ReliefMap's members, in the order of its constructor.
struct ReliefMapShape {
    glm::ivec2 size{0};         // W, H
    glm::ivec2 pyramidSize{0};  // the finest pyramid level's size
    int levelCount = 0;         // levels down to 1 x 1
    float maxHeight = 0.0f;     // the pyramid's top texel: the surface's max, map units
};

class PyramidBuilder;

// Where a map's max pyramids are built: on the CPU (MaxPyramid, then uploaded) or on the
// GPU from the uploaded samples (gl/PyramidBuilder.h). The texels are the same.
enum class PyramidBuild { Cpu, Gpu };

class ReliefTextures {
public:
    // Builds the max pyramid of `map` for the surface `interpolation` makes of it (wrapped
    // in u when `wrapU`: a curved base) and uploads it with the samples. Throws
    // Error(BadInput) naming `source` when the map exceeds GL_MAX_TEXTURE_SIZE,
    // Error(Runtime) when memory runs out. The GL state it changes (texture bindings,
    // unpack alignment) is restored.
    ReliefTextures(const GL& gl, const HeightMap& map, const std::string& source, bool wrapU,
                   Interpolation interpolation);
    // The same from a pyramid the caller built of `map`.
    ReliefTextures(const GL& gl, const HeightMap& map, const MaxPyramid& pyramid,
                   Interpolation interpolation);
    // The same with the pyramids built on the GPU by `builder` (gl/PyramidBuilder.h): the
    // same texels, from the samples once they are on the GPU.
    ReliefTextures(const GL& gl, const HeightMap& map, const std::string& source, bool wrapU,
                   Interpolation interpolation, PyramidBuilder& builder);

    GLuint samples() const { return samples_.id(); }
    GLuint windowPyramid() const { return windows_.id(); }
    GLuint maxPyramid() const { return aligned_.id(); }

    const ReliefMapShape& shape() const { return shape_; }
    bool wrapsU() const { return wrapU_; }
    Interpolation interpolation() const { return interpolation_; }
    // What the three textures take in GPU memory, bytes: the samples and every level of
    // both pyramids.
    std::size_t gpuBytes() const;
    // The pyramids' level sizes, finest first (pyramidLevelSizes).
    const std::vector<glm::ivec2>& levelSizes() const { return levelSizes_; }

    // The samples inside `rect` (map texels) replaced by `values`, rect.width() a row, row
    // 0 first: an edit from the host. The pyramids are the caller's to bring up to date
    // (PyramidBuilder::update). The GL state it changes is restored.
    void writeSamples(const GL& gl, const TexelRect& rect, const float* values);
    // What the GPU holds, read back (through a framebuffer, as GL ES has it): the samples
    // as a map, a level of the aligned or the overlapping pyramid, row 0 first.
    HeightMap readSamples(const GL& gl) const;
    // The samples inside `rect`, rect.width() a row, row 0 first.
    std::vector<float> readSamples(const GL& gl, const TexelRect& rect) const;
    std::vector<float> readAlignedLevel(const GL& gl, int level) const;
    std::vector<float> readWindowLevel(const GL& gl, int level) const;

private:
    friend class PyramidBuilder;  // writes maxHeight after a build or an update

    void allocate(const GL& gl, const HeightMap& map, int levelCount);
    void upload(const GL& gl, const HeightMap& map, const MaxPyramid& pyramid);

    gl::Texture samples_, windows_, aligned_;
    ReliefMapShape shape_;
    std::vector<glm::ivec2> levelSizes_;
    bool wrapU_ = false;
    Interpolation interpolation_ = Interpolation::Bilinear;
};

// Level `level` (width x height) of a single-channel float texture, read back through a
// framebuffer, row 0 first. The GL state it changes is restored.
std::vector<float> readTextureLevel(const GL& gl, GLuint texture, int level, int width, int height);
// The texels inside `rect` of that level, the same way.
std::vector<float> readTextureRect(const GL& gl, GLuint texture, int level, const TexelRect& rect);

}  // namespace microrelief
