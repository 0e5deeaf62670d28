#include "microrelief/gl/PyramidBuilder.h"

#include <string>

#include "microrelief/core/Error.h"
#include "microrelief/gl/ShaderProgram.h"
#include "microrelief/gl/StateGuard.h"

namespace microrelief {

namespace {

// The passes as GLSL 3.30 core: plain enough for ES 3.00 too (the shaders test compiles
// them as both), which a browser's WebGL 2 runs.
constexpr const char* kVersion = "330 core";

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

}  // namespace

PyramidBuilder::PyramidBuilder(const GL& gl, const std::filesystem::path& shaderDir) : gl_(gl) {
    const gl::Shader vertex = gl::compileShader(
        gl, GL_VERTEX_SHADER, assembleShader(shaderDir / "pyramid" / "pass.vert", kVersion));
    finest_ = passProgram(gl, shaderDir, vertex, "finest_level.frag", "pyramid (finest level)");
    windows_ = passProgram(gl, shaderDir, vertex, "window_level.frag", "pyramid (windows)");
    aligned_ = passProgram(gl, shaderDir, vertex, "aligned_level.frag", "pyramid (aligned)");
    finestMapSize_ = gl::uniform(gl, finest_, "mapSize");
    finestWrapU_ = gl::uniform(gl, finest_, "wrapU");
    windowsLevel_ = gl::uniform(gl, windows_, "level");
    alignedLevel_ = gl::uniform(gl, aligned_, "level");
    const gl::StateGuard saved(gl);
    samplerOnUnitZero(gl, finest_, "heights");
    samplerOnUnitZero(gl, windows_, "aligned");
    samplerOnUnitZero(gl, aligned_, "windows");
    vertexArray_ = gl::VertexArray::create(gl);
    framebuffer_ = gl::Framebuffer::create(gl);
}

void PyramidBuilder::build(ReliefTextures& textures) {
    PyramidRegions whole;
    for (const glm::ivec2 size : textures.levelSizes()) {
        whole.aligned.push_back({{0, 0, size.x, size.y}});
        whole.windows.push_back({{0, 0, size.x, size.y}});
    }
    run(textures, std::vector<PyramidRegions>{whole});
}

void PyramidBuilder::update(ReliefTextures& textures, const TexelRect& changed) {
    update(textures, std::vector<TexelRect>{changed});
}

void PyramidBuilder::update(ReliefTextures& textures, const std::vector<TexelRect>& changed) {
    const ReliefMapShape& shape = textures.shape();
    std::vector<PyramidRegions> regions;
    for (const TexelRect& rect : changed)
        regions.push_back(
            pyramidUpdateRegions(shape.size.x, shape.size.y, textures.wrapsU(), rect));
    run(textures, regions);
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

void PyramidBuilder::run(ReliefTextures& textures, const std::vector<PyramidRegions>& all) {
    const gl::PassGuard saved(gl_);
    gl_.BindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
    gl_.BindVertexArray(vertexArray_.id());
    gl_.ActiveTexture(GL_TEXTURE0);
    const GLuint aligned = textures.maxPyramid(), windows = textures.windowPyramid();
    const int levels = textures.shape().levelCount;
    // Level by level, every region's texels of a level before the next level's.
    PyramidRegions regions;
    regions.aligned.resize(levels);
    regions.windows.resize(levels);
    for (const PyramidRegions& r : all) {
        for (int level = 0; level < levels; ++level) {
            regions.aligned[level].insert(regions.aligned[level].end(), r.aligned[level].begin(),
                                          r.aligned[level].end());
            regions.windows[level].insert(regions.windows[level].end(), r.windows[level].begin(),
                                          r.windows[level].end());
        }
    }
    for (int level = 0; level < levels; ++level) {
        mergeTouching(regions.aligned[level]);
        mergeTouching(regions.windows[level]);
    }
    for (int level = 0; level < levels; ++level) {
        if (!regions.aligned[level].empty()) {
            attach(aligned, level);
            if (level == 0) {
                gl_.UseProgram(finest_.id());
                gl_.Uniform2i(finestMapSize_, textures.shape().size.x, textures.shape().size.y);
                gl_.Uniform1i(finestWrapU_, textures.wrapsU() ? 1 : 0);
                gl_.BindTexture(GL_TEXTURE_2D, textures.samples());
            } else {
                gl_.UseProgram(aligned_.id());
                gl_.Uniform1i(alignedLevel_, level - 1);
                gl_.BindTexture(GL_TEXTURE_2D, windows);
            }
            if (level == 0 && gl_.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
                throwRuntime(
                    "this GL cannot render into the R32F max pyramid (incomplete framebuffer)");
            for (const TexelRect& rect : regions.aligned[level]) draw(rect);
        }
        if (!regions.windows[level].empty()) {
            attach(windows, level);
            gl_.UseProgram(windows_.id());
            gl_.Uniform1i(windowsLevel_, level);
            gl_.BindTexture(GL_TEXTURE_2D, aligned);
            for (const TexelRect& rect : regions.windows[level]) draw(rect);
        }
    }
    // The top texel: the surface's maximum (the box and mr_ReliefMap need it).
    attach(aligned, levels - 1);
    gl_.ReadBuffer(GL_COLOR_ATTACHMENT0);
    gl_.PixelStorei(GL_PACK_ALIGNMENT, 4);
    float top = 0.0f;
    gl_.ReadPixels(0, 0, 1, 1, GL_RED, GL_FLOAT, &top);
    attach(0, 0);
    textures.shape_.maxHeight = top;
}

}  // namespace microrelief
