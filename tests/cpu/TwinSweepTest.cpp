// The accuracy sweep (issue 3) for the CPU twin alone: no GL needed, so it runs
// wherever the CPU tests run. The GL sweep (tests/gl) repeats it next to the GPU.
#include <gtest/gtest.h>

#include "SweepCases.h"
#include "TestSupport.h"
#include "microrelief/core/trace/MultilevelTracer.h"

using namespace microrelief;

TEST(TwinSweep, EveryCaseMatchesTheReference) {
    for (const test::SweepMap& m : test::sweepMaps()) {
        const MultilevelTracer twin(*m.map, m.heightScale, m.base, m.interpolation);
        for (const test::SweepView& view : test::sweepViews(m)) {
            const CameraFrame camera =
                resolveCamera(view.camera, test::kSweepSize, test::kSweepSize, 2.0);
            const Accuracy a = measureAccuracy(
                camera, traceReferencePicture(camera, m.geometry()),
                [&](int, int, const Ray& ray) { return test::twinPixel(twin, ray); });
            // Double precision on both sides, the GPU's budgets all the same.
            const std::string where = m.name + " " + view.name + ": " + a.summary();
            EXPECT_LE(a.coverageMismatchPercent(), test::kMaxCoverageMismatchPercent) << where;
            EXPECT_TRUE(test::withinOffBudget(a)) << where;
            EXPECT_EQ(a.exhausted, 0u) << where;
        }
    }
}
