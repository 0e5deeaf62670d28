#include "microrelief/render/ReliefRenderer.h"

#include <algorithm>
#include <array>
#include <string>
#include <vector>

#include <glm/gtc/type_ptr.hpp>

#include "microrelief/core/Error.h"
#include "microrelief/gl/ShaderProgram.h"
#include "microrelief/trace/MultilevelTracer.h"

namespace microrelief {

namespace {
constexpr const char* kDebugViewNames[] = {"shaded", "iterations", "level",
                                           "normal", "depth",      "position"};
constexpr const char* kMethodNames[] = {"multilevel", "normal", "offset", "steep",
                                        "pom",        "relief", "maxmip"};

// The enum value whose name is `name`, by position in `names`; throws Error(BadInput)
// naming the flag and the choices.
template <class Enum, std::size_t N>
Enum parseName(const char* const (&names)[N], const std::string& name, const char* flag) {
    std::string choices;
    for (std::size_t k = 0; k < N; ++k) {
        if (name == names[k]) return static_cast<Enum>(k);
        choices += std::string(k == 0 ? "" : k + 1 == N ? " or " : ", ") + names[k];
    }
    throwBadInput(std::string("unknown ") + flag + " '" + name + "' (expected " + choices + ")");
}
}  // namespace

Method parseMethod(const std::string& name) {
    return parseName<Method>(kMethodNames, name, "--method");
}

const char* methodName(Method method) {
    return kMethodNames[static_cast<int>(method)];
}

bool methodHasSteps(Method method) {
    return method == Method::Steep || method == Method::Pom || method == Method::Relief;
}

bool methodTracesTheSolid(Method method) {
    return method == Method::Multilevel || method == Method::MaxMip;
}

bool methodRunsOnBase(Method method, const BaseShape& base) {
    return !base.curved() || method == Method::Multilevel || method == Method::MaxMip ||
           method == Method::Pom || method == Method::Relief;
}

void checkMethodSupportsBase(Method method, const BaseShape& base) {
    if (methodRunsOnBase(method, base)) return;
    throwBadInput(std::string("--method ") + methodName(method) + " does not run on --base " +
                  baseName(base) + " (curved bases take multilevel, maxmip, pom and relief)");
}

DebugView parseDebugView(const std::string& name) {
    return parseName<DebugView>(kDebugViewNames, name, "--view");
}

const char* debugViewName(DebugView view) {
    return kDebugViewNames[static_cast<int>(view)];
}

ReliefRenderer::ReliefRenderer(const GL& gl, const std::filesystem::path& shaderDir,
                               const MethodSettings& method)
    : gl_(gl), shaderDir_(shaderDir), method_(method) {
    reloadShaders();
    pyramidTexture_ = gl::Texture::create(gl_);
    windowTexture_ = gl::Texture::create(gl_);
    sampleTexture_ = gl::Texture::create(gl_);
    boxArray_ = gl::VertexArray::create(gl_);
    boxVertices_ = gl::Buffer::create(gl_);
    boxIndices_ = gl::Buffer::create(gl_);
}

ReliefRenderer::CompiledProgram ReliefRenderer::compile(const ProgramKey& key) const {
    const auto [method, countFetches, base, interpolation] = key;
    // GLSL 4.00 core where the GL has it (a patch's four samples in one textureGather:
    // bilinear_patch.glsl), else 3.30 core, the oldest with explicit output locations.
    GLint major = 0;
    gl_.GetIntegerv(GL_MAJOR_VERSION, &major);
    const std::string version = major >= 4 ? "400 core" : "330 core";
    std::vector<ShaderDefine> defines = {
        {"MICRORELIEF_METHOD", std::to_string(static_cast<int>(method))},
        {"MICRORELIEF_BASE", std::to_string(static_cast<int>(base))},
        {"MICRORELIEF_INTERPOLATION", std::to_string(static_cast<int>(interpolation))}};
    if (countFetches) defines.push_back({"MICRORELIEF_COUNT_FETCHES", ""});
    const gl::Shader vertex = gl::compileShader(
        gl_, GL_VERTEX_SHADER, assembleShader(shaderDir_ / "relief_box.vert", version));
    const gl::Shader fragment = gl::compileShader(
        gl_, GL_FRAGMENT_SHADER, assembleShader(shaderDir_ / "relief.frag", version, defines));
    return {gl::linkProgram(gl_, vertex, fragment,
                            std::string("relief (") + methodName(method) + ", " +
                                baseName(BaseShape{base}) + ", " +
                                interpolationName(interpolation) + ")"),
            {}};
}

void ReliefRenderer::reloadShaders() {
    const ProgramKey key{method_.method, countFetches_, base_.kind, interpolation_};
    CompiledProgram fresh = compile(key);  // throws before anything changes
    programs_.clear();
    current_ = &(programs_[key] = std::move(fresh));
}

ReliefRenderer::CompiledProgram& ReliefRenderer::program(const ProgramKey& key) {
    auto found = programs_.find(key);
    if (found == programs_.end())
        found = programs_.emplace(key, compile(key)).first;  // throws: nothing changes
    return found->second;
}

void ReliefRenderer::setMethod(const MethodSettings& settings, bool countFetches) {
    checkMethodSupportsBase(settings.method, base_);
    current_ = &program({settings.method, countFetches, base_.kind, interpolation_});
    method_ = settings;
    countFetches_ = countFetches;
}

void ReliefRenderer::setBase(const BaseShape& base) {
    validateBaseShape(base);
    if (mapWidth_ > 0 && base.wrapsU() != wrapsU_) {
        throwRuntime(
            "ReliefRenderer::setBase: between the plane and a curved base the map must "
            "be uploaded again (setHeightMap)");
    }
    checkMethodSupportsBase(method_.method, base);
    current_ = &program({method_.method, countFetches_, base.kind, interpolation_});
    base_ = base;
    if (mapWidth_ > 0) uploadBox();
}

GLint ReliefRenderer::uniform(const char* name) {
    auto [it, inserted] = current_->uniforms.try_emplace(name, -1);
    if (inserted) it->second = gl_.GetUniformLocation(current_->program.id(), name);
    return it->second;
}

namespace {

void uploadLevel(const GL& gl, int level, int width, int height, const float* data) {
    gl.TexImage2D(GL_TEXTURE_2D, level, GL_R32F, width, height, 0, GL_RED, GL_FLOAT, data);
}

// The samples of a curved base repeat in S, so that a patch's textureGather at the seam
// reads column W - 1 and column 0 (bilinear_patch.glsl); everything else clamps.
void setSamplerState(const GL& gl, GLint minFilter, int maxLevel, bool repeatS = false) {
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, minFilter);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, repeatS ? GL_REPEAT : GL_CLAMP_TO_EDGE);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_BASE_LEVEL, 0);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, maxLevel);
}

}  // namespace

