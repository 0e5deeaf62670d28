// One height map as microrelief-bench's --maps list and a fetched-map list (maps.txt, from
// scripts/bench-maps.sh) name it: FILE[:CHANNEL][:normalize], the file and how it is
// loaded (microrelief-render's --channel and --normalize), and the name the report gives it.
#pragma once

#include <string>

#include "microrelief/core/scene/Scene.h"

namespace microrelief::bench {

struct MapEntry {
    MapSource source;   // the file (none: the bundled map), its channel and normalisation
    std::string given;  // where and how it was named, for messages: "--maps 'rock.png:1'"
};

// `text` as FILE[:CHANNEL][:normalize]. The suffixes are read from the right, in that
// order, only where they are exactly ":normalize" and then a whole number (digits only);
// whatever is left is the file name, colons and all: "a:b.png" is a file, "a:b.png:1" its
// channel 1, and a file whose own name ends in ":1" is named "x:1:0". The source's file is
// the file name as written ("default" is the caller's business). Throws Error(BadInput),
// the message not naming the flag (the caller does), for an empty file name or a channel
// beyond the kMaxHeightMapChannels a height map may have.
MapSource parseMapEntry(const std::string& text);

// What the report calls the map: the file's stem, then ":CHANNEL" for a channel other than
// 0 and ":normalize" ("rock", "rock:1", "terrain:normalize", "stone:2:normalize"), so that
// one file's channels stay apart. The bundled map goes by its file's stem (io/ReliefFiles.h:
// heightMapPath).
std::string mapName(const MapSource& source);

}  // namespace microrelief::bench
