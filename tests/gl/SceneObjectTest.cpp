// The relief as an object in someone else's scene (issue 13): placed by a model transform,
// writing depth for the caller's projection and depth convention, leaving the GL state as
// it found it, its uniform block mirrored exactly in C++, and its tracer callable from an
// engine's own shader with a t range and an any-hit query. Checked by numbers against the
// exact reference, on the backend named by --backend=.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "GlTestBackend.h"
#include "TestSupport.h"
#include "microrelief/headless/HeadlessContext.h"
#include "microrelief/core/DataPaths.h"
#include "microrelief/core/Error.h"
#include "microrelief/core/GlslConstants.h"
#include "microrelief/core/base/BaseType.h"
#include "microrelief/gl/ReliefShader.h"
#include "microrelief/gl/ReliefTextures.h"
#include "microrelief/gl/ShaderProgram.h"
#include "microrelief/gl/StateGuard.h"
#include "microrelief/gl/HeadlessRender.h"
#include "microrelief/gl/OffscreenTarget.h"
#include "microrelief/gl/ReliefMap.h"
#include "microrelief/gl/ReliefPrograms.h"
#include "microrelief/gl/ReliefRenderer.h"
#include "microrelief/core/synth/SyntheticMaps.h"
#include "microrelief/core/trace/ReferenceTracer.h"

using namespace microrelief;

namespace {

// An engine's own shader: the single-file multilevel tracer (share/microrelief/shaders/
// single, no include resolver) pasted after a bare #version and the base's and last
// level's macros, the map's textures from ReliefTextures, its own uniforms and rays. Each
// pixel asks for the first point of the solid in [tMin, tMax], closest or any hit, and
// writes t and the hit's kind.
const char* const kRangeQueryMain = R"(
uniform sampler2D windows;
uniform sampler2D heights;
uniform vec2 mapSize;
uniform ivec2 pyramidSize;
uniform int levelCount;
uniform float maxHeight;
uniform float heightScale;
uniform vec3 frameScale;
uniform vec3 eye, right, up, forward;
uniform vec2 viewport;
uniform float tMin, tMax;
uniform bool anyHit;
layout(location = 0) out vec4 outColor;
layout(location = 1) out vec4 outHit;  // t, kind, exhausted, 1
void main() {
    vec2 ndc = gl_FragCoord.xy / viewport * 2.0 - 1.0;
    vec3 dir = forward + ndc.x * right + ndc.y * up;
    mr_Relief relief = mr_Relief(mr_ReliefMap(mapSize, pyramidSize, levelCount, maxHeight, ivec2(1)),
                                 mr_ReliefPlacement(mat4(1.0), mat4(1.0), heightScale, frameScale));
    mr_RayQuery query = mr_closestHitQuery(relief.map);
    query.tMin = tMin;
    query.tMax = tMax;
    query.anyHit = anyHit;
    mr_ReliefHit hit = mr_traceMultilevel(relief, query, windows, heights, mr_baseFramePoint(relief, eye),
                                          mr_baseFrameVector(relief, dir));
    outColor = vec4(0.0);
    outHit = vec4(hit.t, float(hit.kind), hit.exhausted ? 1.0 : 0.0, 1.0);
}
)";

const char* const kFullScreenTriangle =
    "#version 330 core\nvoid main() { vec2 p = vec2(gl_VertexID & 1, gl_VertexID >> 1);\n"
    "gl_Position = vec4(4.0 * p - 1.0, 0.0, 1.0); }\n";

