// The accuracy sweep (issue 3) on the GPU: every case of SweepCases, rendered and
// compared pixel by pixel with the exact reference, and with the CPU twin of the
// traversal. One line per case goes to the log; `ctest -V -R gl` shows the table.
#include <gtest/gtest.h>

#include <memory>

#include "GlTestBackend.h"
#include "SweepCases.h"
#include "TestSupport.h"
#include "microrelief/core/DataPaths.h"
#include "microrelief/gl/ReliefRenderer.h"
#include "microrelief/core/trace/MultilevelTracer.h"

using namespace microrelief;

namespace {

class AccuracySweep : public ::testing::TestWithParam<std::size_t> {
protected:
    void SetUp() override {
        if (!isBackendPresent(test::glBackend()))
            GTEST_SKIP() << test::missingBackendMessage(test::glBackend());
    }
};

TEST_P(AccuracySweep, MatchesTheReference) {
    const test::SweepMap& m = test::sweepMaps()[GetParam()];
    GlContext& context = test::glContext();
    context.makeCurrent();
    const GL& gl = context.gl();
    ReliefRenderer renderer(gl, shaderDirectory());
    renderer.setHeightScale(static_cast<float>(m.heightScale));
    renderer.setHeightMap(*m.map, m.name, m.base, m.interpolation);
    OffscreenTarget target(gl, test::kSweepSize, test::kSweepSize);
    const MultilevelTracer twin(*m.map, m.heightScale, m.base, m.interpolation);

    for (const test::SweepView& view : test::sweepViews(m)) {
        const CameraFrame camera =
            resolveCamera(view.camera, test::kSweepSize, test::kSweepSize, 2.0);
        target.clear(glm::vec3(0.0f));
        renderer.draw(camera, ShadingOptions{});
        const RenderedFrame frame = target.read();
        const test::Accuracy gpu = test::compareWithReference(frame, camera, m.geometry());
        // The CPU twin on the same rays (tests/cpu holds it to the reference): where it
        // and the GPU disagree on hit/miss.
        std::size_t twinVsGpu = 0;
        for (int row = 0; row < camera.height; ++row) {
            for (int column = 0; column < camera.width; ++column) {
                const bool twinHit = test::twinPixel(twin, camera.pixelRay(column, row)).hit;
                twinVsGpu += twinHit != (frame.positionAt(column, row)[3] > 0.5f);
            }
        }
        std::printf(
            "| %-7s | %-22s | %6zu | %7.3f %% | %7.3f %% | %9.2e | %9.2e | %zu | twin vs gpu %zu "
            "|\n",
            backendName(test::glBackend()), (m.name + " " + view.name).c_str(), gpu.referenceHits,
            gpu.coverageMismatchPercent(), gpu.offHalfTexelPercent(), gpu.p99ErrorTexels,
            gpu.maxErrorTexels, gpu.exhausted, twinVsGpu);
        const std::string where = m.name + " " + view.name + ": " + gpu.summary();
        EXPECT_LE(gpu.coverageMismatchPercent(), test::kMaxCoverageMismatchPercent) << where;
        EXPECT_TRUE(test::withinOffBudget(gpu)) << where;
        EXPECT_EQ(gpu.exhausted, 0u) << where;
        EXPECT_LE(100.0 * twinVsGpu / gpu.pixels, test::kMaxCoverageMismatchPercent)
            << "twin against gpu, " << where;
    }
}

std::string caseName(const ::testing::TestParamInfo<std::size_t>& info) {
    return test::sweepMapName(info.param);
}

// One case per map of the list, however long it is.
INSTANTIATE_TEST_SUITE_P(Maps, AccuracySweep,
                         ::testing::Range<std::size_t>(0, test::sweepMapCount()), caseName);

}  // namespace
