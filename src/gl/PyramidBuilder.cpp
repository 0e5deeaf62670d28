#include "microrelief/gl/PyramidBuilder.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "microrelief/core/Error.h"
#include "microrelief/gl/ShaderProgram.h"
#include "microrelief/gl/StateGuard.h"
#include "microrelief/peers/MaxMipPyramid.h"

namespace microrelief {

namespace {

// The passes as GLSL 3.30 core: plain enough for ES 3.00 too (the shaders test compiles
// them as both), which a browser's WebGL 2 runs.
constexpr const char* kVersion = "330 core";

// The windows' finest level of a map this tall or taller is made in bands of this many
// rows through a scratch texture of finest bounds (band + 1 rows of the map's width, R16F:
// at most 0.5 bytes a map texel beside the 6.7 the textures take, within the 8):
// each bound made once, where window_finest.frag makes it four times, once for each window
// over it (measured on llvmpipe at 4096: half the time of the whole build).
constexpr int kBandRows = 64, kBandsFrom = 4 * kBandRows;

gl::Program passProgram(const GL& gl, const std::filesystem::path& shaderDir,
                        const gl::Shader& vertex, const char* fragment, const char* name) {
    const gl::Shader shader = gl::compileShader(
        gl, GL_FRAGMENT_SHADER,
        assembleShader(shaderDir / "pyramid" / fragment, kVersion, {}, {shaderDir}));
    return gl::linkProgram(gl, vertex, shader, name);
}

// A sampler uniform on unit 0, set once.
void samplerOnUnitZero(const GL& gl, const gl::Program& program, const char* name) {
    gl.UseProgram(program.id());
    gl.Uniform1i(gl::uniform(gl, program, name), 0);
}

// Overlapping or touching rectangles become their bounding box, until none do: many dabs
// (an undone stroke) draw each coarse texel once, not once per dab. Drawing a texel that
// did not change is harmless: it gets the value it has.
void mergeTouching(std::vector<TexelRect>& rects) {
    for (bool merged = true; merged;) {
        merged = false;
        for (std::size_t a = 0; a < rects.size() && !merged; ++a) {
            for (std::size_t b = a + 1; b < rects.size() && !merged; ++b) {
                const TexelRect &r = rects[a], &s = rects[b];
                if (r.x0 <= s.x1 && s.x0 <= r.x1 && r.y0 <= s.y1 && s.y0 <= r.y1) {
                    rects[a] = {std::min(r.x0, s.x0), std::min(r.y0, s.y0), std::max(r.x1, s.x1),
                                std::max(r.y1, s.y1)};
                    rects.erase(rects.begin() + static_cast<std::ptrdiff_t>(b));
                    merged = true;
                }
            }
        }
    }
}

// Every region's rectangles of a level together, merged.
PyramidRegions mergeRegions(const std::vector<PyramidRegions>& all, int levels) {
    PyramidRegions merged;
    merged.aligned.resize(levels);
    merged.windows.resize(levels);
    for (const PyramidRegions& r : all) {
        for (int level = 0; level < levels; ++level) {
            merged.aligned[level].insert(merged.aligned[level].end(), r.aligned[level].begin(),
                                         r.aligned[level].end());
            merged.windows[level].insert(merged.windows[level].end(), r.windows[level].begin(),
                                         r.windows[level].end());
        }
    }
    for (int level = 0; level < levels; ++level) {
        mergeTouching(merged.aligned[level]);
        mergeTouching(merged.windows[level]);
    }
    return merged;
}

PyramidRegions wholeLevels(const std::vector<glm::ivec2>& sizes) {
    PyramidRegions whole;
    for (const glm::ivec2 size : sizes) {
        whole.aligned.push_back({{0, 0, size.x, size.y}});
        whole.windows.push_back({{0, 0, size.x, size.y}});
    }
    return whole;
}

}  // namespace

PyramidBuilder::PyramidBuilder(const GL& gl, const std::filesystem::path& shaderDir)
    : gl_(gl), shaderDir_(shaderDir) {
    passVertex_ = gl::compileShader(gl, GL_VERTEX_SHADER,
                                    assembleShader(shaderDir / "pyramid" / "pass.vert", kVersion));
    const gl::Shader& vertex = passVertex_;
    windowFinest_ =
        passProgram(gl, shaderDir, vertex, "window_finest.frag", "pyramid (finest windows)");
    windowBlocks_ =
        passProgram(gl, shaderDir, vertex, "window_blocks.frag", "pyramid (windows of bounds)");
    blocksMapSize_ = gl::uniform(gl, windowBlocks_, "mapSize");
    blocksFirstRow_ = gl::uniform(gl, windowBlocks_, "firstRow");
    windows_ = passProgram(gl, shaderDir, vertex, "window_level.frag", "pyramid (windows)");
    alignedFinest_ =
        passProgram(gl, shaderDir, vertex, "finest_level.frag", "pyramid (finest aligned)");
    aligned_ = passProgram(gl, shaderDir, vertex, "aligned_level.frag", "pyramid (aligned)");
    for (const gl::Program* finest : {&windowFinest_, &alignedFinest_}) {
        const int k = finest == &windowFinest_ ? 0 : 1;
        finestMapSize_[k] = gl::uniform(gl, *finest, "mapSize");
        finestWrapU_[k] = gl::uniform(gl, *finest, "wrapU");
        finestScale_[k] = gl::uniform(gl, *finest, "scaleExponent");
    }
    alignedOrigin_ = gl::uniform(gl, alignedFinest_, "texelOrigin");
    windowsLevel_ = gl::uniform(gl, windows_, "level");
    const gl::StateGuard saved(gl);
    samplerOnUnitZero(gl, windowFinest_, "heights");
    samplerOnUnitZero(gl, alignedFinest_, "heights");
    samplerOnUnitZero(gl, windows_, "windows");
    samplerOnUnitZero(gl, windowBlocks_, "bounds");
    samplerOnUnitZero(gl, aligned_, "aligned");
    vertexArray_ = gl::VertexArray::create(gl);
    framebuffer_ = gl::Framebuffer::create(gl);
}

void PyramidBuilder::build(ReliefTextures& textures) {
    drawAll(textures);
    settleScale(textures);
}

void PyramidBuilder::buildAligned(ReliefTextures& textures) {
    const gl::PassGuard saved(gl_);
    begin();
    drawAligned(textures,
                wholeLevels(maxMipLevelSizes(textures.shape_.size.x, textures.shape_.size.y)));
}

void PyramidBuilder::update(ReliefTextures& textures, const TexelRect& changed) {
    update(textures, std::vector<TexelRect>{changed});
}

void PyramidBuilder::update(ReliefTextures& textures, const std::vector<TexelRect>& changed) {
    const glm::ivec2 map = textures.shape_.size;
    const std::vector<glm::ivec2>& windowSizes = textures.levelSizes();
    const std::vector<glm::ivec2> alignedSizes = maxMipLevelSizes(map.x, map.y);
    std::vector<PyramidRegions> blocks, aligned;
    for (const TexelRect& rect : changed) {
        blocks.push_back(pyramidUpdateRegions(windowSizes, map.x, map.y, textures.wrapsU(), rect));
        aligned.push_back(
            pyramidUpdateRegions(alignedSizes, map.x, map.y, textures.wrapsU(), rect));
    }
    {
        const gl::PassGuard saved(gl_);
        begin();
        drawWindows(textures, mergeRegions(blocks, static_cast<int>(windowSizes.size())).windows);
        if (textures.hasMaxMipPyramid())
            drawAligned(textures, mergeRegions(aligned, static_cast<int>(alignedSizes.size())));
    }
    settleScale(textures);
}

void PyramidBuilder::begin() {
    gl_.BindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
    gl_.BindVertexArray(vertexArray_.id());
    gl_.ActiveTexture(GL_TEXTURE0);
}

void PyramidBuilder::drawAll(ReliefTextures& textures) {
    const gl::PassGuard saved(gl_);
    begin();
    drawWindows(textures, wholeLevels(textures.levelSizes()).windows);
    if (textures.hasMaxMipPyramid()) {
        drawAligned(textures,
                    wholeLevels(maxMipLevelSizes(textures.shape_.size.x, textures.shape_.size.y)));
    }
}

void PyramidBuilder::attach(GLuint texture, int level) {
    gl_.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture, level);
}

