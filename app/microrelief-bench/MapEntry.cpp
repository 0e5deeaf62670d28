#include "MapEntry.h"

#include "microrelief/core/Error.h"
#include "microrelief/io/ReliefFiles.h"

namespace microrelief::bench {

namespace {

// The text after the last ':' of `rest`, if it is `accept`ed: removed from `rest`.
template <typename Accept>
bool takeSuffix(std::string& rest, Accept accept) {
    const std::size_t colon = rest.rfind(':');
    if (colon == std::string::npos || !accept(rest.substr(colon + 1))) return false;
    rest.erase(colon);
    return true;
}

bool wholeNumber(const std::string& text) {
    return !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
}

}  // namespace

MapSource parseMapEntry(const std::string& text) {
    MapSource source;
    std::string rest = text;
    source.load.normalize =
        takeSuffix(rest, [](const std::string& suffix) { return suffix == "normalize"; });
    std::string channel;
    if (takeSuffix(rest, [&](const std::string& suffix) {
            channel = suffix;
            return wholeNumber(suffix);
        })) {
        // Digit by digit, stopping past the bound: no overflow, however long.
        long value = 0;
        for (char digit : channel) {
            value = value * 10 + (digit - '0');
            if (value >= kMaxHeightMapChannels)
                throwBadInput("channel " + channel + " is beyond the " +
                              std::to_string(kMaxHeightMapChannels) +
                              " channels a height map may have");
        }
        source.load.channel = static_cast<int>(value);
    }
    if (rest.empty()) throwBadInput("an empty file name");
    source.file = rest;
    return source;
}

std::string mapName(const MapSource& source) {
    std::string name = heightMapPath(source).stem().string();
    if (source.load.channel != 0) name += ":" + std::to_string(source.load.channel);
    if (source.load.normalize) name += ":normalize";
    return name;
}

}  // namespace microrelief::bench
