#include "ViewerApp.h"

#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>

#include <chrono>
#include <cstdio>

#include "MapFile.h"
#include "SceneOptions.h"
#include "microrelief/core/DataPaths.h"
#include "microrelief/core/Error.h"
#include "microrelief/core/Log.h"
#include "microrelief/core/base/BaseSurface.h"
#include "microrelief/gl/StateGuard.h"
#include "microrelief/io/ImageFile.h"
#include "microrelief/io/ReliefFiles.h"

namespace microrelief {

namespace {

// An error as the viewer shows it: the fields it names as the flags the viewer takes
// (--normalize, not map.load.normalize), as its command line's refusals say them.
std::string shown(const Error& e) {
    return e.message(flagName);
}

constexpr int kLogLines = 8;
// How often the panel's iteration figure is read back: a few times a second is live
// enough, and keeps the readback off most frames on a software rasteriser.
constexpr double kStatisticsInterval = 0.25;
// Fly speed, world units a second (the map spans 1); Shift and Ctrl scale it.
constexpr double kFlySpeed = 0.25;

double now() {
    return glfwGetTime();
}

}  // namespace

std::filesystem::path viewerShaderDirectory(const ViewerOptions& options) {
    if (options.shaderDir) return *options.shaderDir;
    std::error_code ec;
    const std::filesystem::path source = MICRORELIEF_SOURCE_SHADER_DIR;
    const bool fromBuildTree =
        std::filesystem::equivalent(dataDirectory(), MICRORELIEF_BUILD_DATA_DIR, ec);
    if (fromBuildTree && std::filesystem::is_regular_file(source / "relief.frag", ec))
        return source;
    return shaderDirectory();
}

ViewerApp::ViewerApp(const ViewerOptions& options)
    : options_(options), controller_(options.scene.job.camera) {
    state_.scene = options.scene;
    state_.vsync = options.vsync && options.frames == 0;
    state_.panelVisible = options.panel;
    // The map the scene names (io/ReliefFiles.h), the viewer's own to sculpt.
    const std::filesystem::path file = heightMapPath(options.scene.job);
    ReliefFiles loaded = loadReliefFiles(options.scene.job, ReliefParts::Heights);
    const std::string fitted = fitRelief(loaded, file.string());
    ground_ = mapGround(loaded);
    // --save-map FILE.tif keeps a DEM's grid: refused for another map before a window opens.
    if (options.saveMap) checkMapSave(*options.saveMap, ground_);
    const RenderJob& job = state_.scene.job;  // the command line's, over the map
    map_ = loaded.takeHeights();
    mapMaxHeight_ = map_->maxValue();  // once per map, not per frame
    loadedWith_ = options.scene.job.map.load;
    // A bad albedo is a bad argument too: refused before any window opens.
    const ReliefFiles colours = loadReliefFiles(options.scene.job, ReliefParts::Albedo);
    // A degenerate camera is a bad argument: refuse it before any window opens.
    resolveCamera(controller_.camera(), job.width, job.height,
                  sceneRadius(reliefExtent(map_->width * job.tiles.x, map_->height * job.tiles.y,
                                           mapMaxHeight_, job.heightScale, job.base),
                              job.model.objectToWorld()));

    state_.mapName = file.filename().string();
    setupWindow();
    const GL& gl = window_->gl();
    const std::filesystem::path shaders = viewerShaderDirectory(options);
    renderer_ = std::make_unique<ReliefRenderer>(gl, shaders);
    renderer_->setMethod(options.scene.job.method);
    renderer_->setPaging(options.paging);
    applyRelief(map_, file.string());
    if (renderer_->paged() && (options.sculpt || !options.strokes.empty() || options.undo > 0 ||
                               options.saveMap || !options.scene.job.animation.empty())) {
        throwBadInput(file.string() +
                      ": read through pages (larger than the GL's textures), which is neither "
                      "sculpted nor animated");
    }
    timer_ = std::make_unique<GpuTimer>(gl);
    watcher_ = std::make_unique<ShaderWatcher>(shaders);
    sculptTool_ = std::make_unique<SculptTool>(gl, shaders);
    if (!options.scene.job.animation.empty()) {
        animated_ = std::make_unique<AnimatedHeights>(gl, shaders, options.scene.job.animation);
        evaluateAnimation();  // at --time: the first frame drawn shows it
    }
    state_.sculpt = options.sculpt && sculptable();
    state_.brush = options.brush;
    state_.savePath = editedMapPath(file, ground_.has_value());
    if (colours.albedo) renderer_->setAlbedo(&*colours.albedo, colours.albedoFile->string());
    state_.albedoName = colours.albedoFile ? colours.albedoFile->filename().string() : "";

    if (state_.scene.job.map.file)
        state_.scene.job.map.file = std::filesystem::absolute(*state_.scene.job.map.file);
    state_.mapWidth = map_->width;
    state_.mapHeight = map_->height;
    state_.iterationBudget = renderer_->maxIterations();
    state_.shaderFolder = shaders.string();
    state_.glRenderer = window_->renderer() + ", " + window_->version();
    if (options.verbose) note("GL: " + state_.glRenderer);
    if (!fitted.empty()) note(fitted);
}

std::string ViewerApp::fitRelief(const ReliefFiles& loaded, const std::string& source) {
    RenderJob& job = state_.scene.job;
    const GeoreferenceFit& fit = options_.scene.georeference;
    if (georeferenced_) {
        const RenderJob& given = options_.scene.job;
        if (!fit.keepHeightScale) job.heightScale = given.heightScale;
        if (!fit.keepModel) job.model = given.model;
        if (!fit.keepBase) job.base = given.base;
    }
    job = sceneOverMap(job, fit, loaded.heights->width, loaded.heights->height, loaded.georeference,
                       source);
    georeferenced_ = loaded.georeference.has_value();
    return loaded.georeference ? georeferenceSummary(source, *loaded.georeference, job, fit)
                               : exaggerationUnused(source, fit, loaded.georeference);
}

ViewerApp::~ViewerApp() = default;

void ViewerApp::setupWindow() {
    GlfwWindowOptions windowOptions;
    windowOptions.width = options_.scene.job.width;
    windowOptions.height = options_.scene.job.height;
    windowOptions.title = "microrelief-viewer: " + state_.mapName;
    window_ = createGlfwContext(windowOptions);
    GLFWwindow* window = window_->window();

    // A --size larger than the screen would open a window partly off it: fit the window
    // (an automated --screenshot still renders at exactly --size, offscreen).
    GLFWmonitor* monitor = glfwGetPrimaryMonitor();
    if (const GLFWvidmode* mode = monitor ? glfwGetVideoMode(monitor) : nullptr) {
        int width = 0, height = 0;
        glfwGetWindowSize(window, &width, &height);
        const double fit = std::min({1.0, 0.95 * mode->width / width, 0.9 * mode->height / height});
        if (fit < 1.0)
            glfwSetWindowSize(window, static_cast<int>(width * fit),
                              static_cast<int>(height * fit));
    }
    float scaleX = 1.0f, scaleY = 1.0f;
    glfwGetWindowContentScale(window, &scaleX, &scaleY);
    uiScale_ = std::max(1.0f, scaleX);

    glfwSetWindowUserPointer(window, this);
    // Installed before ImGui's callbacks, which call on to it.
    glfwSetDropCallback(window, [](GLFWwindow* w, int count, const char** paths) {
        if (count > 0)
            static_cast<ViewerApp*>(glfwGetWindowUserPointer(w))->droppedFile_ = paths[count - 1];
    });
    // Key presses are queued, not polled: a tap shorter than a slow frame (a software
    // rasteriser's) would fall between two polls of ImGui's key state.
    glfwSetKeyCallback(window, [](GLFWwindow* w, int key, int, int action, int mods) {
        if (action == GLFW_PRESS)
            static_cast<ViewerApp*>(glfwGetWindowUserPointer(w))
                ->pressedKeys_.push_back({key, mods});
    });
    glfwSetWindowCloseCallback(window, [](GLFWwindow* w) {
        glfwSetWindowShouldClose(w, GLFW_FALSE);
        static_cast<ViewerApp*>(glfwGetWindowUserPointer(w))->askToQuit();
    });
    imgui_ = std::make_unique<ImGuiLayer>(*window_, uiScale_);
    setVsync(state_.vsync);
}

int ViewerApp::run() {
    int drawn = 0;
    runScript();
    bool laidOut = false;
    lastFrameTime_ = now();
    while (!glfwWindowShouldClose(window_->window()) &&
           (options_.frames == 0 || drawn < options_.frames || pages_.refining())) {
        waitForEvents();
        if (framebufferSize().x == 0 || framebufferSize().y == 0) {
            glfwWaitEvents();  // minimised: nothing to draw until it comes back
            continue;
        }
        if (!laidOut) {
            // The panel laid out once, unseen, at the window's size, so that the first
            // frame drawn (a one-frame --window-screenshot's) shows it. ImGui hides a new
            // window in the frame that sizes it, where nothing in it can be hovered or
            // clicked: the panel asks for nothing there.
            imgui_->beginFrame();
            drawPanel(state_, uiScale_);
            imgui_->endFrameUndrawn();
            laidOut = true;
        }
        const double start = now();
        frame();
        // A paged map's view draws on past --frames until it is exact.
        const bool last = drawn + 1 >= options_.frames && !pages_.refining();
        present(last && options_.windowScreenshot.has_value());
        state_.frameMilliseconds = (now() - start) * 1e3;
        ++drawn;
    }
    if (options_.frames > 0) {
        if (drawn < options_.frames) throwRuntime("the window closed before the last of --frames");
        writeAutomationOutputs();
    }
    if (options_.printCommand) std::printf("%s\n", renderCommand().c_str());
    return 0;
}

void ViewerApp::writeAutomationOutputs() {
    const GLenum error = window_->gl().GetError();
    if (error != GL_NO_ERROR) throwRuntime("GL error " + gl::enumHex(error) + " while rendering");
    if (options_.saveMap) saveMap(*options_.saveMap);  // throws: a failed save fails the run
    ImageWriteBatch batch;                             // both files or neither
    if (options_.screenshot && pages_.pagesWanted()) {
        logWarning(options_.screenshot->string() +
                   ": not the exact picture: its view reads more pages at once than --memory "
                   "holds (drawn from coarser bounds in parts)");
    }
    const RgbPicture view = options_.screenshot ? viewPicture(*target_, drawnEye_) : RgbPicture{};
    if (options_.screenshot) batch.write(*options_.screenshot, view.image());
    if (options_.windowScreenshot) batch.write(*options_.windowScreenshot, windowPixels_.image());
    batch.commit();
}

void ViewerApp::waitForEvents() {
    // Poll while anything moves; otherwise sleep until an event (or a look at the
    // shader folder is due), so an idle viewer costs nothing.
    const bool busy =
        options_.frames > 0 || state_.continuous || framesToDraw_ > 0 || ImGui::IsAnyMouseDown();
    if (busy) {
        glfwPollEvents();
        framesToDraw_ = std::max(framesToDraw_ - 1, 0);
        return;
    }
    const double timeout = 0.3, start = now();
    glfwWaitEventsTimeout(timeout);
    // Woken by an event: draw a few frames, as ImGui settles hover and clicks over two.
    if (now() - start < 0.9 * timeout) framesToDraw_ = 3;
}

void ViewerApp::frame() {
    // Fly speed needs the time since the last frame, idle waits included; the panel
    // shows the frame's own work, which the waits would hide.
    const double time = now();
    const double seconds = time - lastFrameTime_;
    lastFrameTime_ = time;

    if (droppedFile_) {
        const std::filesystem::path file = *droppedFile_;
        droppedFile_.reset();
        openMap(file);
    }
    if (watcher_->changed()) reloadShaders();

    imgui_->beginFrame();
    handleInput(seconds);
    if (animated_) animate(seconds);
    updatePick();
    sculpt();
    state_.yawDegrees = controller_.yawDegrees();
    state_.pitchDegrees = controller_.pitchDegrees();
    state_.scene.job.camera = controller_.camera();
    const glm::ivec2 size = viewSize();
    state_.scene.job.width = size.x;
    state_.scene.job.height = size.y;
    applyPanel(drawPanel(state_, uiScale_));
    renderView();
    sampleStatistics();
}

void ViewerApp::handleInput(double seconds) {
    if (!imgui_->wantsKeyboard()) {
        for (const KeyPress& press : pressedKeys_) handleKey(press.key, press.mods);
        if (state_.flyMode) flyKeys(seconds);
    }
    pressedKeys_.clear();
    if (!imgui_->wantsMouse()) handleMouse();
}

void ViewerApp::askToQuit() {
    // A script's edits are --save-map's to keep (and its window closed early fails the run).
    if (state_.mapEdited && !quitWarned_ && options_.frames == 0) {
        quitWarned_ = true;
        state_.panelVisible = true;
        note(
            "the map has edits not saved: Ctrl+S (out of fly mode) or the panel's Save map writes "
            "them to " +
            state_.savePath + "; Esc or closing the window again quits without them");
        return;
    }
    glfwSetWindowShouldClose(window_->window(), GLFW_TRUE);
}

void ViewerApp::handleKey(int key, int mods) {
    int debugView = 0;
    switch (keyCommand(key, mods, state_.flyMode, &debugView)) {
        case ViewerCommand::None:
            break;
        case ViewerCommand::Quit:
            askToQuit();
            break;
        case ViewerCommand::ToggleFly:
            state_.flyMode = !state_.flyMode;
            break;
        case ViewerCommand::ResetView:
            controller_.reset();
            break;
        case ViewerCommand::TogglePanel:
            state_.panelVisible = !state_.panelVisible;
            break;
        case ViewerCommand::Screenshot:
            takeScreenshot();
            break;
        case ViewerCommand::CopyCommand:
            copyCommand();
            break;
        case ViewerCommand::ToggleVsync:
            setVsync(!state_.vsync);
            break;
        case ViewerCommand::ToggleSculpt:
            state_.sculpt = !state_.sculpt && sculptable();
            if (sculptable())
                note(state_.sculpt
                         ? "sculpting: on (the left button paints, Alt+drag turns the view, B ends)"
                         : "sculpting: off");
            else
                note(animated_ ? "sculpting: not while the relief is animated (" +
                                     flagName("animation") + ")"
                     : renderer_->paged() ? "sculpting: not a map read through pages (larger "
                                            "than the GL's textures)"
                                          : "sculpting: an untiled map only (Tiles 1, 1)");
            break;
        case ViewerCommand::Undo:
            undo();
            break;
        case ViewerCommand::SaveMap:
            saveMap(state_.savePath);
            break;
        case ViewerCommand::ShrinkBrush:
            state_.brush.radius = std::max(state_.brush.radius * 0.8, 0.5);
            break;
        case ViewerCommand::GrowBrush:
            state_.brush.radius = std::min(state_.brush.radius * 1.25, 512.0);
            break;
        case ViewerCommand::TogglePlay:
            state_.playing = !state_.playing;
            break;
        case ViewerCommand::DebugView:
            state_.scene.job.shading.view = static_cast<DebugView>(debugView);
            break;
    }
}

void ViewerApp::flyKeys(double seconds) {
    const glm::dvec3 direction = flyDirection([](int key) { return ImGui::IsKeyDown(key); });
    if (direction == glm::dvec3(0.0)) return;
    const ImGuiIO& io = ImGui::GetIO();
    const double speed = kFlySpeed * (io.KeyShift ? 4.0 : 1.0) * (io.KeyCtrl ? 0.2 : 1.0);
    // A long stall (a slow frame on a software rasteriser) must not throw the eye away.
    controller_.fly(direction * speed * std::min(seconds, 0.25));
    framesToDraw_ = std::max(framesToDraw_, 2);
}

void ViewerApp::handleMouse() {
    const ImGuiIO& io = ImGui::GetIO();
    const double dx = io.MouseDelta.x, dy = io.MouseDelta.y;
    // A drag is a button held since an earlier frame: a move and a press within one frame
    // (a slow one) moved the pointer before the button went down, and turns nothing.
    const auto dragging = [](ImGuiMouseButton button) {
        return ImGui::IsMouseDown(button) && !ImGui::IsMouseClicked(button);
    };
    const bool panning = dragging(ImGuiMouseButton_Right) || dragging(ImGuiMouseButton_Middle) ||
                         (dragging(ImGuiMouseButton_Left) && io.KeyShift);
    const bool movingLight =
        dragging(ImGuiMouseButton_Left) && glfwGetKey(window_->window(), GLFW_KEY_L) == GLFW_PRESS;
    if (movingLight && (dx != 0.0 || dy != 0.0)) {
        // L held: the drag turns the light (InputBindings.h).
        ShadingOptions& shading = state_.scene.job.shading;
        shading.lightDirection = turnLight(shading.lightDirection, dx, dy);
        shading.lightPosition.reset();
    } else if (panning) {
        // The picture's height in window units, which is what the mouse moves in.
        controller_.pan(dx, dy,
                        viewSize().y * viewRect().scale * io.DisplaySize.y / framebufferSize().y);
    } else if (dragging(ImGuiMouseButton_Left) && (dx != 0.0 || dy != 0.0) &&
               (!state_.sculpt || io.KeyAlt)) {  // in sculpt mode the left button paints
        state_.flyMode ? controller_.look(dx, dy) : controller_.orbit(dx, dy);
    }
    if (io.MouseWheel != 0.0f) controller_.zoom(io.MouseWheel);
    if (ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left) && state_.pick)
        controller_.setTarget(state_.pick->position);
}

