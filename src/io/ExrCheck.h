// An OpenEXR file's header, read before OpenImageIO opens it. OpenEXR 3.1 (Debian 12)
// allocates what a header claims before it reads it: an attribute whose size field says
// 1.2 GB in a 300-byte file gets 1.2 GB (found by the fuzzer, tests/fuzz). Walking the
// header first bounds every attribute by the bytes the file has, and gives each part's
// data window, so that a size beyond the limit is refused before OpenEXR allocates.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace microrelief {

struct ExrPartSize {
    long long width = 0, height = 0;  // of the data window
};

// Whether the file starts with OpenEXR's magic number.
bool hasExrMagic(const std::filesystem::path& file);

// The data window of every part, in file order; empty with `defect` set when the
// header is malformed (an attribute running past the end of the file, a name too long,
// no data window).
std::optional<std::vector<ExrPartSize>> readExrHeader(const std::filesystem::path& file,
                                                      std::string& defect);

}  // namespace microrelief
