#include "ViewerPanel.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cmath>

#include "microrelief/core/base/BaseType.h"
#include "microrelief/gl/ReliefRenderer.h"

namespace microrelief {

const ControlHelp kControls[] = {
    {"Left drag", "Orbit about the target (fly mode: look around; sculpt mode: paint)"},
    {"B", "Sculpt mode on/off: the left button paints with the brush (panel: Sculpt)"},
    {"Alt+left drag", "Sculpt mode: orbit"},
    {"Ctrl+left drag", "Sculpt mode: raise lowers and lower raises"},
    {"[ and ]", "Sculpt mode: a smaller or larger brush"},
    {"Ctrl+Z", "Undo the last stroke"},
    {"Ctrl+S", "Save the edited map (panel: Sculpt)"},
    {"Space", flagName("animation") + ": play or pause the animation"},
    {"Right or middle drag, Shift+left drag", "Pan"},
    {"Scroll", "Zoom; close in, the target moves along (into the box)"},
    {"Double-click", "Orbit about the point under the cursor"},
    {"F", "Fly mode on/off"},
    {"W A S D, Q E", "Fly: forward, left, back, right, down, up (Shift faster, Ctrl slower)"},
    {"R", "Reset the view to the command line's"},
    {"1 ... 6", "Shaded, iterations, level, normal, depth, position"},
    {"F12 or P", "Screenshot of the 3D view (no panel) to out/"},
    {"C", "Copy as command: the microrelief-render command line of this view"},
    {"V", "Vsync on/off"},
    {"Tab", "Show or hide the panel"},
    {"Drop a file", "Open it as the height map"},
    {"Esc", "Quit"},
};
const int kControlCount = static_cast<int>(sizeof(kControls) / sizeof(kControls[0]));

namespace {

const ImVec4 kErrorColor(1.0f, 0.45f, 0.4f, 1.0f);

// The base surface the map is laid over, and its sizes, as the table of bases lists them
// (core/base/BaseType.h). A base picked from the list starts at its example sizes.
void baseControls(BaseShape& base, PanelActions& actions) {
    const std::vector<BaseType>& types = baseTypes();
    std::vector<const char*> names;
    for (const BaseType& type : types) names.push_back(type.name);
    const BaseType& current = baseType(base);
    int index = static_cast<int>(&current - types.data());
    if (ImGui::Combo("Base surface", &index, names.data(), static_cast<int>(names.size()))) {
        base = types[static_cast<std::size_t>(index)].example;
        actions.baseKindChanged = actions.baseChanged = true;
        return;
    }
    for (const BaseSize& size : current.sizes) {
        double numbers[3] = {};
        size.read(base, numbers);
        bool changed = false;
        for (int i = 0; i < size.count; ++i) {
            const std::string label =
                size.label + std::string(size.count == 3 ? std::string(" ") + "xyz"[i] : "");
            float v = static_cast<float>(numbers[i]);
            if (ImGui::SliderFloat(label.c_str(), &v, 0.05f, 2.0f, "%.3f",
                                   ImGuiSliderFlags_Logarithmic)) {
                numbers[i] = std::max(v, 0.01f);
                changed = true;
            }
        }
        if (changed) {
            size.write(base, numbers);
            actions.baseChanged = true;
        }
    }
}

void mapSection(ViewerState& s, PanelActions& actions) {
    if (!ImGui::CollapsingHeader("Height map", ImGuiTreeNodeFlags_DefaultOpen)) return;
    ImGui::TextWrapped("%s", s.mapName.c_str());
    ImGui::Text("%d x %d samples", s.mapWidth, s.mapHeight);
    if (!s.paging.empty()) ImGui::TextWrapped("read through pages: %s", s.paging.c_str());
    const ImGuiStyle& style = ImGui::GetStyle();
    ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x - ImGui::CalcTextSize("Open").x -
                            2.0f * style.FramePadding.x - style.ItemSpacing.x);
    const bool entered =
        ImGui::InputTextWithHint("##path", "path, or drop a file on the window", &s.typedPath,
                                 ImGuiInputTextFlags_EnterReturnsTrue);
    ImGui::SameLine();
    if ((ImGui::Button("Open") || entered) && !s.typedPath.empty()) actions.openMap = s.typedPath;
    // Under the field it is about, not over the panel: the field stays where it was clicked.
    if (!s.mapError.empty()) {
        ImGui::PushTextWrapPos(0.0f);
        ImGui::TextColored(kErrorColor, "Cannot open the map (the current one stays): %s",
                           s.mapError.c_str());
        ImGui::PopTextWrapPos();
    }
    if (ImGui::InputInt("Channel", &s.scene.job.map.load.channel)) {
        s.scene.job.map.load.channel = std::max(s.scene.job.map.load.channel, 0);
        actions.reloadMap = true;
    }
    if (ImGui::Checkbox("Normalise to [0, 1]", &s.scene.job.map.load.normalize))
        actions.reloadMap = true;
    if (ImGui::SliderFloat("Height scale", &s.scene.job.heightScale, 0.001f, 1.0f, "%.4f",
                           ImGuiSliderFlags_Logarithmic)) {
        s.scene.job.heightScale = std::max(s.scene.job.heightScale, 1e-4f);
        actions.heightScaleChanged = true;
    }
    AlbedoSource& albedo = s.scene.job.albedo;
    const AlbedoSource::Kind on =
        albedo.file.empty() ? AlbedoSource::Kind::Default : AlbedoSource::Kind::File;
    // Whether there are colours to turn on: a file, or the bundled map's with the bundled
    // map. Where there are none the box is off and greyed (the choice stays, and comes
    // back with the bundled map).
    const bool offered = albedoOffered(s.scene.job);
    bool colours = offered && albedo.kind != AlbedoSource::Kind::None;
    ImGui::BeginDisabled(!offered);
    if (ImGui::Checkbox("Colours (albedo)", &colours)) {
        // Off keeps the file, so that on brings it back.
        albedo.kind = colours ? on : AlbedoSource::Kind::None;
        actions.albedoChanged = true;
    }
    ImGui::EndDisabled();
    if (!offered && ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
        ImGui::SetTooltip("%s", ("No colours to show: the bundled map's go with its stones (not "
                                 "with another map, nor a field that replaces them); " +
                                 flagName("albedo") + " FILE gives a map its own")
                                    .c_str());
    if (!s.albedoName.empty()) {
        ImGui::SameLine();
        ImGui::TextDisabled("%s", s.albedoName.c_str());
    }
    baseControls(s.scene.job.base, actions);
    int interpolation = s.scene.job.interpolation == Interpolation::Biquadratic ? 1 : 0;
    const char* const interpolations[] = {"bilinear", "biquadratic (smooth)"};
    if (ImGui::Combo("Last level", &interpolation, interpolations, IM_ARRAYSIZE(interpolations))) {
        s.scene.job.interpolation =
            interpolation == 1 ? Interpolation::Biquadratic : Interpolation::Bilinear;
        actions.interpolationChanged = true;
    }
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip(
            "The surface between the samples: bilinear patches (a facet per texel),\n"
            "or the quadratic B-spline of the samples (smooth normals)");
    int tiles[2] = {s.scene.job.tiles.x, s.scene.job.tiles.y};
    if (ImGui::InputInt2("Tiles", tiles, ImGuiInputTextFlags_EnterReturnsTrue)) {
        s.scene.job.tiles = glm::clamp(glm::ivec2(tiles[0], tiles[1]), 1, kMaxTiles);
        actions.interpolationChanged = true;  // a new pyramid, as for another last level
    }
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("The map repeated N x M times (Enter to apply)");
}

// The light as azimuth and elevation, written back only when the user moves a slider,
// so a --light given on the command line stays exactly as given until then.
void lightControls(ShadingOptions& shading) {
    const glm::vec3 l = glm::normalize(shading.lightDirection);
    float azimuth = glm::degrees(std::atan2(l.z, l.x));
    float elevation = glm::degrees(std::asin(std::clamp(l.y, -1.0f, 1.0f)));
    // Both sliders drawn every frame, whichever moved.
    const bool azimuthMoved =
        ImGui::SliderFloat("Light azimuth", &azimuth, -180.0f, 180.0f, "%.0f deg");
    const bool elevationMoved =
        ImGui::SliderFloat("Light elevation", &elevation, -90.0f, 90.0f, "%.0f deg");
    if (azimuthMoved || elevationMoved) {
        const float a = glm::radians(azimuth), e = glm::radians(elevation);
        shading.lightDirection = {std::cos(e) * std::cos(a), std::sin(e),
                                  std::cos(e) * std::sin(a)};
        shading.lightPosition.reset();  // the sliders move a directional light
    }
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Or hold L and drag in the view");
    int shadows = static_cast<int>(shading.shadows);
    const char* const modes[] = {"off", "hard (exact)", "soft (estimate)"};
    if (ImGui::Combo("Shadows", &shadows, modes, IM_ARRAYSIZE(modes)))
        shading.shadows = static_cast<ShadowMode>(shadows);
    if (shading.shadows == ShadowMode::Soft) {
        ImGui::SliderFloat("Light size", &shading.lightSizeDegrees, 0.05f, 20.0f, "%.2f deg",
                           ImGuiSliderFlags_Logarithmic);
        shading.lightSizeDegrees = std::clamp(shading.lightSizeDegrees, 0.01f, 89.0f);
    }
}

// The tracer: the paper's multilevel method, or a peer to compare it with.
void methodControls(MethodSettings& method, PanelActions& actions) {
    int index = static_cast<int>(method.method);
    const char* names[] = {"multilevel (the paper's, exact)",
                           "normal mapping",
                           "parallax offset",
                           "steep parallax",
                           "parallax occlusion",
                           "relief mapping",
                           "maximum mipmaps",
                           "cone step mapping (exact)",
                           "relaxed cone stepping"};
    if (ImGui::Combo("Method", &index, names, IM_ARRAYSIZE(names))) {
        method.method = static_cast<Method>(index);
        actions.methodChanged = true;
    }
    if (methodHasSteps(method.method) &&
        ImGui::SliderInt("Steps", &method.steps, 1, 512, "%d", ImGuiSliderFlags_Logarithmic)) {
        method.steps = std::clamp(method.steps, 1, 65536);
        actions.methodChanged = true;
    }
    if (method.method == Method::Multilevel &&
        ImGui::SliderFloat("Pixel error", &method.pixelError, 0.0f, 8.0f, "%.2f px")) {
        method.pixelError = std::max(method.pixelError, 0.0f);
        actions.methodChanged = true;
    }
}

void viewSection(ViewerState& s, PanelActions& actions) {
    if (!ImGui::CollapsingHeader("View", ImGuiTreeNodeFlags_DefaultOpen)) return;
    methodControls(s.scene.job.method, actions);
    int view = static_cast<int>(s.scene.job.shading.view);
    const char* names[] = {
        "shaded", "iterations (heat map)", "level where the ray stopped", "normal",
        "depth",  "position (AOV)"};
    if (ImGui::Combo("Show", &view, names, IM_ARRAYSIZE(names)))
        s.scene.job.shading.view = static_cast<DebugView>(view);
    lightControls(s.scene.job.shading);
    ImGui::ColorEdit3("Background", &s.scene.job.background.x, ImGuiColorEditFlags_Float);
    float fovy = static_cast<float>(s.scene.job.camera.fovyDegrees);
    if (ImGui::SliderFloat("Field of view", &fovy, 5.0f, 120.0f, "%.1f deg")) {
        s.scene.job.camera.fovyDegrees = fovy;
        actions.fovyChanged = true;
    }
    ImGui::Checkbox("Fly mode (F)", &s.flyMode);
    ImGui::SameLine();
    if (ImGui::Button("Reset view (R)")) actions.resetView = true;
    const Camera& c = s.scene.job.camera;
    ImGui::Text("eye    %+.3f %+.3f %+.3f", c.eye.x, c.eye.y, c.eye.z);
    ImGui::Text("target %+.3f %+.3f %+.3f", c.target.x, c.target.y, c.target.z);
    ImGui::Text("yaw %.1f deg, pitch %.1f deg", s.yawDegrees, s.pitchDegrees);
}

void statsSection(ViewerState& s) {
    if (!ImGui::CollapsingHeader("Method", ImGuiTreeNodeFlags_DefaultOpen)) return;
    if (s.gpuMilliseconds) {
        ImGui::Text("relief pass %.2f ms (GL timer query)", *s.gpuMilliseconds);
        // llvmpipe answers timer queries without timing its rasteriser threads.
        if (*s.gpuMilliseconds < 0.1 * s.wallMilliseconds) {
            ImGui::SameLine();
            ImGui::TextDisabled("(?)");
            if (ImGui::IsItemHovered())
                ImGui::SetTooltip(
                    "This driver's timer misses the rasterisation; see the wall time");
        }
    } else {
        ImGui::TextDisabled("relief pass: waiting for the timer query");
    }
    ImGui::Text("relief pass %.1f ms to glFinish, frame %.1f ms", s.wallMilliseconds,
                s.frameMilliseconds);
    ImGui::Text("iterations per hit pixel: mean %.1f, max %d", s.iterations.meanPerHitPixel,
                s.iterations.maxIterations);
    ImGui::Text("budget %d; %d x %d pixels, %zu hit", s.iterationBudget, s.scene.job.width,
                s.scene.job.height, s.iterations.hitPixels);
    ImGui::Checkbox("Render every frame", &s.continuous);
    ImGui::SameLine();
    const float resolutions[] = {1.0f, 0.5f, 0.25f};
    const char* resolutionNames[] = {"full", "1/2", "1/4"};
    int resolution =
        static_cast<int>(std::find(resolutions, resolutions + 3, s.resolution) - resolutions);
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 4.0f);
    if (ImGui::Combo("Resolution", &resolution, resolutionNames, 3))
        s.resolution = resolutions[resolution];
    if (s.pick) {
        ImGui::Text("cursor: uv %.4f %.4f, h %.4f", s.pick->uv.x, s.pick->uv.y, s.pick->height);
    } else {
        ImGui::TextDisabled("cursor: no relief under it");
    }
}

// The brush and the edited map: the modes, radius and strength, undo and saving.
void sculptSection(ViewerState& s, PanelActions& actions) {
    if (!s.scene.job.animation.empty()) return;  // the field overwrites the samples
    if (!ImGui::CollapsingHeader("Sculpt", ImGuiTreeNodeFlags_DefaultOpen)) return;
    // The brush paints one map; a tiled map's pyramid is rebuilt whole after each edit; a
    // paged map's samples are not on the GPU whole.
    const bool tiled = s.scene.job.tiles != glm::ivec2(1, 1);
    if (tiled || s.pagedMap) s.sculpt = false;
    ImGui::BeginDisabled(tiled || s.pagedMap);
    ImGui::Checkbox("Sculpt with the left button (B)", &s.sculpt);
    ImGui::EndDisabled();
    if (tiled || s.pagedMap) {
        ImGui::SameLine();
        ImGui::TextDisabled(s.pagedMap ? "(not a map read through pages)"
                                       : "(an untiled map only: Tiles 1, 1)");
    }
    int mode = static_cast<int>(s.brush.mode);
    for (int m = 0; m < 4; ++m) {
        if (m > 0) ImGui::SameLine();
        ImGui::RadioButton(brushModeName(static_cast<BrushMode>(m)), &mode, m);
    }
    s.brush.mode = static_cast<BrushMode>(mode);
    float radius = static_cast<float>(s.brush.radius);
    if (ImGui::SliderFloat("Radius", &radius, 1.0f, 512.0f, "%.1f texels",
                           ImGuiSliderFlags_Logarithmic))
        s.brush.radius = std::max(radius, 0.5f);
    const bool fraction = s.brush.mode == BrushMode::Smooth || s.brush.mode == BrushMode::Flatten;
    if (ImGui::SliderFloat("Strength", &s.brush.strength, fraction ? 0.01f : 0.0005f,
                           fraction ? 1.0f : 0.5f,
                           fraction ? "%.2f of the way a dab" : "%.4f map units a dab",
                           ImGuiSliderFlags_Logarithmic))
        s.brush.strength = std::max(s.brush.strength, 1e-5f);
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip(fraction ? "How far a dab moves a sample at the brush's centre:\n"
                                     "towards its neighbours' mean (smooth) or the height\n"
                                     "under the stroke's first dab (flatten)"
                                   : "How much a dab raises or lowers the map at its centre\n"
                                     "(map units; the falloff is (1 - d^2)^2)");
    ImGui::BeginDisabled(s.undoSteps == 0);
    if (ImGui::Button("Undo (Ctrl+Z)")) actions.undo = true;
    ImGui::EndDisabled();
    ImGui::SameLine();
    ImGui::Text("%d stroke%s to undo", s.undoSteps, s.undoSteps == 1 ? "" : "s");
    ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x * 0.62f);
    ImGui::InputText("##save", &s.savePath);
    ImGui::SameLine();
    if (ImGui::Button("Save map (Ctrl+S)")) actions.saveMap = true;
    ImGui::TextDisabled(s.mapEdited ? "edited, not saved (.png: 16 bits, .exr: float)"
                                    : "as opened or saved");
}

