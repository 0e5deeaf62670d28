#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <string>

#include "GlTestBackend.h"
#include "TestSupport.h"

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
    const microrelief::Backend backend = microrelief::test::gBackend;
    std::printf("GL tests on backend %s\n", microrelief::backendName(backend));
    if (!microrelief::isBackendPresent(backend)) {
        // Explicit either way: every test skips (and says why) only where the run allows it.
        std::printf("%s\n", microrelief::test::missingBackendMessage(backend).c_str());
        if (!microrelief::test::missingBackendAllowed(backend)) return 1;
    }
    return RUN_ALL_TESTS();
}
