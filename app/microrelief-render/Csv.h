// The CSV that camera files and manifests are written in (RFC 4180): fields separated
// by commas, a field holding a comma, a quote or leading/trailing space quoted, quotes
// inside doubled. One record a line: quoted fields do not span lines here.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace microrelief {

// `line`'s fields (without their quotes; unquoted fields trimmed of spaces), or nothing
// when a quote is not closed or text follows a closing quote.
std::optional<std::vector<std::string>> splitCsvLine(const std::string& line);

// `field` as a CSV field: quoted where it must be.
std::string csvField(const std::string& field);

}  // namespace microrelief