// An animated relief: its time, playing or paused.
void animationSection(ViewerState& s) {
    if (s.scene.job.animation.empty()) return;
    if (!ImGui::CollapsingHeader("Animation", ImGuiTreeNodeFlags_DefaultOpen)) return;
    ImGui::Text("%s, its pyramid rebuilt on the GPU every frame", s.scene.job.animation.c_str());
    ImGui::Checkbox("Play (Space)", &s.playing);
    float time = static_cast<float>(s.scene.job.time);
    if (ImGui::DragFloat("Time", &time, 0.01f, 0.0f, 0.0f, "%.3f s")) s.scene.job.time = time;
}

void actionsSection(ViewerState& s, PanelActions& actions) {
    if (!ImGui::CollapsingHeader("Output", ImGuiTreeNodeFlags_DefaultOpen)) return;
    if (ImGui::Button("Screenshot (F12)")) actions.screenshot = true;
    ImGui::SameLine();
    if (ImGui::Button("Copy as command (C)")) actions.copyCommand = true;
    if (ImGui::Checkbox("Vsync (V)", &s.vsync)) actions.vsyncChanged = true;
    ImGui::TextDisabled("%s", s.glRenderer.c_str());
}

void shaderSection(ViewerState& s, PanelActions& actions) {
    if (!ImGui::CollapsingHeader("Shaders", ImGuiTreeNodeFlags_DefaultOpen)) return;
    ImGui::TextWrapped("watching %s", s.shaderFolder.c_str());
    if (ImGui::Button("Reload now")) actions.reloadShaders = true;
    ImGui::SameLine();
    if (s.shaderError.empty()) {
        ImGui::TextDisabled("compiled");
    } else {
        ImGui::TextColored(kErrorColor, "error, see the top");
    }
}