void PyramidBuilder::draw(const TexelRect& rect) {
    // The viewport is the rectangle: the triangle covers it, and gl_FragCoord names the
    // level's texels (window coordinates count from the attachment's origin).
    gl_.Viewport(rect.x0, rect.y0, rect.width(), rect.height());
    gl_.DrawArrays(GL_TRIANGLES, 0, 3);
}

void PyramidBuilder::useFinest(const gl::Program& program, int k, const ReliefTextures& textures) {
    gl_.UseProgram(program.id());
    gl_.Uniform2i(finestMapSize_[k], textures.shape_.size.x, textures.shape_.size.y);
    gl_.Uniform1i(finestWrapU_[k], textures.wrapsU() ? 1 : 0);
    gl_.Uniform1i(finestScale_[k], textures.scaleExponent_);
    gl_.BindTexture(GL_TEXTURE_2D, textures.samples());
}

void PyramidBuilder::drawWindowBands(ReliefTextures& textures) {
    // Each band: its texels' bounds (and the next row's) into the scratch texture, then
    // the band's windows from them.
    const glm::ivec2 map = textures.shape_.size;
    if (!scratch_ || scratchWidth_ != map.x) {
        scratch_ = gl::Texture::create(gl_);
        gl_.BindTexture(GL_TEXTURE_2D, scratch_.id());
        gl_.TexImage2D(GL_TEXTURE_2D, 0, GL_R16F, map.x, kBandRows + 1, 0, GL_RED, GL_HALF_FLOAT,
                       nullptr);
        gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
        scratchWidth_ = map.x;
    }
    for (int row = 0; row < map.y; row += kBandRows) {
        const int rows = std::min(kBandRows, map.y - row);
        attach(scratch_.id(), 0);
        useFinest(alignedFinest_, 1, textures);
        gl_.Uniform2i(alignedOrigin_, 0, row);
        draw({0, 0, map.x, rows + 1});
        attach(textures.windowPyramid(), 0);
        gl_.UseProgram(windowBlocks_.id());
        gl_.Uniform2i(blocksMapSize_, map.x, map.y);
        gl_.Uniform1i(blocksFirstRow_, row);
        gl_.BindTexture(GL_TEXTURE_2D, scratch_.id());
        draw({0, row, map.x, row + rows});
    }
    gl_.UseProgram(alignedFinest_.id());
    gl_.Uniform2i(alignedOrigin_, 0, 0);
}

