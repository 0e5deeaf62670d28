// Move-only owners of GL names (Magnum's GL/Shader.h pattern): copy deleted, moves
// leave an explicit empty state, the destructor deletes through the table of the
// context that made the name. Owners must die before their context; the renderer
// keeps them as members and the context outlives the renderer by construction.
#pragma once

#include <utility>

#include "gl/Gl.h"

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

struct TexturePolicy {
    static GLuint create(const GL& gl) {
        GLuint n = 0;
        gl.GenTextures(1, &n);
        return n;
    }
    static void destroy(const GL& gl, GLuint n) { gl.DeleteTextures(1, &n); }
};
struct BufferPolicy {
    static GLuint create(const GL& gl) {
        GLuint n = 0;
        gl.GenBuffers(1, &n);
        return n;
    }
    static void destroy(const GL& gl, GLuint n) { gl.DeleteBuffers(1, &n); }
};
struct VertexArrayPolicy {
    static GLuint create(const GL& gl) {
        GLuint n = 0;
        gl.GenVertexArrays(1, &n);
        return n;
    }
    static void destroy(const GL& gl, GLuint n) { gl.DeleteVertexArrays(1, &n); }
};
struct FramebufferPolicy {
    static GLuint create(const GL& gl) {
        GLuint n = 0;
        gl.GenFramebuffers(1, &n);
        return n;
    }
    static void destroy(const GL& gl, GLuint n) { gl.DeleteFramebuffers(1, &n); }
};
struct RenderbufferPolicy {
    static GLuint create(const GL& gl) {
        GLuint n = 0;
        gl.GenRenderbuffers(1, &n);
        return n;
    }
    static void destroy(const GL& gl, GLuint n) { gl.DeleteRenderbuffers(1, &n); }
};
struct QueryPolicy {
    static GLuint create(const GL& gl) {
        GLuint n = 0;
        gl.GenQueries(1, &n);
        return n;
    }
    static void destroy(const GL& gl, GLuint n) { gl.DeleteQueries(1, &n); }
};
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