void ViewerApp::applyPanel(const PanelActions& a) {
    if (a.openMap) openMap(*a.openMap);
    if (a.reloadMap) openMap(state_.scene.job.map.file);
    if (a.albedoChanged) applyAlbedo();
    if (a.heightScaleChanged) changeRelief("height scale");
    if (a.baseChanged) setBase(a.baseKindChanged);
    if (a.interpolationChanged) setInterpolation();
    if (a.fovyChanged) controller_.setFovy(state_.scene.job.camera.fovyDegrees);
    if (a.methodChanged) setMethod();
    if (a.resetView) controller_.reset();
    if (a.reloadShaders) reloadShaders();
    if (a.screenshot) takeScreenshot();
    if (a.copyCommand) copyCommand();
    if (a.vsyncChanged) setVsync(state_.vsync);
    if (a.undo) undo();
    if (a.saveMap) saveMap(state_.savePath);
}

void ViewerApp::updatePick() {
    state_.pick.reset();
    const ImGuiIO& io = ImGui::GetIO();
    if (imgui_->wantsMouse() || !ImGui::IsMousePosValid()) return;
    // Window units -> framebuffer pixels (HiDPI) -> the view's pixels.
    const glm::ivec2 fb = framebufferSize();
    const double x = io.MousePos.x * fb.x / io.DisplaySize.x,
                 y = io.MousePos.y * fb.y / io.DisplaySize.y;
    const ViewRect rect = viewRect();
    const int column = static_cast<int>(std::floor((x - rect.x) / rect.scale));
    const int row = static_cast<int>(std::floor((y - rect.y) / rect.scale));
    // An animated relief's heights are the field's, a paged map's pyramid is not on the CPU:
    // both are picked from the picture's positions.
    state_.pick = animated_ || renderer_->paged() ? pickFromPicture(column, row)
                                                  : picker_.pick(cameraFrame(), column, row);
}

