// Text for one-line messages. Text from outside (a file name, a camera file's field, a shader's #include line) as it
// may go into a one-line message: control characters, DEL and bytes that are no UTF-8
// written as escapes, so a CR cannot overwrite the line on a terminal, a NUL cannot cut
// it short and a newline cannot split it.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace microrelief {

// `text` with \r, \n, \t as themselves escaped ("\\r"), other control characters, DEL and
// every byte that is not part of well-formed UTF-8 as "\\xNN"; valid UTF-8 (accents, "°")
// unchanged.
std::string printable(std::string_view text);

// `value` in a message, with `significant` digits at most ("0.3", "1e+07"): what a reader
// needs, not an exact copy (for those, the programs' exactNumber).
std::string formatNumber(double value, int significant);

// Words as a list in a sentence: "a", "a or b", "a, b or c" (`last` is " or " or " and ").
std::string joinWords(const std::vector<std::string>& words, std::string_view last);

}  // namespace microrelief
