#include "ShaderWatcher.h"

namespace microrelief {

ShaderWatcher::ShaderWatcher(std::filesystem::path folder)
    : folder_(std::move(folder)), last_(snapshot()), lastLook_(std::chrono::steady_clock::now()) {}

ShaderWatcher::Snapshot ShaderWatcher::snapshot() const {
    Snapshot files;
    std::error_code ec;
    // A file may vanish between listing and stat (an editor's rename): skip it this
    // time; the next look sees the new one.
    for (auto it = std::filesystem::recursive_directory_iterator(folder_, ec);
         !ec && it != std::filesystem::recursive_directory_iterator(); it.increment(ec)) {
        std::error_code statError;
        if (!it->is_regular_file(statError)) continue;
        const auto modified = it->last_write_time(statError);
        const auto size = it->file_size(statError);
        if (!statError) files[it->path()] = {modified, size};
    }
    return files;
}

bool ShaderWatcher::changed(std::chrono::milliseconds interval) {
    const auto now = std::chrono::steady_clock::now();
    if (now - lastLook_ < interval) return false;
    lastLook_ = now;
    Snapshot current = snapshot();
    if (current == last_) return false;
    last_ = std::move(current);
    return true;
}

}  // namespace microrelief
