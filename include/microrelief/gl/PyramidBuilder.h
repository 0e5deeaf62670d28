// The max pyramids built on the GPU from the samples texture, in fragment passes (GLSL
// 3.30 core, and GLSL ES 3.00 as they stand: shaders/pyramid/), texel for texel what
// MaxPyramid (BoundPrecision::Half) keeps, bit for bit: the same finest bounds
// (microrelief/pyramid_bound.glsl, integer arithmetic on the floats' bits, rounded up to
// halves), the same level sizes, wrapped in u on a curved base, for either interpolation;
// stored as R16F halves divided by 2^S (MaxPyramid.h: pyramidScaleExponent).
//
// The passes, one draw each over the texels they compute:
//  * the windows' finest level: on maps of 256 rows or more in bands of 64 rows, the band's
//    finest bounds from the 3 x 3 samples round each texel into a scratch texture (the
//    band's width by 65 rows), then each window the max of its 2 x 2; elsewhere (small
//    maps, edits) each window from the 4 x 4 samples round its 2 x 2 texels at once;
//  * each coarser level of windows from the level below (windows 2p, 2p + 2 of it, and
//    the odd last block's window where a level's last block absorbs it);
//  * where maxmip runs, its quadtree (peers/MaxMipPyramid.h, padded to powers of two): its
//    finest level from the 3 x 3 samples round each texel (0 in the padding), each coarser
//    level the max of four children of the level below.
// A level is drawn from the level below it of the same texture with the sampled range
// ending at the level read, so no pass samples what it writes (no feedback loop), and the
// only scratch memory is the band's. After a change inside a rectangle of the samples only
// the texels whose bounds read it are drawn again, on every level (pyramidUpdateRegions).
// Then the top texel is read back: the map's new maximum, which the box and the tracer
// need, and the check that S still fits it (when the top moved to another binade, every
// texel is drawn again with the new S).
//
// And the `cone` peer's conservative cone map (peers/ConeMap.h), from the samples and the
// quadtree: shaders/pyramid/cone_map.frag, the CPU build's walk per texel in float
// arithmetic, each rounding towards narrower cones, in bands of rows.
#pragma once

#include <filesystem>
#include <vector>

#include "microrelief/gl/Objects.h"
#include "microrelief/gl/ReliefTextures.h"
#include "microrelief/core/heightmap/MaxPyramid.h"

namespace microrelief {

class PyramidBuilder {
public:
    // Compiles the passes from `shaderDir` (the folder holding pyramid/ and microrelief/).
    // Throws Error(Runtime) when they do not compile; a build throws it where the GL cannot
    // render into R16F.
    PyramidBuilder(const GL& gl, const std::filesystem::path& shaderDir);

    // Every texel of the pyramids of `textures` (the windows, and the aligned pyramid where
    // it has one), from its samples; then its shape's maxHeight. The GL state it changes is
    // restored (gl::PassGuard).
    void build(ReliefTextures& textures);
    // The aligned pyramid alone (just made for maxmip), with the windows' S.
    void buildAligned(ReliefTextures& textures);
    // After the samples inside `changed` (map texels; clipped to the map) changed: the
    // texels whose bounds read them, on every level, and maxHeight.
    void update(ReliefTextures& textures, const TexelRect& changed);
    // The same after changes inside several rectangles (a dab over a curved base's seam).
    void update(ReliefTextures& textures, const std::vector<TexelRect>& changed);
    // The conservative cone map of `textures` (ConeKind::Conservative), made or made again
    // from its samples: the apexes bit for bit the CPU build's, each ratio at most the
    // CPU's (mostly the same; the CPU build is the GL tests' reference). Reads maxmip's
    // quadtree, made for the pass and dropped after where the textures had none. An
    // untiled map (throws Error(Runtime) for a tiled one). The GL state it changes is
    // restored.
    void buildConeMap(ReliefTextures& textures);

private:
    void begin();
    void drawAll(ReliefTextures& textures);
    void drawWindowBands(ReliefTextures& textures);
    void drawWindows(ReliefTextures& textures, const std::vector<std::vector<TexelRect>>& windows);
    void drawAligned(ReliefTextures& textures, const PyramidRegions& regions);
    void useFinest(const gl::Program& program, int k, const ReliefTextures& textures);
    float readTop(const ReliefTextures& textures);
    void settleScale(ReliefTextures& textures);
    void attach(GLuint texture, int level);
    void draw(const TexelRect& rect);

    const GL& gl_;
    gl::Program windowFinest_, windowBlocks_, windows_, alignedFinest_, aligned_;
    gl::Shader passVertex_;  // pass.vert, which every pass links
    gl::Program coneMap_;    // linked on the first cone map
    std::filesystem::path shaderDir_;
    GLint finestMapSize_[2] = {-1, -1}, finestWrapU_[2] = {-1, -1}, finestScale_[2] = {-1, -1};
    GLint windowsLevel_ = -1, alignedOrigin_ = -1, blocksMapSize_ = -1, blocksFirstRow_ = -1;
    gl::Texture scratch_;  // a band's finest bounds (drawWindowBands)
    int scratchWidth_ = 0;
    gl::VertexArray vertexArray_;
    gl::Framebuffer framebuffer_;
};

}  // namespace microrelief