std::optional<WorldHit> ViewerApp::pickFromPicture(int column, int row) const {
    if (!target_ || column < 0 || row < 0 || column >= target_->width() || row >= target_->height())
        return std::nullopt;
    const glm::vec4 hit = target_->positionAt(column, row);
    if (hit.w < 0.5f) return std::nullopt;
    const RenderJob& job = state_.scene.job;
    const auto surface = BaseSurface::make(job.base, map_->width, map_->height, job.heightScale,
                                           renderer_->maxHeight());
    // The picture's positions are relative to the eye it was drawn from (ReliefRenderer::draw).
    const glm::dvec3 world = drawnEye_ + glm::dvec3(hit);
    const glm::dvec3 object = job.model.pointToObject(world);
    const glm::dvec3 p = surface->mapPoint(object / job.base.frameScale());
    WorldHit pick;
    pick.uv = glm::dvec2(p.x / map_->width, p.y / map_->height);
    pick.height = p.z;
    pick.position = world;
    return pick;
}

void ViewerApp::sculpt() {
    const bool painting = state_.sculpt && sculptable() && !imgui_->wantsMouse() &&
                          ImGui::IsMouseDown(ImGuiMouseButton_Left) && !ImGui::GetIO().KeyAlt &&
                          !ImGui::GetIO().KeyShift;
    if (!painting) {
        if (sculptTool_->strokeActive()) endStroke();
        return;
    }
    if (!state_.pick || state_.pick->face != HitFace::Top) return;  // not over the surface
    dabAt(state_.pick->uv * glm::dvec2(map_->width, map_->height), ImGui::GetIO().KeyCtrl);
}

