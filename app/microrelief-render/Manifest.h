// The manifest of a batch run (one per shard): a CSV row per frame the run has dealt
// with, "frame,file,camera,ms,status", status "rendered", "skipped" (--skip-existing
// found it complete) or "failed".
//
// Appended, not rewritten: each row goes to the file, opened O_APPEND, in one write(2)
// (checked, and synced to the disk; a row that fails comes off again) once the frame's
// files are in place, so a shard killed at any moment leaves a readable manifest of
// every frame it finished, and a restarted shard appends its rows after them (the
// header is written once, when the file is new). A reader takes a
// frame's last row; a torn last line (power cut) is ended before the next row and is
// skipped by readManifest.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace microrelief {

struct ManifestRow {
    int frame = 0;
    std::string file;    // the picture
    std::string camera;  // the frame's camera (and row flags) as microrelief-render flags
    double ms = 0.0;     // time spent on the frame: render, read back and write
    std::string status;  // rendered, skipped, failed
};

inline constexpr const char* kManifestHeader = "frame,file,camera,ms,status";

class ManifestWriter {
public:
    // Creates the file (and its folder) with its header, or opens it to append. Throws
    // Error(BadInput) for a file that is not a manifest, Error(Runtime) when it cannot
    // be written.
    explicit ManifestWriter(const std::filesystem::path& file);
    ~ManifestWriter();
    ManifestWriter(const ManifestWriter&) = delete;
    ManifestWriter& operator=(const ManifestWriter&) = delete;

    // Throws Error(Runtime) when the row cannot be written.
    void append(const ManifestRow& row);
    const std::filesystem::path& file() const { return file_; }

private:
    // Every byte and fdatasync, or Error(Runtime) with the file as it was before.
    void append(const std::string& text);
    std::filesystem::path file_;
    int fd_ = -1;
};

// The row as the manifest has it, newline included.
std::string manifestLine(const ManifestRow& row);

// Every whole row of a manifest, in file order (a line that is no row is skipped).
// Throws Error(BadInput) when the file cannot be read or is not a manifest.
std::vector<ManifestRow> readManifest(const std::filesystem::path& file);

}  // namespace microrelief