void ReliefRenderer::setHeightMap(const HeightMap& map, const std::string& source,
                                  const BaseShape& base, Interpolation interpolation) {
    validateBaseShape(base);
    checkMethodSupportsBase(method_.method, base);
    GLint maxSize = 0;
    gl_.GetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    if (map.width > maxSize || map.height > maxSize) {
        throwBadInput(source + ": " + std::to_string(map.width) + "x" + std::to_string(map.height) +
                      " is larger than this GPU's GL_MAX_TEXTURE_SIZE (" + std::to_string(maxSize) +
                      ")");
    }
    // Both throw before anything changes (the program is compiled, or looked up, first).
    CompiledProgram& next = program({method_.method, countFetches_, base.kind, interpolation});
    const MaxPyramid pyramid = [&] {
        try {
            // On the GPU from here on; only its shape is kept.
            return MaxPyramid(map, base.wrapsU(), interpolation);
        } catch (const std::bad_alloc&) {
            throwRuntime(source + ": not enough memory for the max pyramid of its " +
                         std::to_string(map.width) + "x" + std::to_string(map.height) + " samples");
        }
    }();
    current_ = &next;  // std::map: the reference stays valid
    base_ = base;
    wrapsU_ = base.wrapsU();
    interpolation_ = interpolation;
    mapWidth_ = map.width;
    mapHeight_ = map.height;
    pyramidWidth_ = pyramid.levelWidth(0);
    pyramidHeight_ = pyramid.levelHeight(0);
    pyramidLevels_ = pyramid.levelCount();
    maxHeight_ = pyramid.texel(pyramid.levelCount() - 1, 0, 0);
    maxIterations_ = traversalBudget(map.width, map.height);

    gl_.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    for (bool windows : {false, true}) {
        gl_.BindTexture(GL_TEXTURE_2D, (windows ? windowTexture_ : pyramidTexture_).id());
        for (int level = 0; level < pyramid.levelCount(); ++level) {
            uploadLevel(
                gl_, level, pyramid.levelWidth(level), pyramid.levelHeight(level),
                (windows ? pyramid.windowLevelData(level) : pyramid.levelData(level)).data());
        }
        setSamplerState(gl_, GL_NEAREST_MIPMAP_NEAREST, pyramid.levelCount() - 1);
    }

    gl_.BindTexture(GL_TEXTURE_2D, sampleTexture_.id());
    uploadLevel(gl_, 0, map.width, map.height, map.samples.data());
    setSamplerState(gl_, GL_NEAREST, 0, wrapsU_);
    gl_.BindTexture(GL_TEXTURE_2D, 0);
    uploadBox();
}

