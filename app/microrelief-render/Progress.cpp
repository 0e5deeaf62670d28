#include "Progress.h"

#include <unistd.h>

#include <cmath>

namespace microrelief {

namespace {

std::string duration(double seconds) {
    const long long s = std::llround(seconds);
    char text[32];
    if (s >= 3600)
        std::snprintf(text, sizeof text, "%lld:%02lld:%02lld", s / 3600, s / 60 % 60, s % 60);
    else
        std::snprintf(text, sizeof text, "%lld:%02lld", s / 60, s % 60);
    return text;
}

}  // namespace

std::string progressLine(int done, int total, int rendered, double renderSeconds) {
    std::string line = "frame " + std::to_string(done) + " of " + std::to_string(total);
    if (rendered > 0 && renderSeconds > 0.0) {
        const double fps = rendered / renderSeconds;
        char rate[32];
        std::snprintf(rate, sizeof rate, ", %.3g fps", fps);
        line += rate;
        line += ", " + duration((total - done) / fps) + " left";
    }
    if (done < total && rendered < done)
        line += " (" + std::to_string(done - rendered) + " skipped)";
    return line;
}

BatchProgress::BatchProgress(int total, bool enabled, std::FILE* out)
    : total_(total), enabled_(enabled && total > 0), out_(out) {}

BatchProgress::~BatchProgress() {
    clear();
}

bool BatchProgress::stderrIsTerminal() {
    return ::isatty(STDERR_FILENO) == 1;
}

void BatchProgress::frameDone(bool rendered, double seconds) {
    ++done_;
    if (rendered) {
        ++rendered_;
        renderSeconds_ += seconds;
    }
    if (!enabled_) return;
    // A few times a second is enough to read, and keeps the terminal out of the way.
    const auto now = std::chrono::steady_clock::now();
    if (shown_ && done_ < total_ && now - lastDraw_ < std::chrono::milliseconds(100)) return;
    lastDraw_ = now;
    draw();
}

void BatchProgress::draw() {
    std::fprintf(out_, "\r\033[Kmicrorelief-render: %s",
                 progressLine(done_, total_, rendered_, renderSeconds_).c_str());
    std::fflush(out_);
    shown_ = true;
    drawnDone_ = done_;
}

void BatchProgress::finish() {
    if (!enabled_ || !shown_) return;
    if (drawnDone_ != done_) draw();  // the last frame's figures, unless already on the line
    std::fputs("\n", out_);
    std::fflush(out_);
    shown_ = false;
}

void BatchProgress::clear() {
    if (!enabled_ || !shown_) return;
    std::fputs("\r\033[K", out_);
    std::fflush(out_);
    shown_ = false;
}

}  // namespace microrelief