void ViewerApp::dabAt(const glm::dvec2& mapPoint, bool invert) {
    try {
        mapEdited(sculptTool_->dab(*renderer_, *map_, state_.scene.job, mapPoint, state_.brush,
                                   invert));
    } catch (const Error& e) {
        note(std::string("brush: ") + shown(e));
    }
}

void ViewerApp::endStroke() {
    const bool counted = sculptTool_->endStroke();
    state_.undoSteps = sculptTool_->undoSteps();
    if (options_.verbose && counted)
        note("stroke drawn: " + std::to_string(state_.undoSteps) + " to undo");
}

void ViewerApp::mapEdited(const std::vector<TexelRect>& changed) {
    if (changed.empty()) return;
    copyChangedSamples(window_->gl(), *renderer_->textures(), changed, *map_);
    picker_.mapChanged(map_, changed);
    mapMaxHeight_ = renderer_->maxHeight();
    state_.undoSteps = sculptTool_->undoSteps();
    discardAsked_ = false;
    // Edited: not the state last saved or opened (undone back to it, it is that state).
    state_.mapEdited = sculptTool_->edited();
    quitWarned_ = false;
    ++mapGeneration_;
}

void ViewerApp::undo() {
    if (sculptTool_->strokeActive()) endStroke();
    const std::vector<TexelRect> changed = sculptTool_->undo(*renderer_);
    if (changed.empty()) return;
    mapEdited(changed);
    note("undone: " + std::to_string(state_.undoSteps) + " stroke(s) left to undo");
}

