// Move-only owners of GL names (Magnum's GL/Shader.h pattern): copy deleted, moves
// leave an explicit empty state, the destructor deletes through the table of the
// context that made the name. Owners must die before their context; the renderer
// keeps them as members and the context outlives the renderer by construction.
#pragma once

#include <utility>

#include "microrelief/gl/Gl.h"

namespace microrelief::gl {

// Deleter signatures differ (glDeleteTextures(n, names) vs glDeleteProgram(name)), so
// each owner names a small policy with `static void destroy(const GL&, GLuint)`.
template <class Policy>
class Object {
public:
    Object() = default;
    Object(const GL& gl, GLuint name) : gl_(&gl), name_(name) {}
    // A fresh name, for the kinds GL generates (textures, buffers, ...):
    // `auto texture = gl::Texture::create(gl);`
    static Object create(const GL& gl) { return Object(gl, Policy::create(gl)); }
    ~Object() { reset(); }

    Object(const Object&) = delete;
    Object& operator=(const Object&) = delete;
    Object(Object&& other) noexcept : gl_(other.gl_), name_(std::exchange(other.name_, 0)) {}
    Object& operator=(Object&& other) noexcept {
        if (this != &other) {
            reset();
            gl_ = other.gl_;
            name_ = std::exchange(other.name_, 0);
        }
        return *this;
    }

    GLuint id() const { return name_; }
    explicit operator bool() const { return name_ != 0; }

    void reset() {
        if (name_ != 0) Policy::destroy(*gl_, name_);
        name_ = 0;
    }

private:
    const GL* gl_ = nullptr;
    GLuint name_ = 0;
};

// The kinds GL generates and deletes in batches (glGenTextures(n, names) and
// glDeleteTextures(n, names), ...): one policy over the two entry points of the table.
template <auto Generate, auto Delete>
struct GeneratedNamePolicy {
    static GLuint create(const GL& gl) {
        GLuint n = 0;
        (gl.*Generate)(1, &n);
        return n;
    }
    static void destroy(const GL& gl, GLuint n) { (gl.*Delete)(1, &n); }
};
using TexturePolicy = GeneratedNamePolicy<&GL::GenTextures, &GL::DeleteTextures>;
using BufferPolicy = GeneratedNamePolicy<&GL::GenBuffers, &GL::DeleteBuffers>;
using VertexArrayPolicy = GeneratedNamePolicy<&GL::GenVertexArrays, &GL::DeleteVertexArrays>;
using FramebufferPolicy = GeneratedNamePolicy<&GL::GenFramebuffers, &GL::DeleteFramebuffers>;
using RenderbufferPolicy = GeneratedNamePolicy<&GL::GenRenderbuffers, &GL::DeleteRenderbuffers>;
using QueryPolicy = GeneratedNamePolicy<&GL::GenQueries, &GL::DeleteQueries>;
// Shaders and programs are made by glCreateShader / glCreateProgram (gl/ShaderProgram.h) and
// deleted one at a time.
struct ShaderPolicy {
    static void destroy(const GL& gl, GLuint n) { gl.DeleteShader(n); }
};
struct ProgramPolicy {
    static void destroy(const GL& gl, GLuint n) { gl.DeleteProgram(n); }
};

using Texture = Object<TexturePolicy>;
using Buffer = Object<BufferPolicy>;
using VertexArray = Object<VertexArrayPolicy>;
using Framebuffer = Object<FramebufferPolicy>;
using Renderbuffer = Object<RenderbufferPolicy>;
using Query = Object<QueryPolicy>;
using Shader = Object<ShaderPolicy>;
using Program = Object<ProgramPolicy>;

}  // namespace microrelief::gl