void ReliefRenderer::setHeightScale(float scale) {
    heightScale_ = scale;
    if (mapWidth_ > 0) uploadBox();
}

void ReliefRenderer::uploadBox() {
    // A small margin keeps every pixel whose ray meets the exact box inside the
    // rasterised proxy; the shader clips the ray to the exact shell itself.
    const ReliefExtent extent =
        reliefExtent(mapWidth_, mapHeight_, maxHeight_, heightScale_, base_);
    const glm::vec3 lo = glm::vec3(extent.min) - 1e-3f, hi = glm::vec3(extent.max) + 1e-3f;
    const std::array<float, 24> corners = {lo.x, lo.y, lo.z, hi.x, lo.y, lo.z, hi.x, lo.y,
                                           hi.z, lo.x, lo.y, hi.z, lo.x, hi.y, lo.z, hi.x,
                                           hi.y, lo.z, hi.x, hi.y, hi.z, lo.x, hi.y, hi.z};
    // Outward-facing counter-clockwise triangles, two per face.
    const std::array<GLushort, 36> indices = {0, 1, 2, 0, 2, 3, 4, 6, 5, 4, 7, 6, 0, 4, 5, 0, 5, 1,
                                              1, 5, 6, 1, 6, 2, 2, 6, 7, 2, 7, 3, 3, 7, 4, 3, 4, 0};
    gl_.BindVertexArray(boxArray_.id());
    gl_.BindBuffer(GL_ARRAY_BUFFER, boxVertices_.id());
    gl_.BufferData(GL_ARRAY_BUFFER, sizeof(corners), corners.data(), GL_STATIC_DRAW);
    gl_.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, boxIndices_.id());
    gl_.BufferData(GL_ELEMENT_ARRAY_BUFFER, sizeof(indices), indices.data(), GL_STATIC_DRAW);
    gl_.EnableVertexAttribArray(0);
    gl_.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
    gl_.BindVertexArray(0);
}