void ViewerApp::saveMap(const std::filesystem::path& file) {
    const bool automated = options_.saveMap.has_value() && file == *options_.saveMap;
    try {
        // Never over a file the view is drawn from (the map, its albedo).
        checkOutputsAreNotInputs({{file, ""}}, filesRead(state_.scene.job));
        // An animated relief's heights are the field's, read back; a sculpted map's are its
        // mirror, kept equal to the GPU's samples dab by dab.
        const HeightMap map = animated_ ? renderer_->textures()->readSamples(window_->gl()) : *map_;
        // A DEM's map saved as .png or .exr: said, in one line, that its ground is not kept.
        if (const std::string dropped = saveHeightMap(map, file, ground_); !dropped.empty()) {
            if (automated)
                logWarning(dropped);
            else
                note(dropped);
        }
    } catch (const Error& e) {
        if (automated) throw;
        note(std::string("map not saved: ") + shown(e));
        return;
    }
    state_.mapEdited = false;
    sculptTool_->saved();
    note("saved the map to " + file.string());
}

void ViewerApp::runScript() {
    for (const ScriptedStroke& stroke : options_.strokes) {
        const Brush saved = state_.brush;
        state_.brush.mode = stroke.mode;
        for (const glm::dvec2& point :
             scriptedDabs(stroke, glm::dvec2(map_->width, map_->height), state_.brush.radius))
            dabAt(point, false);
        state_.brush = saved;
        endStroke();
    }
    for (int k = 0; k < options_.undo; ++k) undo();
}

void ViewerApp::animate(double seconds) {
    RenderJob& job = state_.scene.job;
    // A script (--frames) steps 1/30 s a frame from --time, so its last frame is known; a
    // person sees the time pass.
    if (state_.playing && animatedFrames_ > 0)
        job.time += options_.frames > 0 ? 1.0 / 30.0 : std::min(seconds, 0.25);
    ++animatedFrames_;
    evaluateAnimation();
}

void ViewerApp::evaluateAnimation() {
    animated_->evaluate(*renderer_, state_.scene.job.time);
    mapMaxHeight_ = renderer_->maxHeight();
    ++mapGeneration_;
}

