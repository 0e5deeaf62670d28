// The viewer: a GLFW window whose relief is drawn by the library's ReliefRenderer into
// an OffscreenTarget (the same path as microrelief-render, so a view and its headless
// twin agree pixel for pixel), blitted to the window with the Dear ImGui panel on top.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "CameraController.h"
#include "FrameStats.h"
#include "ImGuiLayer.h"
#include "InputBindings.h"
#include "MapFile.h"
#include "microrelief/core/trace/CpuRelief.h"
#include "OutputFiles.h"
#include "PageRefiner.h"
#include "SculptTool.h"
#include "ShaderWatcher.h"
#include "ViewCapture.h"
#include "ViewerOptions.h"
#include "ViewerPanel.h"
#include "microrelief/gl/AnimatedHeights.h"
#include "microrelief/gl/OffscreenTarget.h"
#include "microrelief/gl/ReliefRenderer.h"
#include "microrelief/glfw/GlfwContext.h"
#include "microrelief/io/ReliefFiles.h"

namespace microrelief {

class ViewerApp {
public:
    // Loads the map, opens the window, compiles the shaders. Throws Error: BadInput for
    // a bad map or camera (exit status 2), Runtime for no display or no GL (1).
    explicit ViewerApp(const ViewerOptions& options);
    ~ViewerApp();
    ViewerApp(const ViewerApp&) = delete;
    ViewerApp& operator=(const ViewerApp&) = delete;

    // Runs until the window closes, or for --frames frames; returns the exit status.
    int run();

    // The microrelief-render command line of the current view.
    std::string renderCommand() const;

private:
    // What the relief pass depends on: when none of it changed, the last picture stands.
    // The scene as drawn (the controller's camera, the view's size, the method that
    // compiled) and the generations of what changes under the same scene (edited heights,
    // a colour file opened again, shaders reloaded).
    struct RenderKey {
        ReliefDesc relief;
        ViewDesc view;
        int mapGeneration, shaderGeneration;
        int pageGeneration;  // pages loaded for a map read through pages
        bool operator==(const RenderKey&) const = default;
    };
    // Where the view's picture lies in the window's framebuffer (pixels, top-left origin).
    struct ViewRect {
        double x, y, scale;
    };

    void setupWindow();
    void frame();
    void waitForEvents();
    void handleInput(double seconds);
    // `mods`: the GLFW modifier bits held when the key went down.
    void handleKey(int key, int mods);
    // Esc or the window's close button: quits, unless the map has edits not saved and this
    // is the first ask since them (then it says so, and a second ask quits).
    void askToQuit();
    void flyKeys(double seconds);
    void handleMouse();
    void applyPanel(const PanelActions& actions);
    void updatePick();
    void renderView();
    // A map read through pages, after each draw: the pages it wanted loaded, the view
    // refined over frames (PageRefiner.h); where the pool falls short, a note says to raise
    // --memory.
    void loadWantedPages();
    void sampleStatistics();
    void present(bool captureWindow);
    // --screenshot and --window-screenshot, after the last frame.
    void writeAutomationOutputs();

    // Sculpting (SculptTool.h): a dab at the cursor while the left button paints, the stroke
    // ended when it is let go; the samples a dab or an undo changed read back into the map's
    // CPU mirror (map_), which the picker and the footprint use and "Save map" writes.
    void sculpt();
    // The brush paints an untiled map that is not animated (a tiled map's picks land on
    // the whole, the brush on one tile; an animated one's heights are the field's) nor read
    // through pages (its samples are not on the GPU whole).
    bool sculptable() const {
        return microrelief::sculptable(state_.scene.job) && !(renderer_ && renderer_->paged());
    }
    void dabAt(const glm::dvec2& mapPoint, bool invert);
    void endStroke();
    void mapEdited(const std::vector<TexelRect>& changed);
    void undo();
    void saveMap(const std::filesystem::path& file);
    // --stroke and --undo, before the first frame.
    void runScript();
    void drawFootprint();
    // --animate: the field at the current time, every frame (the first frame drawn at
    // --time, later ones on by the time that passed).
    void animate(double seconds);
    // The field evaluated at the scene's time, the time left as it is.
    void evaluateAnimation();
    // What the picture shows under pixel (column, row): its position AOV, for an animated
    // relief (which the CPU twin does not follow).
    std::optional<WorldHit> pickFromPicture(int column, int row) const;

