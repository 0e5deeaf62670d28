// Whether an image file ends where its own structure says, for the formats whose
// OpenImageIO 2.4 decoder reads a cut-off file without an error: libjpeg fills the
// missing rows with grey, TGA's footer and GIF's trailer are never read, IFF reads past
// its end, and libtiff returns the strips it has. Checked by ImageFile.cpp's
// imageFileDefect before the full decode. Private to microrelief::io.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace microrelief {

// What says the file is cut off, or nothing: a JPEG without its end-of-image marker, a
// TGA without the TGA 2.0 footer OpenImageIO writes, a GIF without its trailer, an IFF
// shorter than its FORM chunk, a TIFF whose directories, tag values or strips and tiles
// lie past the end. `format` is OpenImageIO's name for it (format_name()); other formats
// have nothing to check here.
std::optional<std::string> cutOffDefect(const std::filesystem::path& file,
                                        const std::string& format);

}  // namespace microrelief