void ViewerApp::drawFootprint() {
    if (!state_.sculpt || !sculptable() || !state_.pick || state_.pick->face != HitFace::Top)
        return;
    const glm::dvec2 centre = state_.pick->uv * glm::dvec2(map_->width, map_->height);
    const CameraFrame camera = cameraFrame();
    target_->bind();
    window_->gl().Viewport(0, 0, target_->width(), target_->height());
    sculptTool_->drawFootprint(*map_, state_.scene.job, centre, state_.brush, camera);
}

void ViewerApp::renderView() {
    const glm::ivec2 size = viewSize();
    if (!target_ || target_->width() != size.x || target_->height() != size.y) {
        target_.reset();  // free the old attachments before making new ones
        target_ = std::make_unique<OffscreenTarget>(window_->gl(), size.x, size.y);
        rendered_.reset();
    }
    const RenderKey key = renderKey();
    // Sculpting re-traces every frame: the footprint follows the cursor over a fresh picture.
    if (rendered_ == key && !state_.continuous && !state_.sculpt) return;
    target_->clear(state_.scene.job.background);
    const double start = now();
    timer_->begin();
    {
        const gl::SrgbWrites srgb(window_->gl());  // the relief's linear colour, encoded
        const CameraFrame frame = cameraFrame();
        renderer_->draw(frame, state_.scene.job.shading);
        drawnEye_ = frame.eye;  // the picture's positions are relative to it
    }
    timer_->end();
    drawFootprint();
    // The wall-clock time to glFinish as well: software rasterisers (llvmpipe) answer
    // timer queries without timing the rasterisation, and read about 0 there.
    window_->gl().Finish();
    state_.wallMilliseconds = (now() - start) * 1e3;
    rendered_ = key;
    statisticsStale_ = true;
    framesToDraw_ = std::max(framesToDraw_, 2);  // the timer's result comes a frame or two later
    loadWantedPages();
}

void ViewerApp::loadWantedPages() {
    PagedPyramid* pager = renderer_->pager();
    if (!pager) {
        pages_.noPages();
        state_.paging.clear();
        return;
    }
    RenderKey view = renderKey();
    view.pageGeneration = 0;
    const bool anotherView = refinedView_ != view;
    refinedView_ = view;
    const auto load = [pager](const std::vector<int>& pages, const std::vector<int>& keep) {
        return pager->loadWhatFitsKeepingRead(pages, keep);
    };
    if (pages_.afterDraw(anotherView, pager->takeWanted(), load)) {
        note("this view reads more pages at once than --memory holds (" +
             std::to_string(pager->capacity()) + " pages of " + std::to_string(pager->pageSide()) +
             "^2 texels): parts of it stay drawn from coarser bounds; raise --memory");
    }
    state_.paging = "pages " + std::to_string(pager->residentCount()) + " of " +
                    std::to_string(pager->capacity()) + " resident, " +
                    std::to_string(pager->pagesLoaded()) + " loaded: " + pages_.progress();
}

void ViewerApp::sampleStatistics() {
    timer_->poll();
    state_.gpuMilliseconds = timer_->lastMilliseconds();
    const double time = now();
    if (!statisticsStale_ || time - lastStatisticsTime_ < kStatisticsInterval) return;
    state_.iterations = readIterationStats(window_->gl(), *target_);
    statisticsStale_ = false;
    lastStatisticsTime_ = time;
}

void ViewerApp::present(bool captureWindow) {
    const GL& gl = window_->gl();
    const glm::ivec2 fb = framebufferSize(), size = viewSize();
    const ViewRect rect = viewRect();
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl.Viewport(0, 0, fb.x, fb.y);
    gl.ClearColor(0.05f, 0.05f, 0.06f, 1.0f);  // the margins around a letterboxed view
    gl.Clear(GL_COLOR_BUFFER_BIT);

    // The view's picture as it is: no panel, no rescaling unless the window's size
    // differs from the view's (a fixed --size with --screenshot).
    target_->bind();
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
    const int x0 = static_cast<int>(std::lround(rect.x)),
              x1 = static_cast<int>(std::lround(rect.x + size.x * rect.scale));
    const int y1 = fb.y - static_cast<int>(std::lround(rect.y));  // GL rows count from the bottom
    const int y0 = fb.y - static_cast<int>(std::lround(rect.y + size.y * rect.scale));
    gl.BlitFramebuffer(0, 0, size.x, size.y, x0, y0, x1, y1, GL_COLOR_BUFFER_BIT,
                       rect.scale == 1.0 ? GL_NEAREST : GL_LINEAR);
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl.Viewport(0, 0, fb.x, fb.y);

    imgui_->render();
    if (captureWindow) windowPixels_ = windowPicture(gl, fb);
    glfwSwapBuffers(window_->window());
}

