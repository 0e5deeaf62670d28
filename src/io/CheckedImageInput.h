// Opening an image file for reading, with the checks every input of the project gets
// before OpenImageIO reads a pixel (README, "Reliability"): a regular file, a PNG or
// OpenEXR header that states a size within the limit (from the header, before anything is
// allocated), a PNG whose structure libpng would accept, and the reader the extension
// names, and only that one. Private to microrelief::io.
#pragma once

#include <OpenImageIO/imageio.h>

#include <filesystem>
#include <memory>
#include <string>

namespace microrelief {

// Throws Error(BadInput) naming the file and the reason; `what` ("a height map", "an
// albedo") in the size message.
std::unique_ptr<OIIO::ImageInput> openCheckedImage(const std::filesystem::path& file, int maxSide,
                                                   const std::string& what);

// Before a reader sees the path: a device (/dev/zero), a FIFO or a socket never ends or
// blocks, and format probes would read it forever. Throws Error(BadInput) naming `name`.
void checkRegularFile(const std::filesystem::path& file, const std::string& name);
// A size from a header, before anything is allocated: empty, or a side beyond `maxSide`,
// is refused (Error(BadInput), `what` as above).
void checkSize(const std::string& name, long long width, long long height, int maxSide,
               const std::string& what);

// OpenImageIO's messages on one line.
std::string oneLine(std::string text);

}  // namespace microrelief
