#include "microrelief/io/AtomicFile.h"

#include <fcntl.h>
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
#include <fstream>
#include <iterator>
#include <mutex>
#include <set>
#include <string>

#include "microrelief/core/Error.h"

namespace microrelief {

namespace {

std::string systemMessage(int error) {
    return std::strerror(error);
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
            // Past `ulimit -f` the kernel sends SIGXFSZ, whose default kills the process
            // with the temporary half written and nothing said; ignored, the write fails
            // with EFBIG, which every write here checks. A handler the program set stays.
            struct sigaction previous {};
            if (::sigaction(SIGXFSZ, nullptr, &previous) == 0 && previous.sa_handler == SIG_DFL)
                std::signal(SIGXFSZ, SIG_IGN);
        });
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

    std::array<Slot, kSlots> slots_;
};

// ".<stem>.tmp-<pid>-<n><extension>": hidden, unique per process and call, and keeping
// the extension (abandonedTemporaryTarget reads the target back from it).
std::filesystem::path temporaryBeside(const std::filesystem::path& target) {
    static std::atomic<int> counter{0};
    const std::string name = "." + target.stem().string() + ".tmp-" + std::to_string(::getpid()) +
                             "-" + std::to_string(counter++) + target.extension().string();
    return target.parent_path() / name;
}

// fsync of a folder, so that a rename or a new name in it is on disk. 0, or the errno;
// a file system that cannot sync folders (EINVAL) has nothing more to do.
int syncFolder(const std::filesystem::path& folder) {
    const std::filesystem::path path = folder.empty() ? "." : folder;
    const int fd = ::open(path.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return errno;
    const int error = ::fsync(fd) == 0 || errno == EINVAL ? 0 : errno;
    ::close(fd);
    return error;
}

}  // namespace

bool writeAll(int fd, const void* data, std::size_t size) {
    CleanupRegistry::instance().installHandlers();  // SIGXFSZ ignored: EFBIG is reported
    const char* bytes = static_cast<const char*>(data);
    while (size > 0) {
        const ssize_t n = ::write(fd, bytes, size);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            if (n == 0) errno = ENOSPC;
            return false;
        }
        bytes += n;
        size -= static_cast<std::size_t>(n);
    }
    return true;
}

void checkReplaceable(const std::filesystem::path& file) {
    std::error_code ec;
    const std::filesystem::file_status status = std::filesystem::status(file, ec);
    if (status.type() == std::filesystem::file_type::directory)
        throwBadInput(file.string() + ": is a directory");
    if (std::filesystem::exists(status) && status.type() != std::filesystem::file_type::regular)
        throwBadInput(file.string() + ": is not a regular file (a device, FIFO or socket)");
}

FileIdentity::FileIdentity(const std::filesystem::path& file) {
    std::error_code ec;
    resolved_ = std::filesystem::weakly_canonical(std::filesystem::absolute(file, ec), ec);
    if (ec) resolved_ = std::filesystem::absolute(file, ec).lexically_normal();
    struct stat info {};
    if (::stat(file.c_str(), &info) == 0)
        inode_ = std::make_pair(static_cast<std::uint64_t>(info.st_dev),
                                static_cast<std::uint64_t>(info.st_ino));
}

bool FileIdentity::sameFileAs(const FileIdentity& other) const {
    return resolved_ == other.resolved_ || (inode_ && other.inode_ && *inode_ == *other.inode_);
}

void checkOutputsAreNotInputs(const std::vector<NamedFile>& outputs,
                              const std::vector<NamedFile>& inputs) {
    if (outputs.empty() || inputs.empty()) return;
    std::vector<FileIdentity> read;
    for (const NamedFile& input : inputs) read.emplace_back(input.file);
    const auto named = [](const NamedFile& f) {
        return f.what.empty() ? f.file.string() : f.what + " " + f.file.string();
    };
    for (const NamedFile& output : outputs) {
        const FileIdentity written(output.file);
        for (std::size_t k = 0; k < inputs.size(); ++k) {
            if (written.sameFileAs(read[k])) {
                throwBadInput(named(output) + ": the same file as " + named(inputs[k]) +
                              ", which this run reads; writing it would replace it (name "
                              "another file)");
            }
        }
    }
}

