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
    run(textures, whole);
}

void PyramidBuilder::update(ReliefTextures& textures, const TexelRect& changed) {
    const ReliefMapShape& shape = textures.shape();
    run(textures, pyramidUpdateRegions(shape.size.x, shape.size.y, textures.wrapsU(), changed));
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

void PyramidBuilder::run(ReliefTextures& textures, const PyramidRegions& regions) {
    const gl::PassGuard saved(gl_);
    gl_.BindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
    gl_.BindVertexArray(vertexArray_.id());
    gl_.ActiveTexture(GL_TEXTURE0);
    const GLuint aligned = textures.maxPyramid(), windows = textures.windowPyramid();
    const int levels = static_cast<int>(regions.aligned.size());
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
