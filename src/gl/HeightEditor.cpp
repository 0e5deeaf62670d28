#include "microrelief/gl/HeightEditor.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "microrelief/core/Error.h"
#include "microrelief/gl/ShaderProgram.h"
#include "microrelief/gl/StateGuard.h"
#include "microrelief/gl/ReliefRenderer.h"

namespace microrelief {

namespace {

// The runs of columns [from, to) (unwrapped: any integers on a curved base) as pieces of
// the map's columns: each piece starts at unwrapped column `start`, map column `column`,
// and is `width` wide. One piece on the plane (already clipped to the map).
struct ColumnRun {
    int start, column, width;
};

std::vector<ColumnRun> columnRuns(int from, int to, int mapWidth) {
    std::vector<ColumnRun> runs;
    for (int x = from; x < to;) {
        const int column = ((x % mapWidth) + mapWidth) % mapWidth;
        const int width = std::min(to - x, mapWidth - column);
        runs.push_back({x, column, width});
        x += width;
    }
    return runs;
}

}  // namespace

const char* brushModeName(BrushMode mode) {
    switch (mode) {
        case BrushMode::Lower:
            return "lower";
        case BrushMode::Smooth:
            return "smooth";
        case BrushMode::Flatten:
            return "flatten";
        default:
            return "raise";
    }
}

HeightEditor::HeightEditor(const GL& gl, const std::filesystem::path& shaderDir) : gl_(gl) {
    const std::string version = "330 core";
    const gl::Shader vertex = gl::compileShader(
        gl, GL_VERTEX_SHADER, assembleShader(shaderDir / "pyramid" / "pass.vert", version));
    const gl::Shader fragment = gl::compileShader(
        gl, GL_FRAGMENT_SHADER,
        assembleShader(shaderDir / "edit" / "brush.frag", version, {}, {shaderDir}));
    program_ = gl::linkProgram(gl, vertex, fragment, "height brush");
    const auto at = [&](const char* name) { return gl::uniform(gl, program_, name); };
    sourceOrigin_ = at("sourceOrigin");
    mapSize_ = at("mapSize");
    wrapU_ = at("wrapU");
    shift_ = at("shift");
    centre_ = at("centre");
    radius_ = at("radius");
    strength_ = at("strength");
    mode_ = at("mode");
    level_ = at("level");
    ceiling_ = at("ceiling");
    const gl::StateGuard saved(gl);
    gl.UseProgram(program_.id());
    gl.Uniform1i(at("source"), 0);
    vertexArray_ = gl::VertexArray::create(gl);
    read_ = gl::Framebuffer::create(gl);
    draw_ = gl::Framebuffer::create(gl);
}

void HeightEditor::copyToScratch(GLuint samples, int mapWidth, bool wrapU,
                                 const TexelRect& source) {
    // The scratch texture grows to the largest copy yet (a dab of the same size reuses it).
    const glm::ivec2 size(source.width(), source.height());
    if (!scratch_ || size.x > scratchSize_.x || size.y > scratchSize_.y) {
        scratchSize_ = glm::max(size, scratchSize_);
        scratch_ = gl::Texture::create(gl_);
        gl_.BindTexture(GL_TEXTURE_2D, scratch_.id());
        gl_.TexImage2D(GL_TEXTURE_2D, 0, GL_R32F, scratchSize_.x, scratchSize_.y, 0, GL_RED,
                       GL_FLOAT, nullptr);
        gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
    }
    gl_.BindTexture(GL_TEXTURE_2D, scratch_.id());
    gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, read_.id());
    gl_.FramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, samples, 0);
    gl_.ReadBuffer(GL_COLOR_ATTACHMENT0);
    const std::vector<ColumnRun> runs =
        wrapU ? columnRuns(source.x0, source.x1, mapWidth)
              : std::vector<ColumnRun>{{source.x0, source.x0, source.width()}};
    for (const ColumnRun& run : runs) {
        gl_.CopyTexSubImage2D(GL_TEXTURE_2D, 0, run.start - source.x0, 0, run.column, source.y0,
                              run.width, source.height());
    }
}

