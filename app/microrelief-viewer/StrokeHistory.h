// What the sculpting tool decides without a window (SculptTool.h draws it on the GPU):
// - StrokeHistory: the map's edit states as the viewer counts them. A stroke that changed a
//   sample is one state, undone in order; the state last saved or opened (no stroke) is not
//   an edit, and undoing back to it makes the map unedited again (the quit and open
//   warnings ask only then).
// - strokeBrush: the brush a dab paints with (Ctrl inverts raise and lower; flatten moves
//   towards the height under the stroke's first dab).
// - scriptedDabs: where a --stroke's dabs fall, a quarter of the radius apart, as a hand's.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "ViewerOptions.h"
#include "microrelief/gl/HeightEditor.h"

namespace microrelief {

class StrokeHistory {
public:
    // A stroke's first dab: a new stroke, not counted until one of its dabs changes a sample.
    void startStroke();
    bool strokeActive() const { return active_; }
    // A dab of the stroke changed samples: the stroke is one of the map's states (once).
    void strokeChanged();
    // The stroke ends (the button let go, an undo); whether it changed the map.
    bool endStroke();
    // An undo wrote samples back: the last stroke's state goes.
    void undone();
    // The map as it is now is on disk: it is the state an edit differs from.
    void saved();
    // Another map: no strokes, nothing to undo, nothing edited.
    void clear();
    // Whether the map differs from the state last saved or opened.
    bool edited() const { return current() != savedId_; }

private:
    int current() const { return ids_.empty() ? 0 : ids_.back(); }

    std::vector<int> ids_;  // the undoable strokes that changed the map, in order
    int nextId_ = 1, savedId_ = 0;
    bool active_ = false, counted_ = false;
};

// The brush a dab paints with: `brush` at `level` (flatten's target), raise and lower
// swapped where `invert` (Ctrl held).
Brush strokeBrush(Brush brush, float level, bool invert);

// The dabs of `stroke` on a `mapSize` map (texels) for a brush of `radius` texels: from its
// start to its end, a quarter of the radius apart (at least one, at its start).
std::vector<glm::dvec2> scriptedDabs(const ScriptedStroke& stroke, const glm::dvec2& mapSize,
                                     double radius);

}  // namespace microrelief
