#include "microrelief/image/ImageFile.h"

#include <OpenImageIO/imageio.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <csignal>
#include <cstring>
#include <mutex>
#include <optional>
#include <vector>

#include "microrelief/core/Error.h"

namespace microrelief {

namespace {

std::string oneLine(std::string text) {
    std::replace(text.begin(), text.end(), '\n', ' ');
    while (!text.empty() && text.back() == ' ') text.pop_back();
    return text;
}

// ".name.tmp-<pid>-<n>.ext": hidden, unique per process and call, and keeping the
// extension, from which OpenImageIO picks the format.
std::filesystem::path temporaryBeside(const std::filesystem::path& target) {
    static std::atomic<int> counter{0};
    const std::string name = "." + target.stem().string() + ".tmp-" + std::to_string(::getpid()) +
                             "-" + std::to_string(counter++) + target.extension().string();
    return target.parent_path() / name;
}

// What a signal must undo: files and folders of unfinished batches, registered while they
// exist. A fixed table of fixed buffers, claimed with atomics, because the handler may
// only use what is async-signal-safe: no allocation, no locks, unlink/rename/rmdir.
class CleanupRegistry {
public:
    enum class Action : int { Unlink, Restore, RemoveFolder };

    static CleanupRegistry& instance() {
        static CleanupRegistry registry;  // constructed before any handler is installed
        return registry;
    }

    // Returns the slot, or -1 when the table is full or a path is too long (the normal
    // paths then still clean up; only a signal would leave that one file).
    int add(Action action, const std::filesystem::path& path,
            const std::filesystem::path& target = {}) {
        installHandlers();
        const std::string a = path.string(), b = target.string();
        if (a.size() >= kPathSize || b.size() >= kPathSize) return -1;
        for (int k = 0; k < kSlots; ++k) {
            int expected = kFree;
            if (!slots_[k].state.compare_exchange_strong(expected, kFilling)) continue;
            std::memcpy(slots_[k].path, a.c_str(), a.size() + 1);
            std::memcpy(slots_[k].target, b.c_str(), b.size() + 1);
            slots_[k].action = action;
            slots_[k].state.store(kLive, std::memory_order_release);
            return k;
        }
        return -1;
    }

    void remove(int slot) {
        if (slot >= 0) slots_[slot].state.store(kFree, std::memory_order_release);
    }

    // From the signal handler: files first (remove unfinished ones, put moved-aside ones
    // back), then the folders a batch made, deepest first, as far as they are empty.
    void undoAll() {
        for (Slot& s : slots_) {
            if (s.state.load(std::memory_order_acquire) != kLive) continue;
            if (s.action == Action::Unlink) ::unlink(s.path);
            if (s.action == Action::Restore) ::rename(s.path, s.target);
        }
        for (int pass = 0; pass < kSlots; ++pass) {
            bool removed = false;
            for (int k = kSlots - 1; k >= 0; --k) {
                Slot& s = slots_[k];
                if (s.state.load(std::memory_order_acquire) != kLive ||
                    s.action != Action::RemoveFolder)
                    continue;
                if (::rmdir(s.path) == 0) {
                    s.state.store(kFree, std::memory_order_release);
                    removed = true;
                }
            }
            if (!removed) break;
        }
    }

private:
    static constexpr int kSlots = 64;
    static constexpr std::size_t kPathSize = 4096;
    static constexpr int kFree = 0, kFilling = 1, kLive = 2;
    struct Slot {
        std::atomic<int> state{kFree};
        Action action = Action::Unlink;
        char path[kPathSize];
        char target[kPathSize];
    };

    static void onSignal(int signal) {
        instance().undoAll();
        // Then die of the signal as if it had never been caught (the exit status says so).
        std::signal(signal, SIG_DFL);
        std::raise(signal);
    }

    void installHandlers() {
        static std::once_flag once;
        std::call_once(once, [] {
            struct sigaction action {};
            action.sa_handler = onSignal;
            sigemptyset(&action.sa_mask);
            for (int signal : {SIGINT, SIGTERM, SIGHUP}) {
                struct sigaction previous {};
                // A signal the program ignores (nohup, a shell's background job) stays so.
                if (::sigaction(signal, nullptr, &previous) == 0 && previous.sa_handler == SIG_IGN)
                    continue;
                ::sigaction(signal, &action, nullptr);
            }
        });
    }

    std::array<Slot, kSlots> slots_;
};

// A path as the file system sees it: symbolic links and "..", resolved as far as the
// path exists (std::filesystem::weakly_canonical), and the file's device and inode when
// it exists, so that a hard link counts as the same file.
struct FileIdentity {
    std::filesystem::path resolved;
    std::optional<std::pair<dev_t, ino_t>> inode;

