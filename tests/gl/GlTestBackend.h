// The GL tests run once per backend: the executable takes --backend=egl|osmesa, and
// every test uses the one context made for it.
#pragma once

#include "microrelief/context/HeadlessContext.h"

namespace microrelief::test {

Backend glBackend();
// Created on first use; tests skip before calling it when the backend is absent.
GlContext& glContext();

}  // namespace microrelief::test
