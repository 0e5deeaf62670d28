#include "microrelief/gl/GlContext.h"

#include <utility>

#include "microrelief/core/Error.h"

namespace microrelief {

void GlContext::loadFunctions(GLADuserptrloadfunc load, void* user, const std::string& who) {
    const int version = gladLoadGLContextUserPtr(&gl_, load, user);
    if (version == 0) throwRuntime(who + ": cannot load the GL functions");
    const int major = GLAD_VERSION_MAJOR(version), minor = GLAD_VERSION_MINOR(version);
    if (major < 3 || (major == 3 && minor < 3)) {
        throwRuntime(who + ": OpenGL " + std::to_string(major) + "." + std::to_string(minor) +
                     " is too old; microrelief needs 3.3 core");
    }
}

namespace {
std::string glString(const GL& gl, GLenum name) {
    const auto* text = reinterpret_cast<const char*>(gl.GetString(name));
    return text ? text : "";
}
}  // namespace

std::string GlContext::renderer() const {
    return glString(gl_, GL_RENDERER);
}
std::string GlContext::version() const {
    return glString(gl_, GL_VERSION);
}

namespace {
// A context someone else made and keeps current.
class AdoptedContext final : public GlContext {
public:
    AdoptedContext(GLADloadfunc load, std::string description)
        : description_(std::move(description)) {
        // glad's user-pointer loader, with the plain loader as the user pointer.
        loadFunctions(
            [](void* user, const char* name) { return reinterpret_cast<GLADloadfunc>(user)(name); },
            reinterpret_cast<void*>(load), description_);
    }
    void makeCurrent() override {}
    std::string description() const override { return description_; }

private:
    std::string description_;
};
}  // namespace

std::unique_ptr<GlContext> adoptCurrentContext(GLADloadfunc load, const std::string& description) {
    if (load == nullptr) throwRuntime(description + ": no GetProcAddress function given");
    return std::make_unique<AdoptedContext>(load, description);
}

}  // namespace microrelief