void ReliefRenderer::draw(const CameraFrame& camera, const ShadingOptions& shading,
                          const PictureTile& tile) {
    if (mapWidth_ == 0) return;
    gl_.UseProgram(current_->program.id());
    const glm::vec3 eye(camera.eye), right(camera.right), up(camera.up), forward(camera.forward);
    // A tile: the same clip space, scaled and shifted in x and y so that the tile fills
    // the viewport (rows z and w are untouched, so the depth is the whole picture's to
    // the bit); the shader adds the tile's origin to gl_FragCoord, so each pixel casts
    // the ray it casts in the whole picture.
    const PictureTile whole{0, 0, camera.width, camera.height};
    const PictureTile& t = tile.width > 0 ? tile : whole;
    glm::dmat4 toTile(1.0);
    toTile[0][0] = static_cast<double>(camera.width) / t.width;
    toTile[1][1] = static_cast<double>(camera.height) / t.height;
    toTile[3][0] = static_cast<double>(camera.width - 2 * t.x - t.width) / t.width;
    toTile[3][1] = static_cast<double>(camera.height - 2 * t.y - t.height) / t.height;
    const glm::mat4 viewProjection(toTile * camera.viewProjection);

    gl_.Uniform1i(uniform("maxPyramid"), 0);
    gl_.Uniform1i(uniform("heightSamples"), 1);
    gl_.Uniform1i(uniform("windowPyramid"), 2);
    gl_.Uniform2f(uniform("reliefSize"), static_cast<float>(mapWidth_),
                  static_cast<float>(mapHeight_));
    gl_.Uniform2i(uniform("pyramidSize"), pyramidWidth_, pyramidHeight_);
    gl_.Uniform1i(uniform("pyramidLevels"), pyramidLevels_);
    gl_.Uniform1f(uniform("reliefMaxHeight"), maxHeight_);
    gl_.Uniform1f(uniform("heightScale"), heightScale_);
    gl_.Uniform1i(uniform("maxIterations"), maxIterations_);
    const ReliefExtent extent =
        reliefExtent(mapWidth_, mapHeight_, maxHeight_, heightScale_, base_);
    gl_.Uniform3fv(uniform("frameScale"), 1, glm::value_ptr(glm::vec3(base_.frameScale())));
    gl_.Uniform3fv(uniform("reliefBoxMin"), 1, glm::value_ptr(glm::vec3(extent.min)));
    gl_.Uniform3fv(uniform("reliefBoxMax"), 1, glm::value_ptr(glm::vec3(extent.max)));
    gl_.Uniform3fv(uniform("eye"), 1, glm::value_ptr(eye));
    gl_.Uniform3fv(uniform("cameraRight"), 1, glm::value_ptr(right));
    gl_.Uniform3fv(uniform("cameraUp"), 1, glm::value_ptr(up));
    gl_.Uniform3fv(uniform("cameraForward"), 1, glm::value_ptr(forward));
    gl_.Uniform2f(uniform("viewportSize"), static_cast<float>(camera.width),
                  static_cast<float>(camera.height));
    gl_.Uniform2f(uniform("tileOrigin"), static_cast<float>(t.x), static_cast<float>(t.y));
    gl_.UniformMatrix4fv(uniform("viewProjection"), 1, GL_FALSE, glm::value_ptr(viewProjection));
    gl_.Uniform3fv(uniform("lightDirection"), 1,
                   glm::value_ptr(glm::normalize(shading.lightDirection)));
    gl_.Uniform3fv(uniform("albedo"), 1, glm::value_ptr(shading.albedo));
    gl_.Uniform1i(uniform("debugView"), static_cast<int>(shading.view));
    gl_.Uniform1i(uniform("methodSteps"), method_.steps);
    gl_.Uniform1i(uniform("methodMinSteps"), method_.minSteps);
    gl_.Uniform1i(uniform("methodRefineSteps"), method_.refineSteps);
    gl_.Uniform1f(uniform("pixelErrorTolerance"), method_.pixelError);

    gl_.ActiveTexture(GL_TEXTURE0);
    gl_.BindTexture(GL_TEXTURE_2D, pyramidTexture_.id());
    gl_.ActiveTexture(GL_TEXTURE1);
    gl_.BindTexture(GL_TEXTURE_2D, sampleTexture_.id());
    gl_.ActiveTexture(GL_TEXTURE2);
    gl_.BindTexture(GL_TEXTURE_2D, windowTexture_.id());

    // Back faces only: exactly one fragment per pixel the box covers, also with the eye
    // inside the box. Depth clamping keeps faces nearer than the near plane.
    gl_.Enable(GL_CULL_FACE);
    gl_.CullFace(GL_FRONT);
    gl_.Enable(GL_DEPTH_TEST);
    gl_.DepthFunc(GL_LESS);
    gl_.Enable(GL_DEPTH_CLAMP);
    gl_.Viewport(0, 0, t.width, t.height);

    gl_.BindVertexArray(boxArray_.id());
    gl_.DrawElements(GL_TRIANGLES, 36, GL_UNSIGNED_SHORT, nullptr);
    gl_.BindVertexArray(0);

    gl_.Disable(GL_DEPTH_CLAMP);
    gl_.Disable(GL_CULL_FACE);
    gl_.ActiveTexture(GL_TEXTURE0);
    gl_.UseProgram(0);
}

}  // namespace microrelief