std::string readFile(const std::filesystem::path& file) {
    std::ifstream in(file);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

// The reference's answer to a range query: the first point of the solid at t >= tMin is
// the hit of the ray restarted there (one that starts inside the solid hits at once),
// kept when it is no farther than tMax.
std::optional<double> referenceInRange(const ReferenceTracer& reference, const Ray& ray,
                                       double tMin, double tMax) {
    const ReferenceHit hit = reference.trace({ray.origin + tMin * ray.direction, ray.direction});
    if (!hit || tMin + hit.t > tMax) return std::nullopt;
    return tMin + hit.t;
}

class SceneObject : public test::GlTest {
protected:
    // Range queries through an engine's own shader (kRangeQueryMain) against the reference,
    // for one base and last level (RangeQueriesFromAnEnginesOwnShader).
    void expectRangeQueries(const std::string& single, const HeightMap& map, const BaseShape& base,
                            Interpolation interpolation, double distance) {
        const GL& g = gl();
        const float heightScale = 0.1f;
        const ReliefTextures textures(g, map, "cobbles", base.wrapsU());
        const std::string macros = "#version 330 core\n#define MICRORELIEF_BASE " +
                                   std::to_string(static_cast<int>(base.kind)) +
                                   "\n#define MICRORELIEF_INTERPOLATION " +
                                   std::to_string(static_cast<int>(interpolation)) + "\n";
        const gl::Shader vertex =
            gl::compileShader(g, GL_VERTEX_SHADER, {kFullScreenTriangle, {}, "330 core"});
        const gl::Shader fragment = gl::compileShader(
            g, GL_FRAGMENT_SHADER, {macros + single + kRangeQueryMain, {}, "330 core"});
        const gl::Program program = gl::linkProgram(g, vertex, fragment, "engine's range query");
        const gl::VertexArray empty = gl::VertexArray::create(g);

        const int size = 64;
        const CameraFrame camera =
            resolveCamera(test::orbitCamera(30.0, 35.0, distance), size, size, 1.0);
        const ReferenceTracer reference(ReliefGeometry{&map, heightScale, base, interpolation});
        std::vector<double> ts;
        for (int row = 0; row < size; ++row) {
            for (int column = 0; column < size; ++column) {
                if (const ReferenceHit h = reference.trace(camera.pixelRay(column, row)))
                    ts.push_back(h.t);
            }
        }
        ASSERT_GT(ts.size(), 1000u);
        std::sort(ts.begin(), ts.end());
        const double lo = ts[ts.size() * 4 / 10], hi = ts[ts.size() * 6 / 10];

        OffscreenTarget target(g, size, size);
        auto uniform = [&](const char* name) { return gl::uniform(g, program, name); };
        struct Query {
            double tMin, tMax;
            bool anyHit;
        };
        const double inf = 3.4e38;
        for (const Query q : {Query{0.0, inf, false}, Query{0.0, inf, true}, Query{lo, hi, false},
                              Query{lo, hi, true}}) {
            target.clear(glm::vec3(0.0f));
            {
                const gl::StateGuard saved(g);
                g.UseProgram(program.id());
                g.ActiveTexture(GL_TEXTURE0);
                g.BindTexture(GL_TEXTURE_2D, textures.windowPyramid());
                g.ActiveTexture(GL_TEXTURE1);
                g.BindTexture(GL_TEXTURE_2D, textures.samples());
                g.Uniform1i(uniform("windows"), 0);
                g.Uniform1i(uniform("heights"), 1);
                const ReliefMapShape& shape = textures.shape();
                g.Uniform2f(uniform("mapSize"), float(shape.size.x), float(shape.size.y));
                g.Uniform2i(uniform("pyramidSize"), shape.pyramidSize.x, shape.pyramidSize.y);
                g.Uniform1i(uniform("levelCount"), shape.levelCount);
                g.Uniform1f(uniform("maxHeight"), shape.maxHeight);
                g.Uniform1f(uniform("heightScale"), heightScale);
                g.Uniform3fv(uniform("frameScale"), 1,
                             glm::value_ptr(glm::vec3(base.frameScale())));
                g.Uniform3fv(uniform("eye"), 1, glm::value_ptr(glm::vec3(camera.eye)));
                g.Uniform3fv(uniform("right"), 1, glm::value_ptr(glm::vec3(camera.right)));
                g.Uniform3fv(uniform("up"), 1, glm::value_ptr(glm::vec3(camera.up)));
                g.Uniform3fv(uniform("forward"), 1, glm::value_ptr(glm::vec3(camera.forward)));
                g.Uniform2f(uniform("viewport"), float(size), float(size));
                g.Uniform1f(uniform("tMin"), float(q.tMin));
                g.Uniform1f(uniform("tMax"), float(q.tMax));
                g.Uniform1i(uniform("anyHit"), q.anyHit ? 1 : 0);
                g.Disable(GL_DEPTH_TEST);
                g.BindVertexArray(empty.id());
                g.DrawArrays(GL_TRIANGLES, 0, 3);
            }
            const RenderedFrame frame = target.read(glm::dvec3(0.0));  // this shader writes world positions
            int flips = 0, far = 0, hits = 0, startsInside = 0, exhausted = 0;
            for (int row = 0; row < size; ++row) {
                for (int column = 0; column < size; ++column) {
                    const float* h = frame.positionAt(column, row);
                    exhausted += h[2] > 0.5f;
                    const bool hit = h[1] > 0.5f;  // kind != MR_RELIEF_MISS
                    const std::optional<double> expected = referenceInRange(
                        reference, camera.pixelRay(column, row), float(q.tMin), float(q.tMax));
                    if (hit != expected.has_value()) {
                        ++flips;
                    } else if (hit) {
                        ++hits;
                        startsInside += *expected == double(float(q.tMin));
                        far += std::abs(h[0] - *expected) > 1e-4;
                    }
                }
            }
            std::printf(
                "    t in [%.4g, %.4g], %s: %d hits (%d at tMin), %d hit/miss flips, %d "
                "off by > 1e-4\n",
                q.tMin, q.tMax, q.anyHit ? "any hit" : "closest", hits, startsInside, flips, far);
            EXPECT_EQ(exhausted, 0);
            EXPECT_LE(flips, size * size / 500);
            EXPECT_LE(far, size * size / 500);
            EXPECT_GT(hits, 300);
            if (q.tMin > 0.0) {
                EXPECT_GT(startsInside, 50);  // the range does start in the solid
            }
        }
    }
};

// A rotation about a skew axis, an uneven scale and a move; with `mirror`, x flipped too.
ModelTransform skewModel(bool mirror) {
    glm::dmat4 m = glm::translate(glm::dmat4(1.0), glm::dvec3(0.3, -0.2, 0.15));
    m = glm::rotate(m, glm::radians(35.0), glm::normalize(glm::dvec3(1.0, 2.0, 0.5)));
    m = glm::scale(m, glm::dvec3(mirror ? -1.3 : 1.3, 0.7, 1.1));
    return ModelTransform(m);
}

// The same hits as the exact reference under the same transform (ReliefGeometry::model):
// rotated, unevenly scaled, moved and mirrored reliefs, on the plane (both last levels)
// and a cylinder, at the thresholds of every other view (RenderTest.cpp: hit/miss 0.1 %
// of pixels, off by more than half a texel 0.2 % of hits; they flip only on grazing rays).
TEST_F(SceneObject, ModelTransformRendersTheReferenceHits) {
    const HeightMap map = synth::cobbles(48, 40, 7);
    struct Case {
        const char* name;
        BaseShape base;
        Interpolation interpolation;
        bool mirror;
    };
    const Case cases[] = {
        {"plane, bilinear", {}, Interpolation::Bilinear, false},
        {"plane, biquadratic, mirrored", {}, Interpolation::Biquadratic, true},
        {"cylinder", BaseShape::cylinder(0.3, 1.0), Interpolation::Bilinear, false}};
    for (const Case& c : cases) {
        const ModelTransform model = skewModel(c.mirror);
        RenderJob job;
        job.width = job.height = 72;
        job.base = c.base;
        job.interpolation = c.interpolation;
        job.model = model;
        const glm::dvec3 centre = model.pointToWorld({0.0, 0.03, 0.0});
        job.camera = test::orbitCamera(40.0, 25.0, 1.7, centre);
        const HeadlessResult r = renderHeadless(test::glContext(), map, "cobbles", job);
        const test::Accuracy a = test::compareWithReference(
            r.frame, r.camera,
            ReliefGeometry{&map, job.heightScale, c.base, c.interpolation, model});
        std::printf("    %-30s %s\n", c.name, a.summary().c_str());
        EXPECT_GT(a.referenceHits, 800u) << c.name;  // the relief is in the picture
        EXPECT_LE(a.coverageMismatchPercent(), 0.1) << c.name;
        EXPECT_LE(a.offHalfTexelPercent(), 0.2) << c.name;
        EXPECT_EQ(a.exhausted, 0u) << c.name;

        // Not the identity's picture: the transform is applied, not ignored.
        RenderJob plain = job;
        plain.model = ModelTransform();
        const HeadlessResult unmoved = renderHeadless(test::glContext(), map, "cobbles", plain);
        EXPECT_NE(r.frame.position, unmoved.frame.position) << c.name;
    }
}

// One renderer across jobs builds only what a job changes: the pyramid for another map,
// addressing or tiles (core/scene/Scene.h: samePyramid), a program once for each
// configuration; a camera, a height scale, a model, another size of the base, another
// curved base or another last level are applied without building the pyramid again. Each picture
// equals a fresh renderer's, bit for bit: what is kept is what a new one would build.
TEST_F(SceneObject, ARendererAcrossJobsRebuildsOnlyWhatEachChanges) {
    const HeightMap map = synth::cobbles(48, 40, 7);
    struct Step {
        const char* name;
        std::function<void(RenderJob&)> change;
        bool heights;  // needsHeights, and one pyramid built
        int programs;  // programs compiled
    };
    const std::vector<Step> steps = {
        {"the camera", [](RenderJob& j) { j.camera = test::orbitCamera(35.0, 60.0, 1.6); }, false,
         0},
        {"the height scale", [](RenderJob& j) { j.heightScale = 0.2f; }, false, 0},
        {"the model", [](RenderJob& j) { j.model = skewModel(false); }, false, 0},
        {"a cylinder", [](RenderJob& j) { j.base = BaseShape::cylinder(0.3, 1.0); }, true, 1},
        {"its radius", [](RenderJob& j) { j.base = BaseShape::cylinder(0.4, 1.0); }, false, 0},
        {"a sphere", [](RenderJob& j) { j.base = BaseShape::sphere(0.45); }, false, 1},
        {"the cylinder again", [](RenderJob& j) { j.base = BaseShape::cylinder(0.4, 1.0); }, false,
         0},
        {"biquadratic", [](RenderJob& j) { j.interpolation = Interpolation::Biquadratic; }, false,
         1},
        // Both at once: the one program of the two (compiled for the sphere above), none between.
        {"the sphere, bilinear",
         [](RenderJob& j) {
             j.base = BaseShape::sphere(0.45);
             j.interpolation = Interpolation::Bilinear;
         },
         false, 0},
        {"maxmip", [](RenderJob& j) { j.method.method = Method::MaxMip; }, false, 1},
        {"hard shadows",
         [](RenderJob& j) {
             j.method.method = Method::Multilevel;
             j.shading.shadows = ShadowMode::Hard;
         },
         false, 1},
        {"tiles",
         [](RenderJob& j) {
             j.tiles = {2, 1}, j.shading.shadows = ShadowMode::Off;
         },
         true, 1},
    };
    RenderJob job;
    job.width = 40;
    job.height = 32;
    job.camera = test::orbitCamera(40.0, 25.0, 1.7);
    HeadlessRenderer renderer(test::glContext(), job.method);
    ASSERT_TRUE(renderer.needsHeights(job));
    renderer.setHeights(job, map, "cobbles");
    EXPECT_FALSE(renderer.needsHeights(job));
    (void)renderer.render(job);
    EXPECT_EQ(renderer.rebuilds().pyramids, 1);
    for (const Step& step : steps) {
        step.change(job);
        const RebuildCounts before = renderer.rebuilds();
        EXPECT_EQ(renderer.needsHeights(job), step.heights) << step.name;
        if (renderer.needsHeights(job)) renderer.setHeights(job, map, "cobbles");
        const HeadlessResult kept = renderer.render(job);
        const RebuildCounts after = renderer.rebuilds();
        EXPECT_EQ(after.pyramids - before.pyramids, step.heights ? 1 : 0) << step.name;
        EXPECT_EQ(after.programs - before.programs, step.programs) << step.name;
        EXPECT_EQ(after.albedos, 0) << step.name;
        const HeadlessResult fresh = renderHeadless(test::glContext(), map, "cobbles", job);
        EXPECT_EQ(kept.frame.color, fresh.frame.color) << step.name;
        EXPECT_EQ(kept.frame.position, fresh.frame.position) << step.name;
        std::size_t hits = 0;  // the relief is in the picture
        for (std::size_t i = 3; i < kept.frame.position.size(); i += 4) hits += kept.frame.position[i] > 0.5f;
        EXPECT_GT(hits, 100u) << step.name;
    }
}

// A relief and its method are applied together: a job that moves from a peer that runs on
// the plane alone (cone) to a cylinder, or back, renders what a fresh renderer of that job
// renders, whichever order the last job left; a pair that cannot run (cone on a cylinder)
// is refused, and the renderer goes on drawing the last job as before.
TEST_F(SceneObject, AReliefAndItsMethodApplyTogetherInEitherOrder) {
    const HeightMap map = synth::cobbles(32, 32, 5);
    RenderJob plane;
    plane.width = 32;
    plane.height = 24;
    plane.camera = test::orbitCamera(40.0, 25.0, 1.7);
    plane.method.method = Method::Cone;
    RenderJob cylinder = plane;
    cylinder.base = baseType("cylinder").defaults;
    cylinder.method.method = Method::Multilevel;
    HeadlessRenderer renderer(test::glContext(), plane.method);
    for (const RenderJob* job : {&plane, &cylinder, &plane}) {
        const std::string what = job == &plane ? "cone on the plane" : "multilevel on a cylinder";
        ASSERT_TRUE(renderer.needsHeights(*job)) << what;
        renderer.setHeights(*job, map, "cobbles");
        const HeadlessResult kept = renderer.render(*job);
        const HeadlessResult fresh = renderHeadless(test::glContext(), map, "cobbles", *job);
        EXPECT_EQ(kept.frame.position, fresh.frame.position) << what;
        std::size_t hits = 0;  // the relief is in the picture
        for (std::size_t i = 3; i < kept.frame.position.size(); i += 4)
            hits += kept.frame.position[i] > 0.5f;
        EXPECT_GT(hits, 100u) << what;
    }
    RenderJob cone = cylinder;
    cone.method.method = Method::Cone;
    const HeadlessResult before = renderer.render(plane);
    try {
        renderer.setHeights(cone, map, "cobbles");
        ADD_FAILURE() << "cone on a cylinder was not refused";
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::BadInput);
    }
    EXPECT_EQ(renderer.render(plane).frame.position, before.frame.position);
}

