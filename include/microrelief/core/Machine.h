// What the machine running the program has (POSIX).
#pragma once

#include <unistd.h>

#include <cstddef>

namespace microrelief {

// The machine's memory, bytes (0 where the system does not say: no bound then).
inline std::size_t physicalMemoryBytes() {
    const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGESIZE);
    return pages > 0 && pageSize > 0 ? static_cast<std::size_t>(pages) * pageSize : 0;
}

}  // namespace microrelief