// Errors first, where they cannot be missed: the panel may scroll.
void errorBanner(const ViewerState& s) {
    ImGui::PushTextWrapPos(0.0f);
    if (!s.shaderError.empty()) {
        ImGui::TextColored(kErrorColor, "Shader error (the previous program keeps running):");
        ImGui::TextColored(kErrorColor, "%s", s.shaderError.c_str());
    }
    ImGui::PopTextWrapPos();
}

void logAndHelp(const ViewerState& s) {
    if (ImGui::CollapsingHeader("Log", ImGuiTreeNodeFlags_DefaultOpen)) {
        ImGui::PushTextWrapPos(0.0f);
        for (const std::string& line : s.log) ImGui::TextUnformatted(line.c_str());
        ImGui::PopTextWrapPos();
    }
    if (ImGui::CollapsingHeader("Controls") &&
        ImGui::BeginTable("controls", 2, ImGuiTableFlags_RowBg)) {
        for (int k = 0; k < kControlCount; ++k) {
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(kControls[k].input);
            ImGui::TableNextColumn();
            ImGui::TextWrapped("%s", kControls[k].action.c_str());
        }
        ImGui::EndTable();
    }
}

void hoverReadout(const ViewerState& s) {
    if (!s.pick || ImGui::GetIO().WantCaptureMouse) return;
    ImGui::BeginTooltip();
    ImGui::Text("uv %.4f, %.4f", s.pick->uv.x, s.pick->uv.y);
    ImGui::Text("h  %.4f", s.pick->height);
    ImGui::EndTooltip();
}

}  // namespace