// Reliefs in one context share its programs (gl/ReliefPrograms.h): a second renderer given
// the first one's ReliefPrograms compiles nothing for a configuration the first compiled,
// draws its own map with it (the picture a renderer with programs of its own draws, bit for
// bit), and the cache holds each configuration once. A reload by one renderer drops the
// programs for both; the other compiles what it needs again at its next draw.
TEST_F(SceneObject, RenderersOfOneContextShareItsPrograms) {
    const HeightMap cobbles = synth::cobbles(32, 32, 5);
    const HeightMap other = synth::cobbles(48, 40, 9);
    const CameraFrame camera = resolveCamera(test::orbitCamera(40.0, 30.0, 1.8), 32, 32, 1.0);
    OffscreenTarget target(gl(), 32, 32);
    const auto draw = [&](ReliefRenderer& renderer) {
        target.clear(glm::vec3(0.0f));
        renderer.draw(camera, ShadingOptions{});
        return target.read(camera.eye);
    };
    const auto programs = std::make_shared<ReliefPrograms>(gl(), shaderDirectory());
    ReliefRenderer first(programs);
    first.apply(ReliefDesc{}, &cobbles, "cobbles");
    (void)draw(first);
    const int afterFirst = programs->compiled();
    EXPECT_EQ(first.rebuilds().programs, afterFirst);
    EXPECT_GE(afterFirst, 1);

    ReliefRenderer second(programs);
    second.apply(ReliefDesc{}, &other, "other");
    const RenderedFrame shared = draw(second);
    EXPECT_EQ(second.rebuilds().programs, 0);
    EXPECT_EQ(programs->compiled(), afterFirst);

    ReliefRenderer alone(gl(), shaderDirectory());
    alone.apply(ReliefDesc{}, &other, "other");
    const RenderedFrame own = draw(alone);
    EXPECT_GE(alone.rebuilds().programs, 1);
    EXPECT_EQ(shared.color, own.color);
    EXPECT_EQ(shared.position, own.position);
    int hits = 0;  // the relief is in the picture
    for (std::size_t k = 3; k < shared.position.size(); k += 4) hits += shared.position[k] > 0.5f;
    EXPECT_GT(hits, 100);

    first.reloadShaders();
    EXPECT_EQ(programs->compiled(), afterFirst + 1);
    const RenderedFrame reloaded = draw(second);
    EXPECT_EQ(reloaded.position, shared.position);
    EXPECT_EQ(programs->compiled(), afterFirst + 1 + second.rebuilds().programs);
}

