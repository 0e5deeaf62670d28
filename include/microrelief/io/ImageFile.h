// Writing pictures and AOVs through OpenImageIO, whole or not at all: each file is
// written to a temporary file in its target's folder and renamed over the target only
// when every file of the job has been written and is on disk (scene-and-cli.md,
// "Outputs"; io/AtomicFile.h says what "written" means).
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "microrelief/io/AtomicFile.h"

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

// Throws Error(BadInput) if no OpenImageIO writer handles the path's extension, or if
// its writer cannot write through a checked stream (whose every write is checked: the
// formats microrelief writes, io/AtomicFile.h).
void checkImageExtension(const std::filesystem::path& file);

// Before any work: every output has a known image extension, is not a folder or other
// non-regular file (a FIFO, a device), lies in a folder that exists or can be made, and
// no two outputs are the same file: compared as resolved paths (symbolic links and ".."
// followed, std::filesystem::weakly_canonical) and, where the file exists, by device and
// inode (hard links). Throws Error(BadInput) naming the file.
void checkOutputTargets(const std::vector<std::filesystem::path>& files);

// Pictures written together, as FileWriteBatch writes files: write() encodes each one
// into its temporary, commit() renames them all into place; what was not committed is
// removed on destruction or on a signal, folders write() made included.
class ImageWriteBatch {
public:
    // Creates the target's folder if needed. Throws Error(Runtime) naming the file,
    // Error(BadInput) for a folder or other non-regular file at the target.
    void write(const std::filesystem::path& file, const ImageData& image);
    void commit() { files_.commit(); }

private:
    FileWriteBatch files_;
};

// RGBA8 rows -> RGB rows (the pictures are opaque); `flipRows` turns GL's bottom-up rows
// into the top-down rows of every output image.
std::vector<std::uint8_t> rgbFromRgba(const std::vector<std::uint8_t>& rgba, int width, int height,
                                      bool flipRows = false);

// One file, atomically.
void writeImageAtomically(const std::filesystem::path& file, const ImageData& image);

// Why `file` is not a whole image, or nothing when it is: what --skip-existing asks of a
// frame before it keeps it. A PNG's every chunk (its length within the file, its CRC,
// IEND last) and its image data inflated; an OpenEXR file's header, then every pixel
// read; where a decoder takes a cut-off file for whole, the end its structure gives (a
// JPEG's end-of-image marker, a TGA's footer, a GIF's trailer, an IFF's FORM length, a
// TIFF's directories and strips), then every pixel; any other format decoded in full.
std::optional<std::string> imageFileDefect(const std::filesystem::path& file);

}  // namespace microrelief
