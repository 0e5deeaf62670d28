// The accuracy sweep (issue 3) on the GPU: every case of SweepCases, rendered and
// compared pixel by pixel with the exact reference, and with the CPU twin of the
// traversal. One line per case goes to the log; `ctest -V -R gl` shows the table.
#include <gtest/gtest.h>

#include <memory>

#include "GlTestBackend.h"
#include "SweepCases.h"
#include "TestSupport.h"
#include "core/DataPaths.h"
#include "render/ReliefRenderer.h"
#include "trace/MultilevelTracer.h"

using namespace microrelief;

namespace {

// Every case, every backend (issue 3): hit/miss may differ only for rays that graze a
// ridge or a silhouette exactly (float on the GPU, double in the reference), at most
// 0.1 % of pixels; a position off by more than half a texel only where such a ray
// lands on a farther surface, at most 0.2 % of hit pixels. No ray may run out of the
// iteration budget.
constexpr double kMaxCoverageMismatchPercent = 0.1;
constexpr double kMaxOffHalfTexelPercent = 0.2;

// Sparse maps seen at grazing angles (the spikes at 1 and 3 degrees) hit only a few
// hundred of the 4096 pixels, where 0.2 % is less than one pixel: one ray that grazes a
// spike's tip in float and passes it in double would fail the case. Such a case may
// have one off pixel; a second one fails it.
bool withinOffBudget(const test::Accuracy& a) {
    return a.offHalfTexel <= 1 || a.offHalfTexelPercent() <= kMaxOffHalfTexelPercent;
}

class AccuracySweep : public ::testing::TestWithParam<std::size_t> {
protected:
    void SetUp() override {
        if (!isBackendPresent(test::glBackend())) GTEST_SKIP() << backendName(test::glBackend()) << " is absent";
    }
};

TEST_P(AccuracySweep, MatchesTheReference) {
    const test::SweepMap& m = test::sweepMaps()[GetParam()];
    GlContext& context = test::glContext();
    context.makeCurrent();
    const GL& gl = context.gl();
    ReliefRenderer renderer(gl, shaderDirectory());
    renderer.setHeightScale(static_cast<float>(m.heightScale));
    renderer.setHeightMap(*m.map, m.name);
    OffscreenTarget target(gl, test::kSweepSize, test::kSweepSize);
    const MultilevelTracer twin(*m.map, m.heightScale);

    for (const test::SweepView& view : test::sweepViews(m)) {
        const CameraFrame camera = resolveCamera(view.camera, test::kSweepSize, test::kSweepSize, 2.0);
        target.clear(glm::vec3(0.0f));
        renderer.draw(camera, ShadingOptions{});
        const RenderedFrame frame = target.read();
        const test::Accuracy gpu = test::compareWithReference(frame, camera, *m.map, m.heightScale);
        // The twin on the same rays, and where it and the GPU disagree on hit/miss.
        std::size_t twinVsGpu = 0;
        const test::Accuracy cpu = test::measureAccuracy(camera, *m.map, m.heightScale, [&](int c, int r, const Ray& ray) {
            TraversalStats stats;
            const auto hit = twin.intersect(ray, &stats);
            twinVsGpu += hit.has_value() != (frame.positionAt(c, r)[3] > 0.5f);
            return test::PixelHit{hit.has_value(), hit ? hit->position : glm::dvec3(0.0), stats.exhausted};
        });
        std::printf("| %-7s | %-22s | %6zu | %7.3f %% | %7.3f %% | %9.2e | %9.2e | %zu | twin: %.3f %% / %.3f %%, vs gpu %zu |\n",
                    backendName(test::glBackend()), (m.name + " " + view.name).c_str(), gpu.referenceHits,
                    gpu.coverageMismatchPercent(), gpu.offHalfTexelPercent(), gpu.p99ErrorTexels, gpu.maxErrorTexels,
                    gpu.exhausted, cpu.coverageMismatchPercent(), cpu.offHalfTexelPercent(), twinVsGpu);
        const std::string where = m.name + " " + view.name + ": " + gpu.summary();
        EXPECT_LE(gpu.coverageMismatchPercent(), kMaxCoverageMismatchPercent) << where;
        EXPECT_TRUE(withinOffBudget(gpu)) << where;
        EXPECT_EQ(gpu.exhausted, 0u) << where;
        EXPECT_LE(cpu.coverageMismatchPercent(), kMaxCoverageMismatchPercent) << "twin " << where;
        EXPECT_TRUE(withinOffBudget(cpu)) << "twin " << where;
        EXPECT_EQ(cpu.exhausted, 0u) << "twin " << where;
    }
}

std::string caseName(const ::testing::TestParamInfo<std::size_t>& info) {
    return test::sweepMaps()[info.param].name;
}

INSTANTIATE_TEST_SUITE_P(Maps, AccuracySweep, ::testing::Range<std::size_t>(0, 12), caseName);

TEST(AccuracySweepCases, CoverTheMapsTheIssueNames) {
    ASSERT_EQ(test::sweepMaps().size(), 12u);  // keep the Range above in step
    EXPECT_GT(test::sweepCases().size(), 200u);
}

}  // namespace