// Reliefs share a map (gl/ReliefMap.h): three renderers draw one ReliefMap, each its own
// relief (the plane; the plane twice as tall and moved; the plane traced by the cone peer,
// whose cone map the map builds once for it), and each picture is the one a renderer that
// uploaded the map for itself draws, bit for bit. A relief of other addressing (a cylinder)
// is refused and changes nothing. An edit through one renderer reaches the others: at their
// next draw their boxes fit the raised maximum and the cone map is built again, and their
// pictures are those of fresh renderers over the edited heights.
TEST_F(SceneObject, ReliefsOfOneMapShareItsTextures) {
    HeightMap heights = synth::cobbles(32, 32, 5);
    const CameraFrame camera = resolveCamera(test::orbitCamera(40.0, 30.0, 1.8), 40, 32, 1.0);
    OffscreenTarget target(gl(), 40, 32);
    const auto draw = [&](ReliefRenderer& renderer) {
        target.clear(glm::vec3(0.0f));
        renderer.draw(camera, ShadingOptions{});
        return target.read(camera.eye);
    };
    const auto programs = std::make_shared<ReliefPrograms>(gl(), shaderDirectory());
    const std::shared_ptr<ReliefMap> map =
        ReliefMap::upload(programs, heights, nullptr, "cobbles", MapUploadSettings{});
    ReliefDesc plane;
    ReliefDesc tall = plane;
    tall.heightScale = 0.2f;
    tall.model = ModelTransform(glm::translate(glm::dmat4(1.0), glm::dvec3(0.05, 0.0, -0.1)));
    MethodSettings multilevel, cone;
    cone.method = Method::Cone;
    struct Relief {
        const char* name;
        ReliefDesc desc;
        MethodSettings method;
    };
    const Relief reliefs[] = {{"plane", plane, multilevel},
                              {"tall, moved", tall, multilevel},
                              {"cone", plane, cone}};
    std::vector<std::unique_ptr<ReliefRenderer>> sharers;
    for (const Relief& r : reliefs) {
        sharers.push_back(std::make_unique<ReliefRenderer>(programs, r.method));
        sharers.back()->apply(r.desc, map);
        EXPECT_EQ(sharers.back()->map(), map) << r.name;
        EXPECT_EQ(sharers.back()->rebuilds().pyramids, 0) << r.name;
    }
    const auto expectAsIfAlone = [&](const char* when) {
        for (std::size_t k = 0; k < sharers.size(); ++k) {
            ReliefRenderer alone(programs, reliefs[k].method);
            alone.apply(reliefs[k].desc, &heights, "cobbles");
            const RenderedFrame own = draw(alone);
            const RenderedFrame shared = draw(*sharers[k]);
            EXPECT_EQ(shared.color, own.color) << reliefs[k].name << ", " << when;
            EXPECT_EQ(shared.position, own.position) << reliefs[k].name << ", " << when;
            int hits = 0;  // the relief is in the picture
            for (std::size_t i = 3; i < shared.position.size(); i += 4)
                hits += shared.position[i] > 0.5f;
            EXPECT_GT(hits, 100) << reliefs[k].name << ", " << when;
        }
    };
    expectAsIfAlone("as built");
    const RenderedFrame before = draw(*sharers[1]);

    ReliefDesc cylinder = plane;
    cylinder.base = BaseShape::cylinder(0.3, 1.0);
    try {
        sharers[1]->apply(cylinder, map);
        ADD_FAILURE() << "a cylinder over the plane's map was not refused";
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::Runtime);
    }
    EXPECT_EQ(draw(*sharers[1]).position, before.position);

    // A spike four times the map's maximum in the middle, written through the first
    // renderer's textures: the others' boxes were fitted to the old maximum.
    const TexelRect spike{13, 13, 19, 19};
    const float top = 4.0f * map->maxHeight();
    for (int j = spike.y0; j < spike.y1; ++j)
        for (int i = spike.x0; i < spike.x1; ++i) heights.at(i, j) = top;
    const std::vector<float> values(static_cast<std::size_t>(spike.width() * spike.height()), top);
    sharers[0]->textures()->writeSamples(gl(), spike, values.data());
    sharers[0]->heightsChanged({spike});
    EXPECT_EQ(map->maxHeight(), top);
    expectAsIfAlone("after an edit through the first");
    EXPECT_NE(draw(*sharers[1]).position, before.position);  // the edit shows
}

