// Writing pictures and AOVs through OpenImageIO, whole or not at all: each file is
// written to a temporary file in its target's folder and renamed over the target only
// when every file of the job has been written (scene-and-cli.md, "Outputs").
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace microrelief {

enum class PixelType { UInt8, UInt16, Float };

// A view of interleaved pixels, row 0 at the top; the file gets this type where its
// format can store it (OpenImageIO converts otherwise).
struct ImageData {
    int width = 0, height = 0, channels = 0;
    PixelType type = PixelType::UInt8;
    const void* pixels = nullptr;
    std::vector<std::string> channelNames;  // empty: OpenImageIO's defaults (R, G, B, A)
};

// Throws Error(BadInput) if no OpenImageIO writer handles the path's extension.
void checkImageExtension(const std::filesystem::path& file);

// Before any work: every output has a known image extension, is not a folder, lies in a
// folder that exists or can be made, and no two outputs are the same file: compared as
// resolved paths (symbolic links and ".." followed, std::filesystem::weakly_canonical)
// and, where the file exists, by device and inode (hard links). Throws Error(BadInput)
// naming the file.
void checkOutputTargets(const std::vector<std::filesystem::path>& files);

// A set of files written together: write() stages each one beside its target, commit()
// renames them all into place, restoring the old files if any rename fails. Whatever
// was not committed is removed on destruction, folders write() made included, so a
// failed run leaves no new or changed file and no new folder. SIGINT, SIGTERM and SIGHUP
// do the same: a handler, installed with the first batch, undoes every unfinished batch
// of the process (temporaries removed, files moved aside put back, new folders removed)
// from a table of fixed buffers, and the process then dies of the signal.
class ImageWriteBatch {
public:
    ImageWriteBatch() = default;
    ImageWriteBatch(const ImageWriteBatch&) = delete;
    ImageWriteBatch& operator=(const ImageWriteBatch&) = delete;
    ~ImageWriteBatch();

    // Creates the target's folder if needed. Throws Error(Runtime) naming the file.
    void write(const std::filesystem::path& file, const ImageData& image);
    void commit();

private:
    void createFolders(const std::filesystem::path& file);

    struct Staged {
        std::filesystem::path target, temporary;
        int slot = -1;  // in the signal handler's table: removes the temporary
    };
    std::vector<Staged> staged_;
    std::vector<std::pair<std::filesystem::path, int>> createdFolders_;  // outermost first
    bool committed_ = false;
};

// RGBA8 rows -> RGB rows (the pictures are opaque); `flipRows` turns GL's bottom-up rows
// into the top-down rows of every output image.
std::vector<std::uint8_t> rgbFromRgba(const std::vector<std::uint8_t>& rgba, int width, int height,
                                      bool flipRows = false);

// One file, atomically.
void writeImageAtomically(const std::filesystem::path& file, const ImageData& image);

// The target whose temporary `file` is, when it is one of ImageWriteBatch's temporary
// files and the process that wrote it is gone: a writer killed before its rename
// (SIGKILL, a power cut) leaves it behind. Else nothing (not a temporary, or one that a
// running process on this machine may still rename).
std::optional<std::filesystem::path> abandonedTemporaryTarget(const std::filesystem::path& file);

}  // namespace microrelief
