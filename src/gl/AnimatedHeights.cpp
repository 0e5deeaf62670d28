#include "microrelief/gl/AnimatedHeights.h"

#include <algorithm>
#include <cmath>

#include "microrelief/core/Error.h"
#include "microrelief/gl/ShaderProgram.h"
#include "microrelief/gl/StateGuard.h"
#include "microrelief/gl/ReliefRenderer.h"

namespace microrelief {

namespace {

// The fields' angular speeds, radians a second (animate.frag): the four waves, the
// ripples' rings, the flood's water level; the flood's waves run at twice the waves'.
constexpr double kWaveSpeeds[4] = {1.1, 1.7, 2.3, 0.9};
constexpr double kRippleSpeed = 5.0;
constexpr double kFloodLevelSpeed = 0.6;

// speed * seconds modulo 2 pi, in double: exact to 1e-6 rad within kMaxAnimationSeconds.
float phase(double speed, double seconds) {
    return static_cast<float>(std::fmod(speed * seconds, 6.283185307179586));
}

}  // namespace

void AnimatedHeights::checkName(const std::string& name) {
    const auto& list = animatedFieldNames();
    if (std::find(list.begin(), list.end(), name) != list.end()) return;
    std::string known;
    for (const std::string& n : list) known += (known.empty() ? "" : ", ") + n;
    throwBadInput("unknown {animation} '" + name + "' (expected " + known + ")");
}

AnimatedHeights::AnimatedHeights(const GL& gl, const std::filesystem::path& shaderDir,
                                 const std::string& name)
    : gl_(gl), name_(name) {
    checkName(name);
    const auto& list = animatedFieldNames();
    field_ = static_cast<int>(std::find(list.begin(), list.end(), name) - list.begin());
    const std::string version = "330 core";
    const gl::Shader vertex = gl::compileShader(
        gl, GL_VERTEX_SHADER, assembleShader(shaderDir / "pyramid" / "pass.vert", version));
    const gl::Shader fragment = gl::compileShader(
        gl, GL_FRAGMENT_SHADER,
        assembleShader(shaderDir / "edit" / "animate.frag", version, {}, {shaderDir}));
    program_ = gl::linkProgram(gl, vertex, fragment, "animated heights (" + name + ")");
    mapSize_ = gl::uniform(gl, program_, "mapSize");
    wavePhase_ = gl::uniform(gl, program_, "wavePhase");
    floodWavePhase_ = gl::uniform(gl, program_, "floodWavePhase");
    ripplePhase_ = gl::uniform(gl, program_, "ripplePhase");
    floodPhase_ = gl::uniform(gl, program_, "floodPhase");
    fieldLocation_ = gl::uniform(gl, program_, "field");
    const gl::StateGuard saved(gl);
    gl.UseProgram(program_.id());
    gl.Uniform1i(gl::uniform(gl, program_, "base"), 0);
    vertexArray_ = gl::VertexArray::create(gl);
    framebuffer_ = gl::Framebuffer::create(gl);
}

void AnimatedHeights::evaluate(ReliefRenderer& renderer, double seconds) {
    ReliefTextures* textures = renderer.textures();
    if (!textures || !std::isfinite(seconds)) return;
    const glm::ivec2 size = textures->shape().size;
    {
        const gl::PassGuard saved(gl_);
        gl_.ActiveTexture(GL_TEXTURE0);
        gl_.BindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
        gl_.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D,
                                 textures->samples(), 0);
        if (baseSize_ != size) {  // the ground: the map's samples, copied once
            base_ = gl::Texture::create(gl_);
            gl_.BindTexture(GL_TEXTURE_2D, base_.id());
            gl_.TexImage2D(GL_TEXTURE_2D, 0, GL_R32F, size.x, size.y, 0, GL_RED, GL_FLOAT, nullptr);
            gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
            gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
            gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
            gl_.ReadBuffer(GL_COLOR_ATTACHMENT0);
            gl_.CopyTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, 0, 0, size.x, size.y);
            baseSize_ = size;
        }
        gl_.BindTexture(GL_TEXTURE_2D, base_.id());
        gl_.BindVertexArray(vertexArray_.id());
        gl_.UseProgram(program_.id());
        gl_.Uniform2i(mapSize_, size.x, size.y);
        glm::vec4 waves, floodWaves;
        for (int k = 0; k < 4; ++k) {
            waves[k] = phase(kWaveSpeeds[k], seconds);
            floodWaves[k] = phase(2.0 * kWaveSpeeds[k], seconds);
        }
        gl_.Uniform4f(wavePhase_, waves.x, waves.y, waves.z, waves.w);
        gl_.Uniform4f(floodWavePhase_, floodWaves.x, floodWaves.y, floodWaves.z, floodWaves.w);
        gl_.Uniform1f(ripplePhase_, phase(kRippleSpeed, seconds));
        gl_.Uniform1f(floodPhase_, phase(kFloodLevelSpeed, seconds));
        gl_.Uniform1i(fieldLocation_, field_);
        gl_.Viewport(0, 0, size.x, size.y);
        gl_.DrawArrays(GL_TRIANGLES, 0, 3);
        gl_.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, 0, 0);
    }
    renderer.heightsReplaced();
}

void AnimatedHeights::restore(ReliefRenderer& renderer) {
    ReliefTextures* textures = renderer.textures();
    if (!textures || !evaluated()) return;
    {
        const gl::PassGuard saved(gl_);
        gl_.ActiveTexture(GL_TEXTURE0);
        gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_.id());
        gl_.FramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D,
                                 base_.id(), 0);
        gl_.ReadBuffer(GL_COLOR_ATTACHMENT0);
        gl_.BindTexture(GL_TEXTURE_2D, textures->samples());
        gl_.CopyTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, 0, 0, baseSize_.x, baseSize_.y);
        gl_.FramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, 0, 0);
    }
    forgetMap();
    renderer.heightsReplaced();
}

}  // namespace microrelief
