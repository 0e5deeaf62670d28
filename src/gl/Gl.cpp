#include "microrelief/gl/Gl.h"

#include <cstdio>

namespace microrelief::gl {

std::string enumHex(GLenum value) {
    char text[16];
    std::snprintf(text, sizeof text, "0x%04X", static_cast<unsigned>(value));
    return text;
}

}  // namespace microrelief::gl
