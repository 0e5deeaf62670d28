// Headless GL contexts, EGL and OSMesa (the microrelief::headless component), behind
// GlContext (GlContext.h).
#pragma once

#include <memory>
#include <string>

#include "microrelief/gl/GlContext.h"

namespace microrelief {

enum class Backend { Auto, Egl, OsMesa };

// Headless contexts render only into framebuffer objects. Auto tries EGL (a hardware
// device first, then Mesa's software device or the surfaceless platform) and falls
// back to OSMesa. Throws Error(Runtime) saying what each backend answered.
std::unique_ptr<GlContext> createHeadlessContext(Backend backend);

// The individual backends; each throws Error(Runtime) when it is absent or fails.
std::unique_ptr<GlContext> createEglContext();
std::unique_ptr<GlContext> createOsMesaContext();

// Whether a backend is installed at all: EGL offers a device or surfaceless display,
// libOSMesa can be opened. A present backend that then fails to make a context is a
// failure to report, not an absence (tests skip only on absence).
bool isBackendPresent(Backend backend);

Backend parseBackend(const std::string& name);  // "auto" | "egl" | "osmesa"
const char* backendName(Backend backend);

}  // namespace microrelief
