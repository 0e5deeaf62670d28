#include "microrelief/Version.h"

namespace microrelief {

const char* libraryVersion() {
    return MICRORELIEF_VERSION_STRING;
}

}  // namespace microrelief