    // The relief of the scene (state_.scene.job) on the renderer and the picker, over
    // `heights` (the samples its map names, as the viewer holds them; `source` names them):
    // the pyramid built again only for other heights, addressing or tiles (ReliefRenderer::
    // apply, core/scene/Scene.h: samePyramid), else the base, last level, height scale and
    // model set on the one there is. Throws as the renderer does, having changed nothing. The one
    // place the viewer hands a relief over.
    void applyRelief(const std::shared_ptr<HeightMap>& heights, const std::string& source);
    // applyRelief over the viewer's map after the panel changed the relief (`what`: the base,
    // the last level, the tiles, the height scale); on an error the panel's relief goes back
    // to the one the renderer kept, and a note says why. Whether it was applied.
    bool changeRelief(const std::string& what);
    void openMap(const std::optional<std::filesystem::path>& file);
    // The colours the scene asks for (io/ReliefFiles.h), loaded into the renderer, or none.
    void applyAlbedo();
    void reloadShaders();
    void setMethod();
    // The base surface in the panel's state; `frame`: point the view at the new object.
    void setBase(bool frame);
    // The last level in the panel's state: the pyramid built again for it.
    void setInterpolation();
    void takeScreenshot();
    void copyCommand();
    void setVsync(bool on);
    void note(const std::string& message);
    // The relief over a map just loaded (its heights still in `loaded`): a georeferenced
    // map's true proportions where the command line lets (app/shared/SceneOptions.h,
    // sceneOverMap); where the map before it set them, the command line's own values come
    // back first. Returns the line to note.
    std::string fitRelief(const ReliefFiles& loaded, const std::string& source);

    glm::ivec2 framebufferSize() const;
    glm::ivec2 viewSize() const;
    ViewRect viewRect() const;
    CameraFrame cameraFrame() const;
    RenderKey renderKey() const;

    ViewerOptions options_;
    ViewerState state_;
    HeightMapLoadOptions loadedWith_;  // the options the current map was loaded with
    bool georeferenced_ = false;       // the current map set the relief's proportions
    std::optional<ReliefDesc> applied_;  // the relief the renderer and the picker hold
    // The CPU mirror of the samples on the GPU (edited); a map read through pages is read
    // from this very object by the pages, and so never written (sculptable(), refusals).
    std::shared_ptr<HeightMap> map_;
    // Where the current map is a DEM's: what a .tif save keeps (MapFile.h).
    std::optional<MapGround> ground_;
    // The surface's top (map_'s largest sample, the pyramid's top once edited or animated),
    // which a new base is framed by (setBase); the view's camera is resolved by the
    // renderer against its own relief (cameraFrame).
    float mapMaxHeight_ = 0.0f;
    CameraController controller_;
    CpuRelief picker_;  // the relief on the CPU, for picks
    float uiScale_ = 1.0f;
    int mapGeneration_ = 0, shaderGeneration_ = 0;
    std::optional<RenderKey> rendered_;  // what the target holds
    glm::dvec3 drawnEye_{0.0};           // the eye the target was drawn from: its positions' origin
    // Paging (loadWantedPages): the view whose pages are kept (its key at page generation
    // 0), and its refinement.
    std::optional<RenderKey> refinedView_;
    PageRefiner pages_;
    bool statisticsStale_ = true;
    double lastStatisticsTime_ = -1.0, lastFrameTime_ = 0.0;
    int framesToDraw_ = 0;  // frames to draw before waiting for events again
    std::optional<std::filesystem::path> droppedFile_;
    int animatedFrames_ = 0;        // frames since the animation started (scripts: 1/30 s each)
    // Keys pressed since the last frame, with the modifiers held as each went down (read at
    // the frame, Ctrl may be up again: a quick Ctrl+Z within one slow frame).
    struct KeyPress {
        int key, mods;
    };
    std::vector<KeyPress> pressedKeys_;
    bool quitWarned_ = false;    // asked to quit with unsaved edits, told so
    bool discardAsked_ = false;  // asked to open a map over unsaved edits, told so
    RgbPicture windowPixels_;  // --window-screenshot

    // GL owners after the window: they are destroyed first, while its context lives.
    std::unique_ptr<GlfwContext> window_;
    std::unique_ptr<ImGuiLayer> imgui_;
    std::unique_ptr<ReliefRenderer> renderer_;
    std::unique_ptr<OffscreenTarget> target_;
    std::unique_ptr<GpuTimer> timer_;
    std::unique_ptr<ShaderWatcher> watcher_;
    std::unique_ptr<SculptTool> sculptTool_;
    std::unique_ptr<AnimatedHeights> animated_;
};

// Where the viewer reads and watches shaders: --shader-dir, else the source tree's
// shaders/ when it runs from its build tree (so edits there hot-reload), else the
// installed ones.
std::filesystem::path viewerShaderDirectory(const ViewerOptions& options);

}  // namespace microrelief
