// The GL tests run once per backend: the executable takes --backend=egl|osmesa, and
// every test uses the one context made for it.
#pragma once

#include <gtest/gtest.h>

#include "TestSupport.h"
#include "microrelief/headless/HeadlessContext.h"

namespace microrelief::test {

Backend glBackend();
// Created on first use; tests skip before calling it when the backend is absent.
GlContext& glContext();

// A GL test: skipped, with the reason, where the backend is absent; else the suite's
// context current and its error flags cleared (what the tests before left: each test
// checks its own).
class GlTest : public ::testing::Test {
protected:
    void SetUp() override {
        if (!isBackendPresent(glBackend())) GTEST_SKIP() << missingBackendMessage(glBackend());
        glContext().makeCurrent();
        while (gl().GetError() != GL_NO_ERROR) {
        }
    }
    static const GL& gl() { return glContext().gl(); }
};

}  // namespace microrelief::test
