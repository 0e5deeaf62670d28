#include "microrelief/gl/StateGuard.h"

namespace microrelief::gl {

StateGuard::StateGuard(const GL& gl) : gl_(gl) {
    gl.GetIntegerv(GL_CURRENT_PROGRAM, &program_);
    gl.GetIntegerv(GL_VERTEX_ARRAY_BINDING, &vertexArray_);
    gl.GetIntegerv(GL_ARRAY_BUFFER_BINDING, &arrayBuffer_);
    gl.GetIntegerv(GL_UNIFORM_BUFFER_BINDING, &uniformBuffer_);
    gl.GetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, 0, &uniformBinding0_);
    gl.GetIntegerv(GL_ACTIVE_TEXTURE, &activeTexture_);
    for (int unit = 0; unit < kUnits; ++unit) {
        gl.ActiveTexture(GL_TEXTURE0 + unit);
        gl.GetIntegerv(GL_TEXTURE_BINDING_2D, &textures_[unit]);
    }
    gl.ActiveTexture(static_cast<GLenum>(activeTexture_));
    gl.GetIntegerv(GL_UNPACK_ALIGNMENT, &unpackAlignment_);
    cullFace_ = gl.IsEnabled(GL_CULL_FACE);
    depthTest_ = gl.IsEnabled(GL_DEPTH_TEST);
    depthClamp_ = gl.IsEnabled(GL_DEPTH_CLAMP);
    gl.GetIntegerv(GL_CULL_FACE_MODE, &cullFaceMode_);
    gl.GetIntegerv(GL_FRONT_FACE, &frontFace_);
    gl.GetIntegerv(GL_DEPTH_FUNC, &depthFunc_);
    gl.GetIntegerv(GL_VIEWPORT, viewport_);
}

namespace {
void setEnabled(const GL& gl, GLenum capability, GLboolean enabled) {
    if (enabled) {
        gl.Enable(capability);
    } else {
        gl.Disable(capability);
    }
}
}  // namespace

StateGuard::~StateGuard() {
    const GL& gl = gl_;
    // A program the caller deleted while it was current lives only as long as it stays
    // current: once a draw here switched away from it, it is gone, and binding its name
    // again would be an error (GL_INVALID_VALUE). No program is what is left of it.
    const bool programLives = program_ == 0 || gl.IsProgram(static_cast<GLuint>(program_));
    gl.UseProgram(programLives ? static_cast<GLuint>(program_) : 0u);
    gl.BindVertexArray(static_cast<GLuint>(vertexArray_));
    gl.BindBuffer(GL_ARRAY_BUFFER, static_cast<GLuint>(arrayBuffer_));
    // Binding 0 first: glBindBufferBase also sets the generic binding, restored after it.
    gl.BindBufferBase(GL_UNIFORM_BUFFER, 0, static_cast<GLuint>(uniformBinding0_));
    gl.BindBuffer(GL_UNIFORM_BUFFER, static_cast<GLuint>(uniformBuffer_));
    for (int unit = 0; unit < kUnits; ++unit) {
        gl.ActiveTexture(GL_TEXTURE0 + unit);
        gl.BindTexture(GL_TEXTURE_2D, static_cast<GLuint>(textures_[unit]));
    }
    gl.ActiveTexture(static_cast<GLenum>(activeTexture_));
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, unpackAlignment_);
    setEnabled(gl, GL_CULL_FACE, cullFace_);
    setEnabled(gl, GL_DEPTH_TEST, depthTest_);
    setEnabled(gl, GL_DEPTH_CLAMP, depthClamp_);
    gl.CullFace(static_cast<GLenum>(cullFaceMode_));
    gl.FrontFace(static_cast<GLenum>(frontFace_));
    gl.DepthFunc(static_cast<GLenum>(depthFunc_));
    gl.Viewport(viewport_[0], viewport_[1], viewport_[2], viewport_[3]);
}

PassGuard::PassGuard(const GL& gl) : state_(gl), gl_(gl) {
    gl.GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &drawFramebuffer_);
    gl.GetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &readFramebuffer_);
    gl.GetIntegerv(GL_PACK_ALIGNMENT, &packAlignment_);
    blend_ = gl.IsEnabled(GL_BLEND);
    scissor_ = gl.IsEnabled(GL_SCISSOR_TEST);
    discard_ = gl.IsEnabled(GL_RASTERIZER_DISCARD);
    gl.GetBooleanv(GL_COLOR_WRITEMASK, colorMask_);
    gl.Disable(GL_BLEND);
    gl.Disable(GL_SCISSOR_TEST);
    gl.Disable(GL_RASTERIZER_DISCARD);
    gl.Disable(GL_CULL_FACE);
    gl.Disable(GL_DEPTH_TEST);
    gl.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

PassGuard::~PassGuard() {
    const GL& gl = gl_;
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(drawFramebuffer_));
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(readFramebuffer_));
    gl.PixelStorei(GL_PACK_ALIGNMENT, packAlignment_);
    setEnabled(gl, GL_BLEND, blend_);
    setEnabled(gl, GL_SCISSOR_TEST, scissor_);
    setEnabled(gl, GL_RASTERIZER_DISCARD, discard_);
    gl.ColorMask(colorMask_[0], colorMask_[1], colorMask_[2], colorMask_[3]);
}

}  // namespace microrelief::gl
