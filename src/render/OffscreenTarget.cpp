#include "render/OffscreenTarget.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/Error.h"

namespace microrelief {

namespace {

gl::Texture makeAttachment(const GL& gl, GLenum internalFormat, GLenum format, GLenum type,
                           int width, int height) {
    gl::Texture texture = gl::Texture::create(gl);
    gl.BindTexture(GL_TEXTURE_2D, texture.id());
    gl.TexImage2D(GL_TEXTURE_2D, 0, static_cast<GLint>(internalFormat), width, height, 0, format,
                  type, nullptr);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return texture;
}

template <class T>
void flipRows(std::vector<T>& pixels, int width, int height, int channels) {
    const std::size_t row = static_cast<std::size_t>(width) * channels;
    for (int j = 0; j < height / 2; ++j) {
        std::swap_ranges(pixels.begin() + j * row, pixels.begin() + (j + 1) * row,
                         pixels.begin() + (height - 1 - j) * row);
    }
}

float srgbEncode(float linear) {
    const float c = std::fmin(std::fmax(linear, 0.0f), 1.0f);
    return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

}  // namespace

OffscreenTarget::OffscreenTarget(const GL& gl, int width, int height)
    : gl_(gl), width_(width), height_(height) {
    GLint maxSize = 0, maxViewport[2] = {0, 0};
    gl_.GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &maxSize);
    gl_.GetIntegerv(GL_MAX_VIEWPORT_DIMS, maxViewport);
    const int limit = std::min({maxSize, maxViewport[0], maxViewport[1]});
    if (width <= 0 || height <= 0 || width > limit || height > limit) {
        throwBadInput("--size " + std::to_string(width) + "x" + std::to_string(height) +
                      " is outside what this GL renders (1 to " + std::to_string(limit) +
                      " per side)");
    }
    framebuffer_ = gl::Framebuffer::create(gl_);
    color_ = makeAttachment(gl_, GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE, width, height);
    position_ = makeAttachment(gl_, GL_RGBA32F, GL_RGBA, GL_FLOAT, width, height);
    stats_ = makeAttachment(gl_, GL_RGBA32F, GL_RGBA, GL_FLOAT, width, height);
    depth_ = gl::Renderbuffer::create(gl_);
    gl_.BindRenderbuffer(GL_RENDERBUFFER, depth_.id());
    gl_.RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);

    gl_.BindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
    gl_.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, color_.id(), 0);
    gl_.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, position_.id(),
                             0);
    gl_.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT2, GL_TEXTURE_2D, stats_.id(), 0);
    gl_.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_.id());
    const GLenum buffers[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
    gl_.DrawBuffers(3, buffers);
    const GLenum status = gl_.CheckFramebufferStatus(GL_FRAMEBUFFER);
    gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        throwRuntime("the offscreen framebuffer is incomplete (status " + gl::enumHex(status) +
                     ")");
    }
}

void OffscreenTarget::bind() const {
    gl_.BindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
    gl_.Viewport(0, 0, width_, height_);
}

void OffscreenTarget::clear(const glm::vec3& background) const {
    bind();
    const float color[4] = {srgbEncode(background.r), srgbEncode(background.g),
                            srgbEncode(background.b), 1.0f};
    const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    const float farDepth = 1.0f;
    gl_.ClearBufferfv(GL_COLOR, 0, color);
    gl_.ClearBufferfv(GL_COLOR, 1, zero);
    gl_.ClearBufferfv(GL_COLOR, 2, zero);
    gl_.ClearBufferfv(GL_DEPTH, 0, &farDepth);
}

RenderedFrame OffscreenTarget::read() const {
    RenderedFrame frame;
    frame.width = width_;
    frame.height = height_;
    const std::size_t count = static_cast<std::size_t>(width_) * height_ * 4;
    frame.color.resize(count);
    frame.position.resize(count);
    frame.stats.resize(count);
    gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_.id());
    gl_.PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl_.ReadBuffer(GL_COLOR_ATTACHMENT0);
    gl_.ReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, frame.color.data());
    gl_.ReadBuffer(GL_COLOR_ATTACHMENT1);
    gl_.ReadPixels(0, 0, width_, height_, GL_RGBA, GL_FLOAT, frame.position.data());
    gl_.ReadBuffer(GL_COLOR_ATTACHMENT2);
    gl_.ReadPixels(0, 0, width_, height_, GL_RGBA, GL_FLOAT, frame.stats.data());
    gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    // GL's row 0 is the bottom of the picture; ours is the top.
    flipRows(frame.color, width_, height_, 4);
    flipRows(frame.position, width_, height_, 4);
    flipRows(frame.stats, width_, height_, 4);
    return frame;
}

}  // namespace microrelief