void PyramidBuilder::drawWindows(ReliefTextures& textures,
                                 const std::vector<std::vector<TexelRect>>& windows) {
    const GLuint texture = textures.windowPyramid();
    const glm::ivec2 map = textures.shape_.size;
    for (int level = 0; level < static_cast<int>(windows.size()); ++level) {
        if (windows[level].empty()) continue;
        attach(texture, level);
        if (level == 0) {
            if (gl_.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
                throwRuntime(
                    "this GL cannot render into the R16F max pyramid (incomplete framebuffer)");
            if (map.y >= kBandsFrom && windows[0].size() == 1 &&
                windows[0][0] == TexelRect{0, 0, map.x, map.y}) {
                drawWindowBands(textures);
                continue;
            }
            useFinest(windowFinest_, 0, textures);
        } else {
            gl_.UseProgram(windows_.id());
            gl_.Uniform1i(windowsLevel_, level - 1);
            gl_.BindTexture(GL_TEXTURE_2D, texture);
            // Read level k - 1, write level k of the same texture: only the level read is
            // in the sampled range, so there is no feedback loop.
            gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_BASE_LEVEL, 0);
            gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, level - 1);
        }
        for (const TexelRect& rect : windows[level]) draw(rect);
    }
    gl_.BindTexture(GL_TEXTURE_2D, texture);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, textures.shape_.levelCount - 1);
}

void PyramidBuilder::drawAligned(ReliefTextures& textures, const PyramidRegions& regions) {
    const GLuint texture = textures.maxPyramid();
    const int levels = static_cast<int>(regions.aligned.size());
    for (int level = 0; level < levels; ++level) {
        if (regions.aligned[level].empty()) continue;
        attach(texture, level);
        if (level == 0) {
            useFinest(alignedFinest_, 1, textures);
        } else {
            gl_.UseProgram(aligned_.id());
            gl_.BindTexture(GL_TEXTURE_2D, texture);
            gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_BASE_LEVEL, level - 1);
            gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, level - 1);
        }
        for (const TexelRect& rect : regions.aligned[level]) draw(rect);
    }
    gl_.BindTexture(GL_TEXTURE_2D, texture);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_BASE_LEVEL, 0);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, levels - 1);
}