// A relief drawn from the scene value alone (ReliefRenderer::draw(ViewDesc)): the camera
// it resolves against its own relief and map (the map's size and highest sample, the base,
// the height scale, the model) is the one HeadlessRenderer resolves, near and far planes
// and all, and the one resolved by hand from the heights' largest value; the picture is
// renderHeadless's, bit for bit, with the view's method: on a moved, scaled plane with the
// cone peer, and on a sphere.
TEST_F(SceneObject, AViewDrawsAsHeadlessRendersIt) {
    HeightMap map = synth::cobbles(48, 40, 7);
    // A largest value no half holds: the pyramid's top (rounded up) is not it.
    for (float& h : map.samples) h *= 0.91234567f;
    RenderJob plane;
    plane.width = 48;
    plane.height = 40;
    plane.heightScale = 0.15f;
    plane.model = skewModel(false);
    plane.camera = test::orbitCamera(40.0, 25.0, 2.5, plane.model.pointToWorld({0.0, 0.0, 0.0}));
    plane.method.method = Method::Cone;
    RenderJob sphere = plane;
    sphere.base = BaseShape::sphere(0.45);
    sphere.model = ModelTransform();
    sphere.camera = test::orbitCamera(30.0, 60.0, 1.9);
    sphere.method.method = Method::Multilevel;
    sphere.shading.shadows = ShadowMode::Hard;
    for (const RenderJob* job : {&plane, &sphere}) {
        const char* what = job == &plane ? "plane, cone" : "sphere, hard shadows";
        const HeadlessResult expected = renderHeadless(test::glContext(), map, "cobbles", *job);
        ReliefRenderer renderer(gl(), shaderDirectory());
        renderer.apply(*job, &map, "cobbles");  // the view's method: draw's to set
        OffscreenTarget target(gl(), job->width, job->height);
        target.clear(job->background);
        CameraFrame camera;
        {
            const gl::SrgbWrites srgb(gl());  // as HeadlessRenderer draws
            camera = renderer.draw(static_cast<const ViewDesc&>(*job));
        }
        EXPECT_EQ(camera.viewProjection, expected.camera.viewProjection) << what;
        EXPECT_EQ(camera.eye, expected.camera.eye) << what;
        // Both against the map's exact highest sample, not its pyramid's rounded top.
        const glm::dmat4 toWorld = job->model.objectToWorld();
        const CameraFrame byHand = resolveCamera(
            job->camera, job->width, job->height,
            sceneRadius(reliefExtent(map, job->heightScale, job->base), toWorld),
            sceneCentre(toWorld));
        EXPECT_EQ(camera.viewProjection, byHand.viewProjection) << what;
        const RenderedFrame frame = target.read(camera.eye);
        EXPECT_EQ(frame.color, expected.frame.color) << what;
        EXPECT_EQ(frame.position, expected.frame.position) << what;
        int hits = 0;  // the relief is in the picture
        for (std::size_t k = 3; k < frame.position.size(); k += 4) hits += frame.position[k] > 0.5f;
        EXPECT_GT(hits, 200) << what;
    }
}

// The scene is checked once, as a whole, at the renderer's door (validateScene): a job the
// description refuses (here a light wider than a hemisphere, which nothing below the scene
// checks) is refused by HeadlessRenderer::render and renderHeadless with the scene's own
// message, before anything is drawn; the renderer then draws the next job as before.
TEST_F(SceneObject, TheSceneIsCheckedAtTheDoor) {
    const HeightMap map = synth::cobbles(32, 32, 5);
    RenderJob job;
    job.width = job.height = 24;
    job.camera = test::orbitCamera(40.0, 25.0, 1.7);
    HeadlessRenderer renderer(test::glContext(), job.method);
    renderer.setHeights(job, map, "cobbles");
    const HeadlessResult before = renderer.render(job);
    RenderJob wide = job;
    wide.shading.lightSizeDegrees = 95.0f;
    ASSERT_FALSE(validateScene(wide, wide).empty());
    std::string expected;  // the scene's first refusal, as throwIfInvalid words it
    try {
        throwIfInvalid(validateScene(wide, wide));
    } catch (const Error& e) {
        expected = e.what();
    }
    EXPECT_NE(expected.find("shading.lightSizeDegrees"), std::string::npos) << expected;
    for (const char* door : {"HeadlessRenderer::render", "renderHeadless"}) {
        try {
            if (std::string(door) == "renderHeadless")
                (void)renderHeadless(test::glContext(), map, "cobbles", wide);
            else
                (void)renderer.render(wide);
            ADD_FAILURE() << door << " drew a scene the description refuses";
        } catch (const Error& e) {
            EXPECT_EQ(e.kind(), ErrorKind::BadInput) << door;
            EXPECT_EQ(std::string(e.what()), expected) << door;
        }
    }
    EXPECT_EQ(renderer.render(job).frame.position, before.frame.position);
}

// ReliefRenderer::draw(view) is a door too: a view the description refuses with the relief
// applied (pom, which knows the top surface only, with hard shadows; cone on the sphere) is
// refused with the scene's message before anything is drawn or set, and the next view draws
// as before.
TEST_F(SceneObject, ADrawnViewIsCheckedAtTheDoor) {
    const HeightMap map = synth::cobbles(32, 32, 5);
    RenderJob job;
    job.width = job.height = 24;
    job.camera = test::orbitCamera(40.0, 25.0, 1.7);
    RenderJob sphere = job;
    sphere.base = BaseShape::sphere();
    RenderJob pomShadows = job;
    pomShadows.method.method = Method::Pom;
    pomShadows.shading.shadows = ShadowMode::Hard;
    RenderJob coneOnSphere = sphere;
    coneOnSphere.method.method = Method::Cone;
    for (const auto& [relief, refused] :
         {std::pair{&job, &pomShadows}, std::pair{&sphere, &coneOnSphere}}) {
        ReliefRenderer renderer(gl(), shaderDirectory());
        renderer.apply(*relief, &map, "cobbles");
        OffscreenTarget target(gl(), job.width, job.height);
        const auto drawn = [&](const ViewDesc& view) {
            target.clear(view.background);
            const CameraFrame camera = renderer.draw(view);
            return target.read(camera.eye).position;
        };
        const std::vector<float> before = drawn(*relief);
        std::string expected;  // the scene's first refusal, as throwIfInvalid words it
        try {
            throwIfInvalid(validateScene(*refused, *refused));
        } catch (const Error& e) {
            expected = e.what();
        }
        ASSERT_FALSE(expected.empty());
        try {
            (void)renderer.draw(static_cast<const ViewDesc&>(*refused));
            ADD_FAILURE() << "draw(view) drew a view the description refuses: " << expected;
        } catch (const Error& e) {
            EXPECT_EQ(e.kind(), ErrorKind::BadInput);
            EXPECT_EQ(std::string(e.what()), expected);
        }
        EXPECT_EQ(renderer.method().method, relief->method.method) << expected;
        EXPECT_EQ(drawn(*relief), before) << expected;
    }
}