    explicit FileIdentity(const std::filesystem::path& file) {
        std::error_code ec;
        resolved = std::filesystem::weakly_canonical(std::filesystem::absolute(file, ec), ec);
        if (ec) resolved = std::filesystem::absolute(file).lexically_normal();
        struct stat info {};
        if (::stat(file.c_str(), &info) == 0) inode = std::make_pair(info.st_dev, info.st_ino);
    }
    bool sameFileAs(const FileIdentity& other) const {
        return resolved == other.resolved || (inode && other.inode && *inode == *other.inode);
    }
};

}  // namespace

void checkImageExtension(const std::filesystem::path& file) {
    const std::string extension = file.extension().string();
    if (extension.empty())
        throwBadInput(file.string() + ": no extension to choose an image format by");
    auto output = OIIO::ImageOutput::create(file.string());
    if (!output) {
        OIIO::geterror();  // clear the pending message
        throwBadInput(file.string() + ": no image format for the extension '" + extension + "'");
    }
}

ImageWriteBatch::~ImageWriteBatch() {
    CleanupRegistry& registry = CleanupRegistry::instance();
    for (const Staged& s : staged_) {
        std::error_code ignored;
        std::filesystem::remove(s.temporary, ignored);
        registry.remove(s.slot);
    }
    // The folders this batch made, deepest first; remove() leaves a folder that is not
    // empty (another program's file, or an earlier committed batch's).
    for (auto it = createdFolders_.rbegin(); it != createdFolders_.rend(); ++it) {
        std::error_code ignored;
        if (!committed_) std::filesystem::remove(it->first, ignored);
        registry.remove(it->second);
    }
}

void ImageWriteBatch::createFolders(const std::filesystem::path& file) {
    const std::filesystem::path folder = file.parent_path();
    if (folder.empty()) return;
    // Each missing folder from the outermost in, made one at a time, so that the batch
    // knows which it made and can take them away again if the job fails.
    std::vector<std::filesystem::path> missing;
    std::error_code ec;
    for (std::filesystem::path p = folder; !p.empty() && !std::filesystem::exists(p, ec);
         p = p.parent_path()) {
        missing.push_back(p);
        if (p == p.parent_path()) break;
    }
    for (auto it = missing.rbegin(); it != missing.rend(); ++it) {
        if (!std::filesystem::create_directory(*it, ec) && ec) {
            throwRuntime(file.string() + ": cannot create the folder " + it->string() + " (" +
                         ec.message() + ")");
        }
        createdFolders_.push_back(
            {*it, CleanupRegistry::instance().add(CleanupRegistry::Action::RemoveFolder, *it)});
    }
    if (!std::filesystem::is_directory(folder, ec))
        throwRuntime(file.string() + ": " + folder.string() + " is not a folder");
}

void ImageWriteBatch::write(const std::filesystem::path& file, const ImageData& image) {
    createFolders(file);
    const std::filesystem::path temporary = temporaryBeside(file);
    // Registered before the file exists: a signal from here on removes it.
    staged_.push_back(
        {file, temporary,
         CleanupRegistry::instance().add(CleanupRegistry::Action::Unlink, temporary)});

    auto output = OIIO::ImageOutput::create(file.string());
    if (!output) throwBadInput(file.string() + ": no image format for this extension");
    const OIIO::TypeDesc type = image.type == PixelType::Float    ? OIIO::TypeDesc::FLOAT
                                : image.type == PixelType::UInt16 ? OIIO::TypeDesc::UINT16
                                                                  : OIIO::TypeDesc::UINT8;
    OIIO::ImageSpec spec(image.width, image.height, image.channels, type);
    if (!image.channelNames.empty()) spec.channelnames = image.channelNames;
    const bool namedAlpha = image.channelNames.size() > 3 && image.channelNames[3] == "A";
    if (image.channels == 4 || namedAlpha) spec.alpha_channel = 3;
    const bool ok = output->open(temporary.string(), spec) &&
                    output->write_image(type, image.pixels) && output->close();
    if (!ok) {
        const std::string reason = oneLine(output->geterror());
        throwRuntime(file.string() + ": cannot write (" +
                     (reason.empty() ? "unknown error" : reason) + ")");
    }
}

void ImageWriteBatch::commit() {
    // Move each existing target aside first, so that a rename failing half-way can be
    // undone: either every target is the new file, or every target is as it was. The
    // registry knows how to undo each step, so that a signal half-way undoes them too.
    CleanupRegistry& registry = CleanupRegistry::instance();
    using Action = CleanupRegistry::Action;
    struct Moved {
        std::filesystem::path target, backup;
        bool replaced = false;
        int slot = -1;  // puts the old file back, or removes the new one
    };
    std::vector<Moved> moved;
    auto rollBack = [&moved, &registry] {
        for (auto it = moved.rbegin(); it != moved.rend(); ++it) {
            std::error_code ignored;
            if (it->replaced) std::filesystem::remove(it->target, ignored);
            if (!it->backup.empty()) std::filesystem::rename(it->backup, it->target, ignored);
            registry.remove(it->slot);
        }
    };
    for (Staged& s : staged_) {
        Moved m{s.target, {}};
        std::error_code ec;
        if (std::filesystem::exists(s.target, ec)) {
            m.backup = temporaryBeside(s.target);
            m.slot = registry.add(Action::Restore, m.backup, s.target);
            std::filesystem::rename(s.target, m.backup, ec);
            if (ec) {
                registry.remove(m.slot);
                rollBack();
                throwRuntime(s.target.string() + ": cannot replace the existing file (" +
                             ec.message() + ")");
            }
        } else {
            m.slot = registry.add(Action::Unlink, s.target);
        }
        moved.push_back(m);
        std::filesystem::rename(s.temporary, s.target, ec);
        if (ec) {
            rollBack();
            throwRuntime(s.target.string() + ": cannot move the finished file into place (" +
                         ec.message() + ")");
        }
        registry.remove(s.slot);  // the temporary is the target now
        s.slot = -1;
        moved.back().replaced = true;
    }
    // Every target is new: from here a signal only removes the old files moved aside.
    for (Moved& m : moved) {
        registry.remove(m.slot);
        m.slot = m.backup.empty() ? -1 : registry.add(Action::Unlink, m.backup);
    }
    for (const Moved& m : moved) {
        std::error_code ignored;
        if (!m.backup.empty()) std::filesystem::remove(m.backup, ignored);
        registry.remove(m.slot);
    }
    staged_.clear();
    committed_ = true;
}

void checkOutputTargets(const std::vector<std::filesystem::path>& files) {
    std::vector<FileIdentity> identities;
    for (std::size_t k = 0; k < files.size(); ++k) {
        std::error_code ec;
        if (std::filesystem::is_directory(files[k], ec))
            throwBadInput(files[k].string() + ": is a directory");
        checkImageExtension(files[k]);
        // The nearest part of the folder that exists must be a folder, or the folders
        // cannot be made.
        std::filesystem::path folder = files[k].parent_path();
        while (!folder.empty() && !std::filesystem::exists(folder, ec))
            folder = folder.parent_path();
        if (!folder.empty() && !std::filesystem::is_directory(folder, ec))
            throwBadInput(files[k].string() + ": " + folder.string() + " is not a folder");
        identities.emplace_back(files[k]);
        for (std::size_t other = 0; other < k; ++other) {
            if (identities[k].sameFileAs(identities[other])) {
                throwBadInput(files[k].string() + ": the same file as " + files[other].string() +
                              ", given for two outputs");
            }
        }
    }
}

std::vector<std::uint8_t> rgbFromRgba(const std::vector<std::uint8_t>& rgba, int width, int height,
                                      bool flipRows) {
    std::vector<std::uint8_t> rgb(static_cast<std::size_t>(width) * height * 3);
    for (int row = 0; row < height; ++row) {
        const int from = flipRows ? height - 1 - row : row;
        for (int column = 0; column < width; ++column) {
            const std::size_t p = (static_cast<std::size_t>(from) * width + column) * 4;
            const std::size_t q = (static_cast<std::size_t>(row) * width + column) * 3;
            rgb[q] = rgba[p];
            rgb[q + 1] = rgba[p + 1];
            rgb[q + 2] = rgba[p + 2];
        }
    }
    return rgb;
}

void writeImageAtomically(const std::filesystem::path& file, const ImageData& image) {
    ImageWriteBatch batch;
    batch.write(file, image);
    batch.commit();
}

std::optional<std::filesystem::path> abandonedTemporaryTarget(const std::filesystem::path& file) {
    // The name temporaryBeside gives: ".<stem>.tmp-<pid>-<n><extension>".
    const std::string name = file.filename().string();
    const std::size_t tag = name.rfind(".tmp-");
    if (name.size() < 2 || name[0] != '.' || tag == std::string::npos || tag < 1)
        return std::nullopt;
    const char* p = name.data() + tag + 5;
    const char* end = name.data() + name.size();
    long pid = 0, n = 0;
    auto read = std::from_chars(p, end, pid);
    if (read.ec != std::errc() || read.ptr == end || *read.ptr != '-' || pid <= 0)
        return std::nullopt;
    read = std::from_chars(read.ptr + 1, end, n);
    if (read.ec != std::errc()) return std::nullopt;
    const std::string extension(read.ptr, end);
    if (!extension.empty() && (extension[0] != '.' || extension.find('.', 1) != std::string::npos))
        return std::nullopt;
    // A process that still runs may yet rename it (kill with signal 0 only asks).
    if (pid == ::getpid() || ::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH)
        return std::nullopt;
    return file.parent_path() / (name.substr(1, tag - 1) + extension);
}

}  // namespace microrelief