void PyramidBuilder::buildConeMap(ReliefTextures& textures) {
    // Rows a draw: a draw is one texel's walk per pixel, thousands of reads where the map is
    // rough, and a long draw can trip a desktop driver's watchdog.
    constexpr int kConeBandRows = 32;
    const glm::ivec2 map = textures.shape_.size;
    if (textures.shape_.tiles != glm::ivec2(1))
        throwRuntime("a cone map is built for an untiled map only");
    // The walk's stack holds 22 levels (cone_map.frag), a map of 2^21 a side: past any
    // GL's textures.
    if (std::max(map.x, map.y) > (1 << 21))
        throwRuntime("a cone map is built on the GPU for maps of at most 2^21 a side");
    if (!coneMap_) {
        coneMap_ = passProgram(gl_, shaderDir_, passVertex_, "cone_map.frag", "cone map");
        const gl::StateGuard saved(gl_);
        gl_.UseProgram(coneMap_.id());
        gl_.Uniform1i(gl::uniform(gl_, coneMap_, "heights"), 0);
        gl_.Uniform1i(gl::uniform(gl_, coneMap_, "aligned"), 1);
    }
    const bool hadQuadtree = textures.hasMaxMipPyramid();
    if (!hadQuadtree) {
        textures.allocateAligned(gl_);
        buildAligned(textures);
    }
    const GLuint cones = textures.allocateConeMap(gl_, ReliefTextures::ConeKind::Conservative).id();
    {
        const gl::PassGuard saved(gl_);
        begin();
        attach(cones, 0);
        if (gl_.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            throwRuntime("this GL cannot render into the RG16F cone map (incomplete framebuffer)");
        gl_.UseProgram(coneMap_.id());
        gl_.Uniform2i(gl::uniform(gl_, coneMap_, "mapSize"), map.x, map.y);
        gl_.Uniform1i(gl::uniform(gl_, coneMap_, "levelCount"),
                      static_cast<int>(maxMipLevelSizes(map.x, map.y).size()));
        gl_.Uniform1i(gl::uniform(gl_, coneMap_, "scaleExponent"), textures.scaleExponent_);
        gl_.ActiveTexture(GL_TEXTURE1);
        gl_.BindTexture(GL_TEXTURE_2D, textures.maxPyramid());
        gl_.ActiveTexture(GL_TEXTURE0);
        gl_.BindTexture(GL_TEXTURE_2D, textures.samples());
        for (int row = 0; row < map.y; row += kConeBandRows)
            draw({0, row, map.x, std::min(row + kConeBandRows, map.y)});
        attach(0, 0);
    }
    if (!hadQuadtree) textures.aligned_.reset();
}

float PyramidBuilder::readTop(const ReliefTextures& textures) {
    const gl::PassGuard saved(gl_);
    gl_.BindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
    attach(textures.windowPyramid(), textures.shape_.levelCount - 1);
    gl_.ReadBuffer(GL_COLOR_ATTACHMENT0);
    gl_.PixelStorei(GL_PACK_ALIGNMENT, 4);
    float top = 0.0f;
    gl_.ReadPixels(0, 0, 1, 1, GL_RED, GL_FLOAT, &top);
    attach(0, 0);
    return top;
}

void PyramidBuilder::settleScale(ReliefTextures& textures) {
    // The top, read back, is the map's largest sample rounded up (MaxPyramid.h), divided by
    // 2^S. S must be pyramidScaleExponent of it; where the texels were drawn with another
    // (the top moved to another binade since the last build, or past a half's range), all
    // of them are drawn again with the S the top asks for. Two passes settle it in
    // practice (a top that went to +inf or to the least bound takes a few more); each is a
    // valid bound, only not the one MaxPyramid keeps.
    for (int attempt = 0;; ++attempt) {
        const int s = textures.scaleExponent_;
        const float stored = readTop(textures);
        const float smallest = std::ldexp(1.0f, -14);
        int fitting = s;
        if (std::isinf(stored)) {
            fitting = s + 16;
        } else if (stored == 0.0f) {
            fitting = pyramidScaleExponent(0.0f);
        } else if (stored <= smallest) {
            fitting = s - 28;  // maybe raised to the least bound: look again with less
        } else {
            fitting = pyramidScaleExponent(std::ldexp(stored, s));
        }
        fitting = std::clamp(fitting, pyramidScaleExponent(0.0f), pyramidScaleExponent(3e38f));
        if (fitting == s || attempt == 16) {
            textures.shape_.maxHeight = std::ldexp(stored, s);
            return;
        }
        textures.scaleExponent_ = fitting;
        drawAll(textures);
    }
}

}  // namespace microrelief
