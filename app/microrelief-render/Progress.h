// Progress of a batch run on a terminal: "frame k of n, F fps, M:SS left", rewritten in
// place on stderr; nothing at all when stderr is not a terminal (logs, pipes, Slurm
// output files) or with --quiet.
#pragma once

#include <chrono>
#include <cstdio>
#include <string>

namespace microrelief {

// The line after `done` of `total` frames, `rendered` of them drawn in `renderSeconds`
// (the rest skipped, taking no time): the rate of the drawn ones, and the time the
// frames still to do take at that rate.
std::string progressLine(int done, int total, int rendered, double renderSeconds);

class BatchProgress {
public:
    // `enabled`: draw at all (a terminal, not --quiet).
    BatchProgress(int total, bool enabled, std::FILE* out = stderr);
    ~BatchProgress();

    // One more frame dealt with; `rendered`: it was drawn, in `seconds`.
    void frameDone(bool rendered, double seconds);
    // Clears the line, so that another message starts on an empty one; the next
    // frameDone draws it again.
    void clear();
    // Ends the line, leaving the last figures on the terminal.
    void finish();

    // Whether stderr is a terminal.
    static bool stderrIsTerminal();

private:
    void draw();
    int total_;
    bool enabled_;
    std::FILE* out_;
    int done_ = 0, rendered_ = 0;
    int drawnDone_ = -1;  // done_ when the line was last drawn
    double renderSeconds_ = 0.0;
    bool shown_ = false;
    std::chrono::steady_clock::time_point lastDraw_{};
};

}  // namespace microrelief
