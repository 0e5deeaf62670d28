// Both max pyramids built on the GPU from the samples texture, in fragment passes (GLSL
// 3.30 core, and GLSL ES 3.00 as they stand: shaders/pyramid/), texel for texel what
// MaxPyramid builds on the CPU, bit for bit (heightmap/MaxPyramid.h): the same finest
// level (microrelief/pyramid_bound.glsl, integer arithmetic on the floats' bits), the same
// padding and level sizes, wrapped in u on a curved base, for either interpolation.
//
// The passes, one draw each over the texels they compute:
//  * the aligned pyramid's finest level from the 3 x 3 samples around each texel (0 in
//    the padding);
//  * on each level k, the windows from the aligned texels (max of 2 x 2);
//  * the aligned level k + 1 from the windows of level k: its texel (p, q) is window
//    (2p, 2q), the max of its four children, one read.
// No pass reads the texture it writes, so there is no feedback loop to avoid, and no
// scratch memory. After a change inside a rectangle of the samples only the texels whose
// bounds read it are drawn again, on every level (pyramidUpdateRegions). Then the top
// texel is read back: the map's new maximum, which the box and the tracer need.
#pragma once

#include <filesystem>
#include <vector>

#include "microrelief/gl/Objects.h"
#include "microrelief/gl/ReliefTextures.h"
#include "microrelief/heightmap/MaxPyramid.h"

namespace microrelief {

class PyramidBuilder {
public:
    // Compiles the passes from `shaderDir` (the folder holding pyramid/ and microrelief/).
    // Throws Error(Runtime) when they do not compile, or the GL cannot render to R32F.
    PyramidBuilder(const GL& gl, const std::filesystem::path& shaderDir);

    // Every texel of both pyramids of `textures`, from its samples; then its shape's
    // maxHeight. The GL state it changes is restored (gl::PassGuard).
    void build(ReliefTextures& textures);
    // After the samples inside `changed` (map texels; clipped to the map) changed: the
    // texels whose bounds read them, on every level, and maxHeight.
    void update(ReliefTextures& textures, const TexelRect& changed);
    // The same after changes inside several rectangles (a dab over a curved base's seam).
    void update(ReliefTextures& textures, const std::vector<TexelRect>& changed);

private:
    void run(ReliefTextures& textures, const std::vector<PyramidRegions>& regions);
    void attach(GLuint texture, int level);
    void draw(const TexelRect& rect);

    const GL& gl_;
    gl::Program finest_, windows_, aligned_;
    GLint finestMapSize_ = -1, finestWrapU_ = -1, windowsLevel_ = -1, alignedLevel_ = -1;
    gl::VertexArray vertexArray_;
    gl::Framebuffer framebuffer_;
};

}  // namespace microrelief
