// Camera paths: the frames microrelief-render draws in one process, each a whole scene
// (map, camera, shading) built on the command line's. --turntable N turns the command
// line's camera around its target; --cameras FILE reads one camera a row, with the
// row's own map and shading flags where it has them.
//
// Camera files are CSV with a header, or JSON lines (one object a line), told apart by
// their first line; blank lines and lines starting with # are skipped. Data rows are
// frames 0, 1, ... in file order.
//   CSV columns: eye_x, eye_y, eye_z, target_x, target_y, target_z (needed); up_x, up_y,
//     up_z and fovy (optional; an absent column or an empty field takes the command
//     line's value); flags (optional).
//   JSON keys: "eye": [x, y, z], "target": [x, y, z] (needed); "up": [x, y, z],
//     "fovy": degrees, "flags": "..." (optional).
// `flags` holds the row's map and shading flags as on a command line, e.g.
// "--height maps/b.png --light 0,1,0" (a CSV field with commas is quoted): any of
// --height --channel --normalize --height-scale --size --light --method --steps
// --pixel-error --view --background, applied on top of the command line's; the camera
// itself comes from the columns only. Paths are relative to the working folder, as on
// the command line.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "SceneOptions.h"

namespace microrelief {

struct PathFrame {
    SceneOptions scene;
    std::string flags;   // the row's own flags as written ("" for none)
    std::string origin;  // where the frame comes from, for messages: "cams.csv: line 4 (frame 2)"
};

// `views` views around the target at the eye's distance and elevation: frame k's eye
// and up are the command line's turned by 360 k / views degrees about the vertical (y)
// axis through the target, counter-clockwise seen from above; frame 0 is the command
// line's camera as given. Throws Error(BadInput) for a degenerate camera.
std::vector<PathFrame> turntablePath(const SceneOptions& base, int views);
// Frame k of that turntable alone. Throws Error(BadInput) for a degenerate camera.
PathFrame turntableFrame(const SceneOptions& base, int views, int k);

// The frames of a path, made when asked for: a turntable holds only its command line's
// scene (a million views cost nothing until drawn), a camera file its rows (each checked
// as it was read).
class CameraPath {
public:
    // Throws Error(BadInput) for no views or a degenerate camera at frame 0.
    static CameraPath turntable(const SceneOptions& base, int views);
    explicit CameraPath(std::vector<PathFrame> rows) : rows_(std::move(rows)) {}

    int size() const { return base_ ? views_ : static_cast<int>(rows_.size()); }
    // Frame k, 0 <= k < size(). Throws Error(BadInput) for a degenerate turntable camera.
    PathFrame frame(int k) const;
    // Whether any frame draws soft shadows (and so uses --light-size).
    bool anySoftShadows() const;

private:
    CameraPath() = default;
    std::vector<PathFrame> rows_;
    std::optional<SceneOptions> base_;  // a turntable's
    int views_ = 0;
};

// --cameras FILE. Throws Error(BadInput) naming the file, the line and the reason for a
// missing or unreadable file, a missing or unknown column, a field that is not a
// finite number, a degenerate camera (eye = target, up along the view, fovy outside
// (0, 180)) or bad row flags (--help among them): before any frame is drawn. A UTF-8
// byte order mark before the first line (as spreadsheets write) is skipped.
std::vector<PathFrame> readCameraFile(const std::filesystem::path& file, const SceneOptions& base);
// The same from the file's text; `source` names the file in messages.
std::vector<PathFrame> parseCameraFile(const std::string& text, const std::string& source,
                                       const SceneOptions& base);

// The camera as microrelief-render flags, every number exact:
// "--eye=x,y,z --target=x,y,z --up=x,y,z --fovy F".
std::string cameraFlags(const Camera& camera);

}  // namespace microrelief