StagedFile::StagedFile(const std::filesystem::path& target) : target_(target) {
    CleanupRegistry& registry = CleanupRegistry::instance();
    for (;;) {
        temporary_ = temporaryBeside(target);
        // A name that is there (left by a dead process with this pid) is skipped, not
        // registered: a signal must never remove a file this process did not make.
        struct stat info {};
        if (::lstat(temporary_.c_str(), &info) == 0) continue;
        // Registered before the file exists: a signal from here on removes it.
        slot_ = registry.add(CleanupRegistry::Action::Unlink, temporary_);
        fd_ = ::open(temporary_.c_str(), O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd_ >= 0) return;
        const int error = errno;
        registry.remove(slot_);
        slot_ = -1;
        if (error != EEXIST) fail(error);
    }
}

StagedFile::~StagedFile() {
    if (fd_ >= 0) ::close(fd_);
    if (!temporary_.empty()) ::unlink(temporary_.c_str());
    CleanupRegistry::instance().remove(slot_);
}

void StagedFile::fail(int error) const {
    throwRuntime(target_.string() + ": cannot write (" + systemMessage(error) + ")");
}

void StagedFile::writeAt(const void* data, std::size_t size, std::uint64_t offset) {
    size_ = std::max(size_, offset + size);  // asked for, whether or not it gets there
    if (error_ != 0 || fd_ < 0) return;
    const char* bytes = static_cast<const char*>(data);
    while (size > 0) {
        const ssize_t n = ::pwrite(fd_, bytes, size, static_cast<off_t>(offset));
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            error_ = n < 0 ? errno : ENOSPC;
            return;
        }
        bytes += n;
        size -= static_cast<std::size_t>(n);
        offset += static_cast<std::uint64_t>(n);
    }
}

std::size_t StagedFile::readAt(void* data, std::size_t size, std::uint64_t offset) const {
    if (fd_ < 0) return 0;
    const ssize_t n = ::pread(fd_, data, size, static_cast<off_t>(offset));
    return n > 0 ? static_cast<std::size_t>(n) : 0;
}

void StagedFile::finish() {
    if (finished_) return;
    if (error_ != 0) fail(error_);
    if (::fsync(fd_) != 0) fail(errno);
    // What the file system holds against what the writer asked for: a second, independent
    // check that every write got there, should a failure ever go unrecorded.
    struct stat info {};
    if (::fstat(fd_, &info) != 0) fail(errno);
    if (static_cast<std::uint64_t>(info.st_size) != size_) {
        throwRuntime(target_.string() + ": cannot write (the file holds " +
                     std::to_string(info.st_size) + " of the " + std::to_string(size_) +
                     " bytes written)");
    }
    const int fd = fd_;
    fd_ = -1;
    if (::close(fd) != 0) fail(errno);
    finished_ = true;
}

void StagedFile::renamed() {
    temporary_.clear();
    CleanupRegistry::instance().remove(slot_);
    slot_ = -1;
}

FileWriteBatch::~FileWriteBatch() {
    staged_.clear();  // removes the temporaries not renamed
    // The folders this batch made, deepest first; remove() leaves a folder that is not
    // empty (another program's file, or an earlier committed batch's).
    CleanupRegistry& registry = CleanupRegistry::instance();
    for (auto it = createdFolders_.rbegin(); it != createdFolders_.rend(); ++it) {
        std::error_code ignored;
        if (!committed_) std::filesystem::remove(it->first, ignored);
        registry.remove(it->second);
    }
}

