// Headless GL through OSMesa, loaded at run time with dlopen so that a machine without
// it (Mesa 25.1 removed OSMesa) loses only this backend. We take our own function
// table from OSMesaGetProcAddress; nothing here links against libOSMesa.
#include <dlfcn.h>

#include <cstdlib>
#include <string>
#include <vector>

#include "microrelief/headless/HeadlessContext.h"
#include "microrelief/core/Error.h"

namespace microrelief {

namespace {

// The few OSMesa declarations we use (GL/osmesa.h), declared here so the build does not
// need the header either.
using OSMesaContext = struct osmesa_context*;
using PFNOSMesaCreateContextAttribs = OSMesaContext (*)(const int* attribList, OSMesaContext share);
using PFNOSMesaDestroyContext = void (*)(OSMesaContext);
using PFNOSMesaMakeCurrent = unsigned char (*)(OSMesaContext, void* buffer, unsigned type,
                                               int width, int height);
using PFNOSMesaGetProcAddress = void (*(*)(const char*))();
constexpr int OSMESA_FORMAT = 0x22, OSMESA_RGBA = 0x1908, OSMESA_DEPTH_BITS = 0x30,
              OSMESA_PROFILE = 0x33, OSMESA_CORE_PROFILE = 0x34,
              OSMESA_CONTEXT_MAJOR_VERSION = 0x36, OSMESA_CONTEXT_MINOR_VERSION = 0x37;
constexpr unsigned kUnsignedByte = 0x1401;

struct OsMesaLibrary {
    void* handle = nullptr;
    PFNOSMesaCreateContextAttribs createContextAttribs = nullptr;
    PFNOSMesaDestroyContext destroyContext = nullptr;
    PFNOSMesaMakeCurrent makeCurrent = nullptr;
    PFNOSMesaGetProcAddress getProcAddress = nullptr;
};

// Loaded once per process and kept: unloading a GL driver under live contexts is unsafe.
const OsMesaLibrary& library() {
    static const OsMesaLibrary lib = [] {
        OsMesaLibrary l;
        // MICRORELIEF_OSMESA_LIBRARY names another library (or a missing one, to test
        // the program without this backend).
        if (const char* name = std::getenv("MICRORELIEF_OSMESA_LIBRARY"); name && *name) {
            l.handle = dlopen(name, RTLD_NOW | RTLD_LOCAL);
        } else {
            for (const char* candidate : {"libOSMesa.so.8", "libOSMesa.so.6", "libOSMesa.so"}) {
                if ((l.handle = dlopen(candidate, RTLD_NOW | RTLD_LOCAL)) != nullptr) break;
            }
        }
        if (!l.handle) return l;
        l.createContextAttribs = reinterpret_cast<PFNOSMesaCreateContextAttribs>(
            dlsym(l.handle, "OSMesaCreateContextAttribs"));
        l.destroyContext =
            reinterpret_cast<PFNOSMesaDestroyContext>(dlsym(l.handle, "OSMesaDestroyContext"));
        l.makeCurrent =
            reinterpret_cast<PFNOSMesaMakeCurrent>(dlsym(l.handle, "OSMesaMakeCurrent"));
        l.getProcAddress =
            reinterpret_cast<PFNOSMesaGetProcAddress>(dlsym(l.handle, "OSMesaGetProcAddress"));
        return l;
    }();
    return lib;
}

GLADapiproc loadOsMesa(void* user, const char* name) {
    const auto* lib = static_cast<const OsMesaLibrary*>(user);
    return reinterpret_cast<GLADapiproc>(lib->getProcAddress(name));
}

class OsMesaContextImpl final : public GlContext {
public:
    explicit OsMesaContextImpl(OSMesaContext context) : context_(context) {
        makeCurrent();
        loadFunctions(loadOsMesa, const_cast<OsMesaLibrary*>(&library()), "OSMesa");
    }
    ~OsMesaContextImpl() override { library().destroyContext(context_); }

    // OSMesa needs a colour buffer to make a context current; ours is a single pixel,
    // since every picture is drawn into a framebuffer object.
    void makeCurrent() override {
        if (!library().makeCurrent(context_, pixel_.data(), kUnsignedByte, 1, 1)) {
            throwRuntime("OSMesa: OSMesaMakeCurrent failed");
        }
    }
    std::string description() const override { return "osmesa"; }

private:
    OSMesaContext context_;
    std::vector<unsigned char> pixel_ = std::vector<unsigned char>(4);
};

}  // namespace

bool isOsMesaPresent() {
    return library().handle != nullptr;
}

std::unique_ptr<GlContext> createOsMesaContext() {
    const OsMesaLibrary& lib = library();
    if (!lib.handle) throwRuntime("OSMesa: libOSMesa.so.8 not found (Debian package libosmesa6)");
    if (!lib.createContextAttribs || !lib.destroyContext || !lib.makeCurrent ||
        !lib.getProcAddress) {
        throwRuntime("OSMesa: the library lacks OSMesaCreateContextAttribs (too old)");
    }
    const int attributes[] = {OSMESA_FORMAT,
                              OSMESA_RGBA,
                              OSMESA_DEPTH_BITS,
                              0,
                              OSMESA_PROFILE,
                              OSMESA_CORE_PROFILE,
                              OSMESA_CONTEXT_MAJOR_VERSION,
                              3,
                              OSMESA_CONTEXT_MINOR_VERSION,
                              3,
                              0};
    OSMesaContext context = lib.createContextAttribs(attributes, nullptr);
    if (!context) throwRuntime("OSMesa: cannot create a GL 3.3 core context");
    try {
        return std::make_unique<OsMesaContextImpl>(context);
    } catch (...) {
        lib.destroyContext(context);  // the constructor threw: no destructor runs
        throw;
    }
}

}  // namespace microrelief
