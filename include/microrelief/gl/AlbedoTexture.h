// An albedo on the GPU (core/image/Albedo.h): one 2D texture with its whole mip chain, 8-bit
// images as SRGB8_ALPHA8 (the GL decodes them before it filters), others as RGBA16F,
// filtered trilinearly; relief.frag spreads taps along each pixel's footprint for the
// anisotropy. Repeating in both directions: the map's tiles and a curved base's seam
// continue it, and the plane's edges are clamped by the shader's coordinates.
#pragma once

#include "microrelief/gl/Objects.h"
#include "microrelief/core/image/Albedo.h"

namespace microrelief {

class AlbedoTexture {
public:
    // Throws Error(BadInput) beyond GL_MAX_TEXTURE_SIZE naming `source`. GL state restored.
    AlbedoTexture(const GL& gl, const AlbedoImage& image, const std::string& source);

    GLuint id() const { return texture_.id(); }
    int width() const { return width_; }
    int height() const { return height_; }

private:
    gl::Texture texture_;
    int width_ = 0, height_ = 0;
};

}  // namespace microrelief