// A GL error an earlier call left on the context is said as the caller's, not taken for the
// render's own ("while rendering"); the next render draws. A map uploaded with `shared`
// other than its `heights` is refused.
TEST_F(SceneObject, ErrorsThatAreNotTheLibrarysAreSaidAsSuch) {
    const HeightMap map = synth::cobbles(32, 32, 5);
    RenderJob job;
    job.width = job.height = 16;
    job.camera = test::orbitCamera(40.0, 25.0, 1.7);
    HeadlessRenderer renderer(test::glContext(), job.method);
    renderer.setHeights(job, map, "cobbles");
    const HeadlessResult before = renderer.render(job);
    gl().Enable(0x7fff);  // no capability: GL_INVALID_ENUM, left pending
    try {
        (void)renderer.render(job);
        ADD_FAILURE() << "a render over a pending GL error";
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::Runtime);
        EXPECT_EQ(std::string(e.what()),
                  "GL error 0x0500 left by an earlier call on this context, before rendering "
                  "cobbles");
    }
    EXPECT_EQ(renderer.render(job).frame.position, before.frame.position);

    const auto programs = std::make_shared<ReliefPrograms>(gl(), shaderDirectory());
    const auto other = std::make_shared<const HeightMap>(synth::cobbles(8, 8, 1));
    try {
        (void)ReliefMap::upload(programs, map, other, "cobbles", MapUploadSettings{});
        ADD_FAILURE() << "a map uploaded with another map as its shared heights";
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::Runtime);
        EXPECT_EQ(std::string(e.what()), "ReliefMap::upload: `shared` is not `heights` (cobbles)");
    }
}

// MapUploadSettings::of(relief) builds the map with the relief's addressing: the sphere's
// (u wraps) and a tiled plane's are taken by apply(relief, map); the plain plane's map is not
// the sphere's.
TEST_F(SceneObject, AMapBuiltForAReliefIsTheOneItDraws) {
    const auto heights = std::make_shared<const HeightMap>(synth::cobbles(32, 32, 5));
    const auto programs = std::make_shared<ReliefPrograms>(gl(), shaderDirectory());
    ReliefDesc sphere, tiled, plane;
    sphere.base = BaseShape::sphere();
    tiled.tiles = {3, 2};
    for (const ReliefDesc* relief : {&sphere, &tiled, &plane}) {
        const MapUploadSettings settings = MapUploadSettings::of(*relief);
        EXPECT_EQ(settings.wrapU, relief->base.wrapsU());
        EXPECT_EQ(settings.tiles, relief->tiles);
        const std::shared_ptr<ReliefMap> map =
            ReliefMap::upload(programs, *heights, heights, "cobbles", settings);
        ReliefRenderer renderer(programs, MethodSettings{});
        EXPECT_NO_THROW(renderer.apply(*relief, map)) << baseName(relief->base);
        if (relief == &plane) {
            EXPECT_THROW(renderer.apply(sphere, map), Error);
        }
    }
}

// Before any map, both draws say so (Error(Runtime)) rather than draw nothing.
TEST_F(SceneObject, DrawingBeforeAMapIsRefused) {
    ReliefRenderer renderer(gl(), shaderDirectory());
    RenderJob job;
    job.width = job.height = 8;
    const CameraFrame camera = resolveCamera(job.camera, job.width, job.height, 2.0, {});
    for (const char* which : {"draw(camera, shading)", "draw(view)"}) {
        try {
            if (std::string(which) == "draw(view)")
                (void)renderer.draw(static_cast<const ViewDesc&>(job));
            else
                renderer.draw(camera, job.shading);
            ADD_FAILURE() << which << " drew without a map";
        } catch (const Error& e) {
            EXPECT_EQ(e.kind(), ErrorKind::Runtime) << which;
            EXPECT_NE(std::string(e.what()).find("no map"), std::string::npos) << e.what();
        }
    }
}

