#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <string>

#include "GlTestBackend.h"

namespace microrelief::test {

Backend gBackend = Backend::Egl;  // set by main from --backend=

Backend glBackend() {
    return gBackend;
}

GlContext& glContext() {
    static std::unique_ptr<GlContext> context = createHeadlessContext(gBackend);
    return *context;
}

}  // namespace microrelief::test

int main(int argc, char** argv) {
    ::testing::InitGoogleTest(&argc, argv);
    for (int k = 1; k < argc; ++k) {
        const std::string arg = argv[k];
        if (arg.rfind("--backend=", 0) == 0)
            microrelief::test::gBackend = microrelief::parseBackend(arg.substr(10));
    }
    std::printf("GL tests on backend %s\n", microrelief::backendName(microrelief::test::gBackend));
    return RUN_ALL_TESTS();
}
