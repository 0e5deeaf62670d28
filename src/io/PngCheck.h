// A PNG file's structure, checked before OpenImageIO reads it. OpenImageIO 2.4's PNG
// reader (Debian 12) gives libpng an error callback that records the message and
// returns, so libpng's default handler then prints "libpng error: ..." to stderr
// itself before the read fails: a second line beside our one-line error, which no
// API of OpenImageIO 2.4 turns off (its warning callback is silent; the error one is
// not). Refusing what libpng would call an error before libpng sees it keeps stderr
// ours without touching file descriptor 2.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

namespace microrelief {

struct PngHeader {
    std::uint32_t width = 0, height = 0;
    int bitDepth = 0, colorType = 0;
    bool interlaced = false;
};

// Whether the file starts with the PNG signature.
bool hasPngSignature(const std::filesystem::path& file);

// Reads the IHDR chunk: the picture size, before anything else is read. Empty when the
// file does not start with a valid IHDR; `defect` then says why.
std::optional<PngHeader> readPngHeader(const std::filesystem::path& file, std::string& defect);

// Walks every chunk (lengths within the file, CRCs, IHDR first, PLTE where a palette
// image needs it, IDAT present and contiguous, IEND last) and inflates the image data
// (a complete zlib stream of exactly the size IHDR implies, every row's filter type
// 0 to 4). Returns what is wrong, empty for a sound file. Reads in small pieces: the
// memory it needs does not grow with the picture.
std::optional<std::string> pngStructureDefect(const std::filesystem::path& file);

}  // namespace microrelief