// The window depth written for each convention: OpenGL's [-1, 1] clip depth and
// glClipControl's [0, 1], each standard and reversed (near at 1, a GREATER test, cleared to
// 0). Unprojecting a hit pixel's depth through the projection gives back the AOV's world
// position to 1e-5 (a 32-bit float depth buffer; the camera's range is 0.5 to 5, so depth
// rounding moves a point by about 1e-6 there), and every convention shows the same
// picture, pixel for pixel.
TEST_F(SceneObject, DepthRoundTripsUnderEveryConvention) {
    const HeightMap map = synth::cobbles(40, 40, 3);
    const bool clipControl = gl().ClipControl != nullptr;
    if (!clipControl) std::printf("    no glClipControl here: [0, 1] depth not tried\n");
    ReliefRenderer renderer(gl(), shaderDirectory());
    renderer.apply(ReliefDesc{}, &map, "cobbles");
    const CameraFrame base = resolveCamera(test::orbitCamera(35.0, 40.0, 1.6), 64, 64, 1.0);
    OffscreenTarget target(gl(), 64, 64);
    std::optional<RenderedFrame> first;
    int conventions = 0;
    for (bool zeroToOne : {false, true}) {
        if (zeroToOne && !clipControl) continue;
        for (bool reversed : {false, true}) {
            const DepthConvention depth{zeroToOne, reversed};
            const double near = 0.5, far = 5.0;
            const double aspect = 1.0, fovy = 2.0 * std::atan(glm::length(base.up));
            // Reversed: the same projection with near and far swapped (near -> 1).
            const glm::dmat4 projection =
                zeroToOne ? glm::perspectiveRH_ZO(fovy, aspect, reversed ? far : near,
                                                  reversed ? near : far)
                          : glm::perspectiveRH_NO(fovy, aspect, reversed ? far : near,
                                                  reversed ? near : far);
            CameraFrame camera = base;
            camera.viewProjection = projection * glm::lookAt(base.eye, base.eye + base.forward,
                                                             glm::normalize(base.up));
            if (zeroToOne) gl().ClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
            renderer.setDepthConvention(depth);
            target.clear(glm::vec3(0.1f), reversed ? 0.0f : 1.0f);
            {
                const gl::SrgbWrites srgb(gl());
                renderer.draw(camera, ShadingOptions{});
            }
            const RenderedFrame frame = target.read(camera.eye);
            const std::vector<float> depths = target.readDepth();
            if (zeroToOne) gl().ClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
            ++conventions;

            const glm::dmat4 inverse = glm::inverse(camera.viewProjection);
            double worst = 0.0;
            int hits = 0;
            for (int row = 0; row < 64; ++row) {
                for (int column = 0; column < 64; ++column) {
                    const float* p = frame.positionAt(column, row);
                    if (p[3] < 0.5f) continue;
                    ++hits;
                    const double d = depths[static_cast<std::size_t>(row) * 64 + column];
                    const glm::dvec4 ndc((column + 0.5) / 32.0 - 1.0, 1.0 - (row + 0.5) / 32.0,
                                         zeroToOne ? d : 2.0 * d - 1.0, 1.0);
                    const glm::dvec4 h = inverse * ndc;
                    const glm::dvec3 world = glm::dvec3(h) / h.w;
                    worst = std::max(worst, glm::length(world - frame.worldPositionAt(column, row)));
                }
            }
            std::printf("    clip depth %s, %s: %d hits, worst round trip %.2g\n",
                        zeroToOne ? "[0, 1]" : "[-1, 1]", reversed ? "reversed" : "standard", hits,
                        worst);
            EXPECT_GT(hits, 1000);
            EXPECT_LT(worst, 1e-5) << zeroToOne << reversed;
            if (!first) {
                first = frame;
            } else {
                EXPECT_EQ(frame.color, first->color) << zeroToOne << reversed;
                EXPECT_EQ(frame.position, first->position) << zeroToOne << reversed;
            }
        }
    }
    EXPECT_GE(conventions, 2);
}

// Whatever the caller had bound and set before a draw or an upload is there after it:
// the program, vertex array, array and uniform buffers, the textures of units 0 to 2 and
// the active unit, face culling and winding, the depth test, its function, depth
// clamping, the viewport and the unpack alignment (gl/StateGuard.h).
TEST_F(SceneObject, DrawLeavesTheGlStateAsItFoundIt) {
    const GL& g = gl();
    // A caller's state, as unlike the renderer's as can be.
    const gl::Shader vertex = gl::compileShader(
        g, GL_VERTEX_SHADER,
        {"#version 330 core\nvoid main() { gl_Position = vec4(0.0); }\n", {}, "330 core"});
    const gl::Shader fragment = gl::compileShader(
        g, GL_FRAGMENT_SHADER,
        {"#version 330 core\nout vec4 c;\nvoid main() { c = vec4(1.0); }\n", {}, "330 core"});
    const gl::Program program = gl::linkProgram(g, vertex, fragment, "caller's");
    const gl::VertexArray array = gl::VertexArray::create(g);
    const gl::Buffer buffer = gl::Buffer::create(g), uniforms = gl::Buffer::create(g);
    const gl::Texture textures[3] = {gl::Texture::create(g), gl::Texture::create(g),
                                     gl::Texture::create(g)};
    g.UseProgram(program.id());
    g.BindVertexArray(array.id());
    g.BindBuffer(GL_ARRAY_BUFFER, buffer.id());
    g.BindBufferBase(GL_UNIFORM_BUFFER, 0, uniforms.id());
    for (GLuint unit = 0; unit < 3; ++unit) {
        g.ActiveTexture(GL_TEXTURE0 + unit);
        g.BindTexture(GL_TEXTURE_2D, textures[unit].id());
    }
    g.ActiveTexture(GL_TEXTURE5);
    g.Disable(GL_CULL_FACE);
    g.CullFace(GL_FRONT_AND_BACK);
    g.FrontFace(GL_CW);
    g.Disable(GL_DEPTH_TEST);
    g.DepthFunc(GL_ALWAYS);
    g.Disable(GL_DEPTH_CLAMP);
    g.Viewport(1, 2, 3, 4);
    g.PixelStorei(GL_UNPACK_ALIGNMENT, 1);

    auto snapshot = [&] {
        std::vector<GLint> s;
        for (GLenum name : {GL_CURRENT_PROGRAM, GL_VERTEX_ARRAY_BINDING, GL_ARRAY_BUFFER_BINDING,
                            GL_UNIFORM_BUFFER_BINDING, GL_ACTIVE_TEXTURE, GL_CULL_FACE_MODE,
                            GL_FRONT_FACE, GL_DEPTH_FUNC, GL_UNPACK_ALIGNMENT}) {
            GLint value = 0;
            g.GetIntegerv(name, &value);
            s.push_back(value);
        }
        GLint binding0 = 0;
        g.GetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, 0, &binding0);
        s.push_back(binding0);
        GLint active = 0;
        g.GetIntegerv(GL_ACTIVE_TEXTURE, &active);
        for (GLuint unit = 0; unit < 3; ++unit) {
            GLint texture = 0;
            g.ActiveTexture(GL_TEXTURE0 + unit);
            g.GetIntegerv(GL_TEXTURE_BINDING_2D, &texture);
            s.push_back(texture);
        }
        g.ActiveTexture(static_cast<GLenum>(active));
        for (GLenum capability : {GL_CULL_FACE, GL_DEPTH_TEST, GL_DEPTH_CLAMP})
            s.push_back(g.IsEnabled(capability));
        GLint viewport[4];
        g.GetIntegerv(GL_VIEWPORT, viewport);
        s.insert(s.end(), viewport, viewport + 4);
        return s;
    };
    const std::vector<GLint> before = snapshot();

    const HeightMap map = synth::cobbles(32, 32, 5);
    OffscreenTarget target(g, 32, 32);
    ReliefRenderer renderer(g, shaderDirectory());
    renderer.apply(ReliefDesc{}, &map, "cobbles");
    target.clear(glm::vec3(0.0f));  // binds the target: the one change the caller asked for
    renderer.draw(resolveCamera(test::orbitCamera(40.0, 30.0, 1.8), 32, 32, 1.0), ShadingOptions{});
    g.BindFramebuffer(GL_FRAMEBUFFER, 0);
    g.Viewport(1, 2, 3,
               4);  // OffscreenTarget::clear set its own: the target's doing, not the draw's

    EXPECT_EQ(snapshot(), before);
    // And it drew: the relief covers part of the picture.
    const RenderedFrame frame = target.read(glm::dvec3(0.0));  // hits counted only
    int hits = 0;
    for (std::size_t k = 3; k < frame.position.size(); k += 4) hits += frame.position[k] > 0.5f;
    EXPECT_GT(hits, 100);
    // The caller's objects die with this scope: leave none of them bound (a program
    // deleted while current would outlive the test).
    g.UseProgram(0);
    g.BindVertexArray(0);
    EXPECT_EQ(g.GetError(), static_cast<GLenum>(GL_NO_ERROR));
}