void ViewerApp::applyRelief(const std::shared_ptr<HeightMap>& heights, const std::string& source) {
    const ReliefDesc& wanted = state_.scene.job;
    // Another map (one opened, or one read again) or another pyramid: built of its heights.
    const bool newHeights = heights != map_ || renderer_->needsHeights(wanted);
    // Shared, not copied, where the renderer reads the map through pages: a paged map is
    // neither sculpted nor animated (refused), so nothing writes to it while they read it.
    if (newHeights)
        renderer_->apply(wanted, std::shared_ptr<const HeightMap>(heights), source,
                         PyramidBuild::Gpu);
    else
        renderer_->apply(wanted);  // the pyramid kept
    picker_.apply(wanted, heights);
    applied_ = wanted;
    ++mapGeneration_;
    state_.pagedMap = renderer_->paged();
    if (state_.pagedMap) state_.sculpt = false;
}

void ViewerApp::openMap(const std::optional<std::filesystem::path>& file) {
    // The scene over the map asked for: that file, or none for the bundled map.
    ReliefDesc asked = state_.scene.job;
    asked.map.file = file;
    const std::filesystem::path path = heightMapPath(asked);
    std::string fitted;
    const RenderJob before = state_.scene.job;
    const bool georeferencedBefore = georeferenced_;
    try {
        // Opening another map (or this one with other options) drops the edits: asked
        // twice, as quitting is.
        if (state_.mapEdited && options_.frames == 0 && !discardAsked_) {
            discardAsked_ = true;
            throwBadInput(
                "the map has edits not saved (Ctrl+S or Save map writes them); open "
                "again to drop them");
        }
        ReliefFiles loaded = loadReliefFiles(asked, ReliefParts::Heights);
        fitted = fitRelief(loaded, path.string());
        std::shared_ptr<HeightMap> map = loaded.takeHeights();
        // An animated field replaces the samples on the GPU, which a paged map does not
        // hold whole (as at start: refused).
        GLint maxTexture = 0;
        window_->gl().GetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTexture);
        if (animated_ && (map->width > maxTexture || map->height > maxTexture)) {
            throwBadInput(path.string() + ": larger than the GL's textures (" +
                          std::to_string(maxTexture) +
                          "), so read through pages, which an animated relief is not");
        }
        state_.scene.job.map.file =
            file ? std::optional(std::filesystem::absolute(*file)) : std::nullopt;
        applyRelief(map, path.string());
        map_ = std::move(map);
        ground_ = mapGround(loaded);
        mapMaxHeight_ = map_->maxValue();
    } catch (const Error& e) {
        // The current map stays, and so do the file and options it was loaded with, and
        // the proportions it set.
        state_.scene.job = before;
        georeferenced_ = georeferencedBefore;
        state_.scene.job.map = applied_->map;
        state_.scene.job.map.load = loadedWith_;
        state_.mapError = shown(e);
        note(std::string("cannot open: ") + shown(e));
        return;
    }
    sculptTool_->clear();
    state_.undoSteps = 0;
    state_.mapEdited = false;
    state_.savePath = editedMapPath(path, ground_.has_value());
    if (animated_) {
        animated_->forgetMap();
        evaluateAnimation();
    }
    loadedWith_ = state_.scene.job.map.load;
    state_.mapName = path.filename().string();
    state_.mapWidth = map_->width;
    state_.mapHeight = map_->height;
    state_.mapError.clear();
    state_.iterationBudget = renderer_->maxIterations();
    applyAlbedo();  // the bundled map's colours come and go with it
    ++mapGeneration_;
    glfwSetWindowTitle(window_->window(), ("microrelief-viewer: " + state_.mapName).c_str());
    note("opened " + path.string() + " (" + std::to_string(map_->width) + "x" +
         std::to_string(map_->height) + ")");
    if (!fitted.empty()) note(fitted);
}

void ViewerApp::applyAlbedo() {
    try {
        const ReliefFiles colours = loadReliefFiles(state_.scene.job, ReliefParts::Albedo);
        if (colours.albedo)
            renderer_->setAlbedo(&*colours.albedo, colours.albedoFile->string());
        else
            renderer_->setAlbedo(nullptr);
        state_.albedoName = colours.albedoFile ? colours.albedoFile->filename().string() : "";
    } catch (const Error& e) {
        // The colours go; the relief stays.
        renderer_->setAlbedo(nullptr);
        state_.albedoName.clear();
        note(std::string("cannot open the albedo: ") + shown(e));
    }
    ++mapGeneration_;
}

void ViewerApp::reloadShaders() {
    try {
        renderer_->reloadShaders();
    } catch (const Error& e) {
        // ReliefRenderer keeps the previous program running; the message names file:line.
        state_.shaderError = shown(e);
        note(std::string("shader error, previous program kept: ") + shown(e));
        return;
    }
    state_.shaderError.clear();
    ++shaderGeneration_;
    note("shaders reloaded from " + watcher_->folder().string());
}

void ViewerApp::setMethod() {
    MethodSettings& method = state_.scene.job.method;
    // What microrelief-render derives from --steps, so "copy as command" reproduces it.
    method.setSteps(method.steps);
    try {
        renderer_->setMethod(method);
    } catch (const Error& e) {
        method = renderer_->method();  // the renderer keeps the method that compiles
        state_.shaderError = shown(e);
        note(std::string("shader error, previous method kept: ") + shown(e));
    }
}

