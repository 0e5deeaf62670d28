#include "microrelief/gl/OffscreenTarget.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "microrelief/core/Error.h"
#include "microrelief/gl/StateGuard.h"

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

}  // namespace

OffscreenTarget::OffscreenTarget(const GL& gl, int width, int height)
    : gl_(gl), width_(width), height_(height) {
    GLint maxSize = 0, maxViewport[2] = {0, 0};
    gl_.GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &maxSize);
    gl_.GetIntegerv(GL_MAX_VIEWPORT_DIMS, maxViewport);
    const int limit = std::min({maxSize, maxViewport[0], maxViewport[1]});
    if (width <= 0 || height <= 0 || width > limit || height > limit) {
        throwBadInput("{size} " + std::to_string(width) + "x" + std::to_string(height) +
                      " is outside what this GL renders (1 to " + std::to_string(limit) +
                      " per side)");
    }
    framebuffer_ = gl::Framebuffer::create(gl_);
    color_ = makeAttachment(gl_, GL_SRGB8_ALPHA8, GL_RGBA, GL_UNSIGNED_BYTE, width, height);
    position_ = makeAttachment(gl_, GL_RGBA32F, GL_RGBA, GL_FLOAT, width, height);
    stats_ = makeAttachment(gl_, GL_RGBA32F, GL_RGBA, GL_FLOAT, width, height);
    shadow_ = makeAttachment(gl_, GL_R32F, GL_RED, GL_FLOAT, width, height);
    depth_ = gl::Renderbuffer::create(gl_);
    gl_.BindRenderbuffer(GL_RENDERBUFFER, depth_.id());
    gl_.RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, width, height);

    gl_.BindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
    gl_.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, color_.id(), 0);
    gl_.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, position_.id(),
                             0);
    gl_.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT2, GL_TEXTURE_2D, stats_.id(), 0);
    gl_.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT3, GL_TEXTURE_2D, shadow_.id(), 0);
    gl_.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_.id());
    const GLenum buffers[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2,
                              GL_COLOR_ATTACHMENT3};
    gl_.DrawBuffers(4, buffers);
    const GLenum status = gl_.CheckFramebufferStatus(GL_FRAMEBUFFER);
    gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        // Within the GL's limits (checked above), what refuses a large target is most
        // likely its memory (llvmpipe: GL_OUT_OF_MEMORY): the attachments take 44 bytes a pixel
        // (sRGB colour 4, position 16, statistics 16, shadow 4, depth 4), 11.8 GB at 16384 x 16384.
        const GLenum error = gl_.GetError();
        char gigabytes[32];
        std::snprintf(gigabytes, sizeof gigabytes, "%.2g GB",
                      44.0 * static_cast<double>(width) * height / 1e9);
        throwRuntime("the offscreen framebuffer of " + std::to_string(width) + "x" +
                     std::to_string(height) + " could not be made (status " + gl::enumHex(status) +
                     (error == GL_OUT_OF_MEMORY ? ", out of memory" : "") +
                     "; its attachments take " + gigabytes + "): a smaller {size}");
    }
}

void OffscreenTarget::bind() const {
    gl_.BindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
    gl_.Viewport(0, 0, width_, height_);
}

void OffscreenTarget::clear(const glm::vec3& background, float depth) const {
    bind();
    const gl::SrgbWrites srgb(gl_);  // the linear background, encoded by the GL
    const float color[4] = {background.r, background.g, background.b, 1.0f};
    const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};

    gl_.ClearBufferfv(GL_COLOR, 0, color);
    gl_.ClearBufferfv(GL_COLOR, 1, zero);
    gl_.ClearBufferfv(GL_COLOR, 2, zero);
    gl_.ClearBufferfv(GL_COLOR, 3, zero);
    gl_.ClearBufferfv(GL_DEPTH, 0, &depth);
}