// ReliefParameters (C++, generated from shaders/relief_parameters.glsl) and the
// MicroreliefParameters block the linker laid out (std140) agree on every member's offset
// and on the block's size.
TEST_F(SceneObject, ParametersBlockMatchesItsMirror) {
    const ReliefShader shader(gl(), shaderDirectory(), ReliefShaderConfig{});
    EXPECT_EQ(shader.parametersSize(), static_cast<GLint>(sizeof(ReliefParameters)));
    EXPECT_GT(std::size(kReliefParameterMembers), 30u);
    for (const auto& [name, offset] : kReliefParameterMembers)
        EXPECT_EQ(shader.parameterOffset(name), static_cast<GLint>(offset)) << name;
}

// Closest and any hit over [0, inf) and over a range that starts inside the relief (many
// rays start in the solid, and hit at tMin) and ends inside it (many hits lie beyond), on
// the plane with both last levels and on a cylinder: against the reference, hit/miss may
// flip for at most 0.2 % of pixels (rays that meet the surface within float rounding of
// tMin or tMax), and t agrees to 1e-4 (about 2e-3 texels: the exact hits of every other
// test agree far closer) for all but 0.2 %.
TEST_F(SceneObject, RangeQueriesFromAnEnginesOwnShader) {
    const std::string single =
        readFile(dataDirectory() / "shaders" / "single" / "multilevel_trace.glsl");
    ASSERT_FALSE(single.empty());
    const HeightMap map = synth::cobbles(64, 64, 11);
    struct Case {
        const char* name;
        BaseShape base;
        Interpolation interpolation;
        double distance;
    };
    for (const Case& c :
         {Case{"plane, bilinear", {}, Interpolation::Bilinear, 1.5},
          Case{"plane, biquadratic", {}, Interpolation::Biquadratic, 1.5},
          Case{"cylinder", BaseShape::cylinder(0.3, 1.0), Interpolation::Bilinear, 1.2}}) {
        std::printf("    %s\n", c.name);
        expectRangeQueries(single, map, c.base, c.interpolation, c.distance);
    }
}

}  // namespace

// mr_wrapIndex, the curved bases' wrap of a sample or cell column round the seam, is i mod
// n in 0..n - 1 for every i and n a shader meets (i from -2n to 2n, n from 1 to 200, the
// odd sizes with it), in integers alone. Its float predecessor, floor(float(i) /
// float(n)), was exact under llvmpipe's division and one off at multiples of n under
// NVIDIA's (docs/perf/2026-12-04-gpu-h200.md), which no test here could show.
TEST_F(SceneObject, WrapIndexIsTheExactModuloForEveryColumnAShaderMeets) {
    const GL& g = gl();
    const std::string single =
        readFile(dataDirectory() / "shaders" / "single" / "multilevel_trace.glsl");
    ASSERT_FALSE(single.empty());
    const char* const main = R"(
layout(location = 0) out vec4 outColor;
layout(location = 1) out vec4 outWrapped;
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    int n = p.y + 1, i = p.x - 2 * n;
    outColor = vec4(0.0);
    outWrapped = vec4(float(mr_wrapIndex(i, n)), float(i), float(n), 1.0);
}
)";
    const std::string macros = "#version 330 core\n#define MICRORELIEF_BASE " +
                               std::to_string(glsl::kBaseKindCylinder) + "\n";  // u wraps
    const gl::Shader vertex =
        gl::compileShader(g, GL_VERTEX_SHADER, {kFullScreenTriangle, {}, "330 core"});
    const gl::Shader fragment =
        gl::compileShader(g, GL_FRAGMENT_SHADER, {macros + single + main, {}, "330 core"});
    const gl::Program program = gl::linkProgram(g, vertex, fragment, "mr_wrapIndex");
    const gl::VertexArray empty = gl::VertexArray::create(g);
    const int width = 801, height = 200;  // i up to 4n + 1 - 2n for n = 200
    OffscreenTarget target(g, width, height);
    target.clear(glm::vec3(0.0f));
    {
        const gl::StateGuard saved(g);
        g.UseProgram(program.id());
        g.Disable(GL_DEPTH_TEST);
        g.BindVertexArray(empty.id());
        g.DrawArrays(GL_TRIANGLES, 0, 3);
    }
    const RenderedFrame frame = target.read(glm::dvec3(0.0));
    // Each pixel says which i and n it wrapped (the frame's rows may run either way up).
    long checked = 0, wrong = 0;
    for (int row = 0; row < height; ++row) {
        for (int column = 0; column < width; ++column) {
            const float* got = frame.positionAt(column, row);
            const int i = int(got[1]), n = int(got[2]);
            ASSERT_GE(n, 1);
            if (i > 2 * n) continue;
            const int expected = ((i % n) + n) % n;
            wrong += int(got[0]) != expected;
            ++checked;
        }
    }
    EXPECT_EQ(wrong, 0) << "of " << checked;
    EXPECT_EQ(checked, 200L * 201 * 2 + 200);  // the sum of 4n + 1 for n = 1..200
}
