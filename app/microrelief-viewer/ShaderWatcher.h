// Shader hot reload, the polling kind: every few tenths of a second the viewer asks
// whether any file under the shader folder was added, removed or modified (a change of
// size or modification time). Polling needs no inotify and sees editors that save by
// writing a new file and renaming it over the old one.
#pragma once

#include <chrono>
#include <filesystem>
#include <map>

namespace microrelief {

class ShaderWatcher {
public:
    explicit ShaderWatcher(std::filesystem::path folder);

    const std::filesystem::path& folder() const { return folder_; }

    // True once after the folder's files change; looks at most every `interval`.
    bool changed(std::chrono::milliseconds interval = std::chrono::milliseconds(300));

private:
    struct Stamp {
        std::filesystem::file_time_type modified;
        std::uintmax_t size = 0;
        bool operator==(const Stamp&) const = default;
    };
    using Snapshot = std::map<std::filesystem::path, Stamp>;
    Snapshot snapshot() const;

    std::filesystem::path folder_;
    Snapshot last_;
    std::chrono::steady_clock::time_point lastLook_;
};

}  // namespace microrelief
