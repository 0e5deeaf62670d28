// The GL state the library's draws and uploads change, saved on construction and
// restored on destruction (bgfx's explicit state, made scoped): a library that draws in
// an engine's context leaves it as it found it. What it covers is listed below; anything
// else the library leaves alone.
#pragma once

#include "microrelief/gl/Gl.h"

namespace microrelief::gl {

class StateGuard {
public:
    explicit StateGuard(const GL& gl);
    ~StateGuard();
    StateGuard(const StateGuard&) = delete;
    StateGuard& operator=(const StateGuard&) = delete;

    // Texture units whose GL_TEXTURE_2D binding is saved: 0 .. kUnits - 1.
    static constexpr int kUnits = 4;

private:
    const GL& gl_;
    GLint program_ = 0, vertexArray_ = 0, arrayBuffer_ = 0;
    GLint uniformBuffer_ = 0, uniformBinding0_ = 0;
    GLint activeTexture_ = 0, textures_[kUnits] = {};
    GLint unpackAlignment_ = 4;
    GLboolean cullFace_ = GL_FALSE, depthTest_ = GL_FALSE, depthClamp_ = GL_FALSE;
    GLint cullFaceMode_ = GL_BACK, frontFace_ = GL_CCW, depthFunc_ = GL_LESS;
    GLint viewport_[4] = {};
};

// What an offscreen pass of the library's own (the GPU pyramid builder, the height
// brush: gl/PyramidBuilder.h, gl/HeightEditor.h) needs beyond StateGuard, saved and set for
// a scope and restored after it: the draw and read framebuffers, blending, the scissor
// test, the colour write mask, rasteriser discard and the pack alignment; culling and the
// depth test off (StateGuard restores those). Its draws then write every texel they cover
// as the fragment shader computes it, whatever state the caller left.
class PassGuard {
public:
    explicit PassGuard(const GL& gl);
    ~PassGuard();
    PassGuard(const PassGuard&) = delete;
    PassGuard& operator=(const PassGuard&) = delete;

private:
    StateGuard state_;
    const GL& gl_;
    GLint drawFramebuffer_ = 0, readFramebuffer_ = 0, packAlignment_ = 4;
    GLboolean blend_ = GL_FALSE, scissor_ = GL_FALSE, discard_ = GL_FALSE;
    GLboolean colorMask_[4] = {GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE};
};

// sRGB writes (GL_FRAMEBUFFER_SRGB) on for a scope, as they were after it: the relief's
// colour is linear, and a target with an sRGB colour format encodes it only while they
// are on (clears included).
class SrgbWrites {
public:
    explicit SrgbWrites(const GL& gl) : gl_(gl), was_(gl.IsEnabled(GL_FRAMEBUFFER_SRGB)) {
        gl_.Enable(GL_FRAMEBUFFER_SRGB);
    }
    ~SrgbWrites() {
        if (!was_) gl_.Disable(GL_FRAMEBUFFER_SRGB);
    }
    SrgbWrites(const SrgbWrites&) = delete;
    SrgbWrites& operator=(const SrgbWrites&) = delete;

private:
    const GL& gl_;
    GLboolean was_;
};

}  // namespace microrelief::gl
