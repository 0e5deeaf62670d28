// What the machine running the program has (POSIX; Linux's /proc/meminfo where there is one).
#pragma once

#include <unistd.h>

#include <charconv>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>

namespace microrelief {

// The machine's memory, bytes (0 where the system does not say: no bound then).
inline std::size_t physicalMemoryBytes() {
    const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGESIZE);
    return pages > 0 && pageSize > 0 ? static_cast<std::size_t>(pages) * pageSize : 0;
}

// The "MemAvailable: N kB" line of Linux's /proc/meminfo, in bytes; 0 where `meminfo` has
// no such line or its number does not read.
inline std::size_t memAvailableBytes(std::string_view meminfo) {
    constexpr std::string_view key = "MemAvailable:";
    for (std::size_t at = 0; at < meminfo.size();) {
        std::size_t end = meminfo.find('\n', at);
        if (end == std::string_view::npos) end = meminfo.size();
        std::string_view line = meminfo.substr(at, end - at);
        at = end + 1;
        if (line.substr(0, key.size()) != key) continue;
        line.remove_prefix(key.size());
        while (!line.empty() && line.front() == ' ') line.remove_prefix(1);
        std::uint64_t kib = 0;
        const auto [rest, error] = std::from_chars(line.data(), line.data() + line.size(), kib);
        const std::string_view unit(rest, line.data() + line.size() - rest);
        if (error != std::errc() || unit != " kB" || kib > SIZE_MAX / 1024) return 0;
        return static_cast<std::size_t>(kib) * 1024;
    }
    return 0;
}

// The environment variable that stands for the memory available, in MiB (a positive whole
// number; anything else is ignored),
// where a test needs a machine of another size without taking its memory.
inline constexpr const char* kAvailableMemoryVariable = "MICRORELIEF_AVAILABLE_MEMORY_MIB";

// The memory a program may take now, bytes: what kAvailableMemoryVariable says where it is
// set to a number of MiB; else Linux's MemAvailable (its estimate of what can be allocated
// without swapping: the free memory and the caches it can drop), which another program's use
// lowers; else, where that cannot be read, the machine's physical memory. 0 where nothing
// says (no bound then). What the programs admit a map against (docs/reliability-inputs.md).
inline std::size_t availableMemoryBytes() {
    if (const char* given = std::getenv(kAvailableMemoryVariable); given && *given) {
        const std::string_view text(given);
        std::uint64_t mib = 0;
        const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), mib);
        if (error == std::errc() && end == text.data() + text.size() && mib > 0 &&
            mib <= SIZE_MAX >> 20)
            return static_cast<std::size_t>(mib) << 20;
    }
    std::ifstream meminfo("/proc/meminfo");
    std::ostringstream text;
    if (meminfo && (text << meminfo.rdbuf()))
        if (const std::size_t available = memAvailableBytes(text.str()); available > 0)
            return available;
    return physicalMemoryBytes();
}

}  // namespace microrelief