void FileWriteBatch::createFolders(const std::filesystem::path& file) {
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

StagedFile& FileWriteBatch::stage(const std::filesystem::path& target) {
    checkReplaceable(target);
    createFolders(target);
    staged_.push_back(std::make_unique<StagedFile>(target));
    return *staged_.back();
}

void FileWriteBatch::add(const std::filesystem::path& target, std::string_view bytes) {
    StagedFile& file = stage(target);
    file.write(bytes);
    file.finish();
}

void FileWriteBatch::commit() {
    for (const auto& s : staged_) {
        s->finish();
        // Again, just before the rename: a folder made there since stage() must not be
        // moved aside and replaced by a file.
        checkReplaceable(s->target());
    }
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
    for (const auto& s : staged_) {
        Moved m{s->target(), {}};
        std::error_code ec;
        if (std::filesystem::exists(std::filesystem::symlink_status(s->target(), ec))) {
            m.backup = temporaryBeside(s->target());
            m.slot = registry.add(Action::Restore, m.backup, s->target());
            std::filesystem::rename(s->target(), m.backup, ec);
            if (ec) {
                registry.remove(m.slot);
                rollBack();
                throwRuntime(s->target().string() + ": cannot replace the existing file (" +
                             ec.message() + ")");
            }
        } else {
            m.slot = registry.add(Action::Unlink, s->target());
        }
        moved.push_back(m);
        std::filesystem::rename(s->temporary(), s->target(), ec);
        if (ec) {
            rollBack();
            throwRuntime(s->target().string() + ": cannot move the finished file into place (" +
                         ec.message() + ")");
        }
        s->renamed();  // the temporary is the target now
        moved.back().replaced = true;
    }
    // Every target is new and whole: from here a signal only removes the old files moved
    // aside, and leaves the new ones, which a reader may already have seen.
    for (Moved& m : moved) {
        registry.remove(m.slot);
        m.slot = m.backup.empty() ? -1 : registry.add(Action::Unlink, m.backup);
    }
    // The renames on disk: each target's folder, and the folder above each folder this
    // batch made (its new name). Until then the old files stay, to be put back if it fails.
    std::set<std::filesystem::path> folders;
    for (const auto& s : staged_) folders.insert(s->target().parent_path());
    for (const auto& [folder, slot] : createdFolders_) folders.insert(folder.parent_path());
    for (const std::filesystem::path& folder : folders) {
        if (const int error = syncFolder(folder); error != 0) {
            rollBack();
            throwRuntime(staged_.front()->target().string() + ": cannot write (syncing " +
                         (folder.empty() ? std::string(".") : folder.string()) + ": " +
                         systemMessage(error) + ")");
        }
    }
    for (const Moved& m : moved) {
        std::error_code ignored;
        if (!m.backup.empty()) std::filesystem::remove(m.backup, ignored);
        registry.remove(m.slot);
    }
    staged_.clear();
    committed_ = true;
}

void writeFileAtomically(const std::filesystem::path& file, std::string_view bytes) {
    FileWriteBatch batch;
    batch.add(file, bytes);
    batch.commit();
}

namespace {

// Whether process `pid` has exited and waits to be reaped: state 'Z' in /proc/PID/stat,
// the field after the command's closing parenthesis (the command may hold one itself).
// False where /proc cannot say (not Linux, or the process is gone).
bool isZombie(long pid) {
    std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
    const std::string line((std::istreambuf_iterator<char>(stat)),
                           std::istreambuf_iterator<char>());
    const std::size_t close = line.rfind(')');
    return close != std::string::npos && close + 2 < line.size() && line[close + 2] == 'Z';
}

}  // namespace

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
    // A process that still runs may yet rename it (kill with signal 0 only asks; a zombie,
    // dead and not yet reaped by its parent, answers too but renames nothing).
    if (pid == ::getpid() ||
        ((::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) && !isZombie(pid)))
        return std::nullopt;
    return file.parent_path() / (name.substr(1, tag - 1) + extension);
}

}  // namespace microrelief
