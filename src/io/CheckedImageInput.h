// Opening an image file for reading, with the checks every input of the project gets
// before OpenImageIO reads a pixel (README, "Reliability"): a regular file, a PNG or
// OpenEXR header that states a size within the limit (from the header, before anything is
// allocated), a PNG whose structure libpng would accept, and the reader the extension
// names, and only that one. Private to microrelief::io.
#pragma once

#include <OpenImageIO/imageio.h>

#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>

namespace microrelief {

// Throws Error(BadInput) naming the file and the reason; `what` ("a height map", "an
// albedo") in the size message.
// `maxSamples` (0: none) bounds width x height from the header too (checkSize).
std::unique_ptr<OIIO::ImageInput> openCheckedImage(const std::filesystem::path& file, int maxSide,
                                                   const std::string& what,
                                                   std::size_t maxSamples = 0);

// Before a reader sees the path: a device (/dev/zero), a FIFO or a socket never ends or
// blocks, and format probes would read it forever. Throws Error(BadInput) naming `name`
// and what the file should be (`what`: "an image", "a mesh").
void checkRegularFile(const std::filesystem::path& file, const std::string& name,
                      const std::string& what = "an image");
// A size from a header, before anything is allocated: empty, a side beyond `maxSide`, or
// more samples than `maxSamples` (0: no bound; the message says what drawing them would
// take in memory, kPagedBytesPerSample a sample: MapOverMemory) is refused
// (Error(BadInput), `what` as above).
void checkSize(const std::string& name, long long width, long long height, int maxSide,
               const std::string& what, std::size_t maxSamples = 0);
// A library's message (OpenImageIO's, Assimp's) on one line.
std::string oneLine(std::string text);

}  // namespace microrelief