bool ViewerApp::changeRelief(const std::string& what) {
    try {
        applyRelief(map_, state_.mapName);
        return true;
    } catch (const Error& e) {
        // The renderer keeps the relief that works; so does the panel.
        ReliefDesc& relief = state_.scene.job;
        relief.base = applied_->base;
        relief.interpolation = applied_->interpolation;
        relief.tiles = applied_->tiles;
        relief.heightScale = applied_->heightScale;
        note(what + " not changed: " + shown(e));
        return false;
    }
}

void ViewerApp::setInterpolation() {
    // Another surface between the samples (another finest level) or other tiles (another
    // addressing): a new pyramid.
    if (changeRelief("last level or tiles"))
        note(std::string("last level: ") + interpolationName(state_.scene.job.interpolation));
}

void ViewerApp::setBase(bool frame) {
    // Between the plane and a curved base the pyramid is built anew (u wraps).
    if (!changeRelief("base surface") || !frame) return;
    const BaseShape& base = state_.scene.job.base;
    // The new object fills the view from where the camera looks now: the target at the
    // middle of its box, the eye back along the view until the box's sphere fits.
    const ReliefExtent extent =
        reliefExtent(map_->width, map_->height, mapMaxHeight_, state_.scene.job.heightScale, base);
    const glm::dvec3 centre = 0.5 * (extent.min + extent.max);
    const double radius = 0.5 * glm::length(extent.max - extent.min);
    controller_.frame(centre, radius);
}

void ViewerApp::takeScreenshot() {
    const std::filesystem::path file = screenshotPath("out", localTimestamp());
    try {
        writeImageAtomically(file, viewPicture(*target_, drawnEye_).image());
        note("wrote " + file.string());
    } catch (const Error& e) {
        note(std::string("screenshot failed: ") + shown(e));
    }
}

std::string ViewerApp::renderCommand() const {
    SceneOptions scene = state_.scene;
    scene.job.camera = controller_.camera();
    const glm::ivec2 size = viewSize();
    scene.job.width = size.x;
    scene.job.height = size.y;
    return renderCommandLine(scene);
}

void ViewerApp::copyCommand() {
    const std::string command = renderCommand();
    glfwSetClipboardString(window_->window(), command.c_str());
    note("copied: " + command);
}

void ViewerApp::setVsync(bool on) {
    state_.vsync = on;
    glfwSwapInterval(on ? 1 : 0);
}

void ViewerApp::note(const std::string& message) {
    std::printf("microrelief-viewer: %s\n", message.c_str());
    std::fflush(stdout);
    state_.log.push_back(message);
    while (state_.log.size() > kLogLines) state_.log.pop_front();
}

glm::ivec2 ViewerApp::framebufferSize() const {
    glm::ivec2 size(0);
    glfwGetFramebufferSize(window_->window(), &size.x, &size.y);
    return size;
}

glm::ivec2 ViewerApp::viewSize() const {
    // An automated screenshot renders at exactly --size, to compare with microrelief-render;
    // otherwise the view fills the window, one ray per framebuffer pixel.
    if (options_.screenshot) return {options_.scene.job.width, options_.scene.job.height};
    // A fraction of the framebuffer's resolution keeps a software rasteriser interactive.
    const glm::dvec2 scaled =
        glm::dvec2(framebufferSize()) * static_cast<double>(state_.resolution);
    return glm::max(glm::ivec2(glm::round(scaled)), glm::ivec2(1));
}

ViewerApp::ViewRect ViewerApp::viewRect() const {
    const glm::ivec2 fb = framebufferSize(), size = viewSize();
    if (fb == size) return {0.0, 0.0, 1.0};
    const double scale =
        std::min(static_cast<double>(fb.x) / size.x, static_cast<double>(fb.y) / size.y);
    return {(fb.x - size.x * scale) * 0.5, (fb.y - size.y * scale) * 0.5, scale};
}

CameraFrame ViewerApp::cameraFrame() const {
    // Against the relief the renderer holds, which every panel change applies at once (or
    // puts back in the panel): the clip range microrelief-render resolves for the same scene.
    const glm::ivec2 size = viewSize();
    return renderer_->resolveCamera(controller_.camera(), size.x, size.y);
}

ViewerApp::RenderKey ViewerApp::renderKey() const {
    RenderKey key{state_.scene.job, state_.scene.job, mapGeneration_, shaderGeneration_,
                  pages_.generation()};
    key.view.camera = controller_.camera();
    const glm::ivec2 size = viewSize();
    key.view.width = size.x;
    key.view.height = size.y;
    key.view.method = renderer_->method();
    // Shadows take the exact methods: under a peer they change nothing drawn.
    if (!methodTracesTheSolid(key.view.method.method)) key.view.shading.shadows = ShadowMode::Off;
    return key;
}

}  // namespace microrelief