PanelActions drawPanel(ViewerState& state, float uiScale) {
    PanelActions actions;
    hoverReadout(state);
    if (!state.panelVisible) return actions;
    // Fixed width, as tall as its content up to the window's height (then it scrolls).
    const float margin = 8.0f * uiScale, width = 380.0f * uiScale;
    ImGui::SetNextWindowPos(ImVec2(margin, margin), ImGuiCond_FirstUseEver);
    // In a window not half as wide again as the panel, the panel would hide most of the
    // view: it starts folded to its title bar there (a double-click on the bar or a click
    // on its arrow opens it).
    ImGui::SetNextWindowCollapsed(ImGui::GetIO().DisplaySize.x < 1.5f * width,
                                  ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSizeConstraints(
        ImVec2(width, 0.0f),
        ImVec2(width, std::max(ImGui::GetIO().DisplaySize.y - 2.0f * margin, 50.0f)));
    ImGui::SetNextWindowBgAlpha(0.85f);
    const bool open =
        ImGui::Begin("microrelief", &state.panelVisible, ImGuiWindowFlags_AlwaysAutoResize);
    // A window shrunk to almost nothing (a near-minimise) pushes the panel up and left past
    // its corner, and ImGui leaves it there when the window grows back, its title bar, fold
    // arrow and close box cut off: it is kept at or below and right of the corner.
    const ImVec2 at = ImGui::GetWindowPos();
    if (at.x < 0.0f || at.y < 0.0f)
        ImGui::SetWindowPos(ImVec2(std::max(at.x, 0.0f), std::max(at.y, 0.0f)));
    if (open) {
        errorBanner(state);
        mapSection(state, actions);
        viewSection(state, actions);
        sculptSection(state, actions);
        animationSection(state);
        statsSection(state);
        actionsSection(state, actions);
        shaderSection(state, actions);
        logAndHelp(state);
    }
    ImGui::End();
    return actions;
}

}  // namespace microrelief
