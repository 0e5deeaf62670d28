#include "StrokeHistory.h"

#include <algorithm>
#include <cmath>

namespace microrelief {

void StrokeHistory::startStroke() {
    active_ = true;
    counted_ = false;
}

void StrokeHistory::strokeChanged() {
    if (counted_) return;
    ids_.push_back(nextId_++);
    counted_ = true;
}

bool StrokeHistory::endStroke() {
    const bool counted = counted_;
    active_ = false;
    counted_ = false;
    return counted;
}

void StrokeHistory::undone() {
    if (!ids_.empty()) ids_.pop_back();
}

void StrokeHistory::saved() {
    savedId_ = current();
}

void StrokeHistory::clear() {
    ids_.clear();
    savedId_ = 0;
}

Brush strokeBrush(Brush brush, float level, bool invert) {
    brush.level = level;
    if (invert && brush.mode == BrushMode::Raise)
        brush.mode = BrushMode::Lower;
    else if (invert && brush.mode == BrushMode::Lower)
        brush.mode = BrushMode::Raise;
    return brush;
}

std::vector<glm::dvec2> scriptedDabs(const ScriptedStroke& stroke, const glm::dvec2& mapSize,
                                     double radius) {
    const glm::dvec2 from = stroke.from * mapSize, to = stroke.to * mapSize;
    const int dabs =
        std::max(1, static_cast<int>(std::ceil(glm::length(to - from) / (0.25 * radius))) + 1);
    std::vector<glm::dvec2> points;
    points.reserve(static_cast<std::size_t>(dabs));
    for (int k = 0; k < dabs; ++k)
        points.push_back(dabs == 1 ? from
                                   : glm::mix(from, to, static_cast<double>(k) / (dabs - 1)));
    return points;
}

}  // namespace microrelief
