#include "ViewCapture.h"

namespace microrelief {

RgbPicture viewPicture(const OffscreenTarget& target, const glm::dvec3& eye) {
    const RenderedFrame picture = target.read(eye);
    return {picture.width, picture.height,
            rgbFromRgba(picture.color, picture.width, picture.height, false)};
}

RgbPicture windowPicture(const GL& gl, const glm::ivec2& framebufferSize) {
    const int width = framebufferSize.x, height = framebufferSize.y;
    std::vector<std::uint8_t> rgba(static_cast<std::size_t>(width) * height * 4);
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    gl.ReadBuffer(GL_BACK);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl.ReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    return {width, height, rgbFromRgba(rgba, width, height, true)};
}

}  // namespace microrelief