std::vector<TexelRect> HeightEditor::dab(ReliefRenderer& renderer, const glm::dvec2& centre,
                                         const Brush& brush) {
    if (!(brush.radius > 0.0) || !std::isfinite(brush.radius) || !(brush.strength > 0.0f) ||
        !std::isfinite(brush.strength) || !std::isfinite(brush.level) || !(brush.ceiling > 0.0f))
        throwBadInput("a brush needs a positive radius and strength and a finite level");
    ReliefTextures* textures = renderer.textures();
    if (!textures || !std::isfinite(centre.x) || !std::isfinite(centre.y)) return {};
    const glm::ivec2 map = textures->shape().size;
    const bool wrapU = textures->wrapsU();

    // The samples whose centres (i + 0.5) lie within the radius, unwrapped; on a curved
    // base no wider than the map, each column taken once at its nearer image.
    TexelRect dab{static_cast<int>(std::floor(centre.x - brush.radius)),
                  static_cast<int>(std::floor(centre.y - brush.radius)),
                  static_cast<int>(std::ceil(centre.x + brush.radius)),
                  static_cast<int>(std::ceil(centre.y + brush.radius))};
    dab.y0 = std::max(dab.y0, 0);
    dab.y1 = std::min(dab.y1, map.y);
    if (wrapU) {
        if (dab.width() > map.x) {
            dab.x0 = static_cast<int>(std::floor(centre.x)) - map.x / 2;
            dab.x1 = dab.x0 + map.x;
        }
    } else {
        dab.x0 = std::max(dab.x0, 0);
        dab.x1 = std::min(dab.x1, map.x);
    }
    if (dab.empty()) return {};
    // The copy: one sample more round the dab for smoothing, rows clamped to the map, and
    // columns too on the plane.
    TexelRect source{dab.x0 - 1, std::max(dab.y0 - 1, 0), dab.x1 + 1, std::min(dab.y1 + 1, map.y)};
    if (!wrapU) {
        source.x0 = std::max(source.x0, 0);
        source.x1 = std::min(source.x1, map.x);
    }

    std::vector<TexelRect> changed;
    {
        const gl::PassGuard saved(gl_);
        gl_.ActiveTexture(GL_TEXTURE0);
        copyToScratch(textures->samples(), map.x, wrapU, source);

        // What undo needs: the samples the dab will draw over, before it.
        if (!strokeOpen_) {
            strokes_.emplace_back();
            strokeOpen_ = true;
        }
        const std::vector<ColumnRun> pieces =
            wrapU ? columnRuns(dab.x0, dab.x1, map.x)
                  : std::vector<ColumnRun>{{dab.x0, dab.x0, dab.width()}};
        gl_.PixelStorei(GL_PACK_ALIGNMENT, 4);
        for (const ColumnRun& piece : pieces) {
            const TexelRect rect{piece.column, dab.y0, piece.column + piece.width, dab.y1};
            Change change{
                rect, std::vector<float>(static_cast<std::size_t>(rect.width()) * rect.height())};
            gl_.ReadPixels(rect.x0, rect.y0, rect.width(), rect.height(), GL_RED, GL_FLOAT,
                           change.before.data());
            strokes_.back().push_back(std::move(change));
            changed.push_back(rect);
        }

        gl_.BindFramebuffer(GL_DRAW_FRAMEBUFFER, draw_.id());
        gl_.FramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D,
                                 textures->samples(), 0);
        gl_.BindVertexArray(vertexArray_.id());
        gl_.UseProgram(program_.id());
        gl_.Uniform2i(sourceOrigin_, source.x0, source.y0);
        gl_.Uniform2i(mapSize_, map.x, map.y);
        gl_.Uniform1i(wrapU_, wrapU ? 1 : 0);
        gl_.Uniform2f(centre_, static_cast<float>(centre.x), static_cast<float>(centre.y));
        gl_.Uniform1f(radius_, static_cast<float>(brush.radius));
        gl_.Uniform1f(strength_, brush.strength);
        gl_.Uniform1i(mode_, static_cast<int>(brush.mode));
        gl_.Uniform1f(level_, brush.level);
        gl_.Uniform1f(ceiling_, brush.ceiling);
        gl_.BindTexture(GL_TEXTURE_2D, scratch_.id());
        for (const ColumnRun& piece : pieces) {
            gl_.Uniform1i(shift_, piece.start - piece.column);
            gl_.Viewport(piece.column, dab.y0, piece.width, dab.height());
            gl_.DrawArrays(GL_TRIANGLES, 0, 3);
        }
        gl_.FramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, 0, 0);
        gl_.FramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, 0, 0);
    }
    trimHistory();
    renderer.heightsChanged(changed);
    return changed;
}

void HeightEditor::endStroke() {
    if (strokeOpen_ && !strokes_.empty() && strokes_.back().empty()) strokes_.pop_back();
    strokeOpen_ = false;
}

std::vector<TexelRect> HeightEditor::undo(ReliefRenderer& renderer) {
    endStroke();
    ReliefTextures* textures = renderer.textures();
    if (strokes_.empty() || !textures) return {};
    std::vector<TexelRect> changed;
    const std::vector<Change>& stroke = strokes_.back();
    for (auto change = stroke.rbegin(); change != stroke.rend(); ++change) {
        textures->writeSamples(gl_, change->rect, change->before.data());
        changed.push_back(change->rect);
    }
    strokes_.pop_back();
    renderer.heightsChanged(changed);
    return changed;
}

int HeightEditor::undoSteps() const {
    return static_cast<int>(strokes_.size());
}

void HeightEditor::clear() {
    strokes_.clear();
    strokeOpen_ = false;
}

void HeightEditor::trimHistory() {
    std::size_t bytes = 0;
    for (const auto& stroke : strokes_)
        for (const Change& change : stroke) bytes += change.before.size() * sizeof(float);
    // The oldest strokes go first; the one being drawn stays, whatever its size.
    while (bytes > kUndoBudgetBytes && strokes_.size() > 1) {
        for (const Change& change : strokes_.front()) bytes -= change.before.size() * sizeof(float);
        strokes_.erase(strokes_.begin());
    }
}

}  // namespace microrelief