RenderedFrame OffscreenTarget::read(const glm::dvec3& positionOrigin) const {
    RenderedFrame frame;
    frame.positionOrigin = positionOrigin;
    frame.width = width_;
    frame.height = height_;
    const std::size_t count = static_cast<std::size_t>(width_) * height_ * 4;
    frame.color.resize(count);
    frame.position.resize(count);
    frame.stats.resize(count);
    frame.shadow.resize(count / 4);
    readInto(frame, 0, 0, width_, height_);
    return frame;
}

std::vector<float> OffscreenTarget::readDepth() const {
    std::vector<float> depth(static_cast<std::size_t>(width_) * height_);
    gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_.id());
    gl_.PixelStorei(GL_PACK_ALIGNMENT, 4);
    gl_.ReadPixels(0, 0, width_, height_, GL_DEPTH_COMPONENT, GL_FLOAT, depth.data());
    gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    // Top row first, as the other outputs.
    std::vector<float> flipped(depth.size());
    for (int r = 0; r < height_; ++r) {
        std::copy_n(depth.begin() + static_cast<std::ptrdiff_t>(r) * width_, width_,
                    flipped.begin() + static_cast<std::ptrdiff_t>(height_ - 1 - r) * width_);
    }
    return flipped;
}

glm::vec4 OffscreenTarget::positionAt(int column, int row) const {
    glm::vec4 position(0.0f);
    if (column < 0 || row < 0 || column >= width_ || row >= height_) return position;
    GLint previous = 0, alignment = 4;
    gl_.GetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &previous);
    gl_.GetIntegerv(GL_PACK_ALIGNMENT, &alignment);
    gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_.id());
    gl_.ReadBuffer(GL_COLOR_ATTACHMENT1);
    gl_.PixelStorei(GL_PACK_ALIGNMENT, 4);
    gl_.ReadPixels(column, height_ - 1 - row, 1, 1, GL_RGBA, GL_FLOAT, &position.x);
    gl_.PixelStorei(GL_PACK_ALIGNMENT, alignment);
    gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(previous));
    return position;
}

void OffscreenTarget::readInto(RenderedFrame& frame, int x, int y, int width, int height) const {
    std::vector<std::uint8_t> color(static_cast<std::size_t>(width) * height * 4);
    std::vector<float> position(color.size()), stats(color.size()), shadow(color.size() / 4);
    gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_.id());
    gl_.PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl_.ReadBuffer(GL_COLOR_ATTACHMENT0);
    gl_.ReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, color.data());
    gl_.ReadBuffer(GL_COLOR_ATTACHMENT1);
    gl_.ReadPixels(0, 0, width, height, GL_RGBA, GL_FLOAT, position.data());
    gl_.ReadBuffer(GL_COLOR_ATTACHMENT2);
    gl_.ReadPixels(0, 0, width, height, GL_RGBA, GL_FLOAT, stats.data());
    gl_.ReadBuffer(GL_COLOR_ATTACHMENT3);
    gl_.ReadPixels(0, 0, width, height, GL_RED, GL_FLOAT, shadow.data());
    gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    // GL's row 0 is the bottom of the picture; ours is the top: tile row r is GL row
    // y + r of the picture, its row frame.height - 1 - (y + r).
    const std::size_t rowValues = static_cast<std::size_t>(width) * 4;
    for (int r = 0; r < height; ++r) {
        const std::size_t from = static_cast<std::size_t>(r) * rowValues;
        const std::size_t to =
            (static_cast<std::size_t>(frame.height - 1 - (y + r)) * frame.width + x) * 4;
        std::copy_n(color.begin() + from, rowValues, frame.color.begin() + to);
        std::copy_n(position.begin() + from, rowValues, frame.position.begin() + to);
        std::copy_n(stats.begin() + from, rowValues, frame.stats.begin() + to);
        std::copy_n(shadow.begin() + from / 4, width, frame.shadow.begin() + to / 4);
    }
}

}  // namespace microrelief
