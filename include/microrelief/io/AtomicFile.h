// Writing files whole or not at all (the microrelief::io component), for every file the
// programs write: pictures, AOVs, maps, the bundler's GLSL, the benchmark's reports
// (docs/reliability-writes.md). A write is done only when every byte is on disk:
//
//   - each file is written to a new temporary file beside its target, made with O_EXCL
//     (never a file that is there, not even a user's "<target>.tmp");
//   - every write(2) is checked, and the first failure (ENOSPC, EFBIG under `ulimit -f`,
//     EIO) sticks: later writes are not tried, and finish() reports it;
//   - finish() flushes the file to the disk (fsync), compares the size the file system
//     reports with the extent the writes asked for, and checks close(2);
//   - commit() renames the temporaries over their targets and then syncs the folders,
//     so the new names are on disk too; a folder or other non-regular file at a target
//     is refused, never moved away;
//   - whatever was not committed is removed: on errors, on destruction, and on SIGINT,
//     SIGTERM and SIGHUP (a handler undoes every unfinished batch of the process from a
//     table of fixed buffers, async-signal-safe, and the process then dies of the
//     signal). SIGXFSZ is ignored, so that a write past `ulimit -f` fails with EFBIG
//     and is reported, instead of killing the process over a half-written temporary.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace microrelief {

// A new file being written beside its target: "<folder>/.<stem>.tmp-<pid>-<n><ext>",
// hidden, unique (made with O_EXCL; a name taken is skipped) and keeping the extension.
class StagedFile {
public:
    // Creates the temporary. Throws Error(Runtime) naming the target.
    explicit StagedFile(const std::filesystem::path& target);
    ~StagedFile();  // removes the temporary unless it was renamed into place
    StagedFile(const StagedFile&) = delete;
    StagedFile& operator=(const StagedFile&) = delete;

    // Writes every byte at `offset` or records why not; after a failure it does nothing.
    // A writer that ignores what it is told still cannot make a partial file pass:
    // finish() throws the first failure.
    void writeAt(const void* data, std::size_t size, std::uint64_t offset);
    void write(std::string_view bytes) { writeAt(bytes.data(), bytes.size(), size_); }
    // What is there, for writers that read back what they wrote (TIFF may).
    std::size_t readAt(void* data, std::size_t size, std::uint64_t offset) const;
    // The end of the furthest write asked for: the file's size when every write succeeds.
    std::uint64_t size() const { return size_; }
    bool failed() const { return error_ != 0; }

    // Every write succeeded, fsync, the size on disk is size(), close: or Error(Runtime)
    // "<target>: cannot write (<reason>)".
    void finish();

    const std::filesystem::path& target() const { return target_; }
    const std::filesystem::path& temporary() const { return temporary_; }
    bool finished() const { return finished_; }
    // After the temporary became the target: nothing left to remove.
    void renamed();

private:
    [[noreturn]] void fail(int error) const;
    std::filesystem::path target_, temporary_;
    int fd_ = -1;
    int slot_ = -1;  // in the signal handler's table: removes the temporary
    std::uint64_t size_ = 0;
    int error_ = 0;  // the first failed write's errno
    bool finished_ = false;
};

// A set of files written together: stage() makes each one's temporary, commit() renames
// them all into place, restoring the old files if any rename fails. Whatever was not
// committed is removed on destruction, folders stage() made included, so a failed run
// leaves no new or changed file and no new folder.
class FileWriteBatch {
public:
    FileWriteBatch() = default;
    FileWriteBatch(const FileWriteBatch&) = delete;
    FileWriteBatch& operator=(const FileWriteBatch&) = delete;
    ~FileWriteBatch();

    // Creates the target's folder if needed. Throws Error(BadInput) when the target is a
    // folder or another non-regular file, Error(Runtime) naming it when it cannot be made.
    // The file stays valid until the batch is destroyed; finish() it before commit().
    StagedFile& stage(const std::filesystem::path& target);
    // stage, write and finish in one.
    void add(const std::filesystem::path& target, std::string_view bytes);
    void commit();

private:
    void createFolders(const std::filesystem::path& file);
    std::vector<std::unique_ptr<StagedFile>> staged_;
    std::vector<std::pair<std::filesystem::path, int>> createdFolders_;  // outermost first
    bool committed_ = false;
};

// One file, whole or not at all. Throws Error as FileWriteBatch does.
void writeFileAtomically(const std::filesystem::path& file, std::string_view bytes);

// Throws Error(BadInput) "<file>: is a directory" (or "is not a regular file": a FIFO, a
// device) when something other than a regular file is at `file` (links followed), which
// a write would move away or never finish.
void checkReplaceable(const std::filesystem::path& file);

// Where a file lies, to tell two names of one file apart from two files: its path
// resolved (std::filesystem::weakly_canonical: symbolic links and ".." followed as far as
// the path exists) and, where it exists, its device and inode (hard links, bind mounts).
class FileIdentity {
public:
    explicit FileIdentity(const std::filesystem::path& file);
    bool sameFileAs(const FileIdentity& other) const;

private:
    std::filesystem::path resolved_;
    std::optional<std::pair<std::uint64_t, std::uint64_t>> inode_;  // st_dev, st_ino
};

// A file a program reads or writes, with what the program calls it in a message: its flag
// ("--height"), or where it was named ("cams.csv: line 4 (frame 2): --height").
struct NamedFile {
    std::filesystem::path file;
    std::string what;
};

// Before anything is written: no output is one of the files the run reads (FileIdentity:
// the same path, or the same inode through a link), which writing it would replace. Throws
// Error(BadInput) "--out c.png: the same file as --height c.png, which this run reads;
// writing it would replace it (name another file)".
void checkOutputsAreNotInputs(const std::vector<NamedFile>& outputs,
                              const std::vector<NamedFile>& inputs);

// The target whose temporary `file` is, when it is one of StagedFile's temporaries and
// the process that wrote it is gone: a writer killed before its rename (SIGKILL, a power
// cut) leaves it behind. Else nothing (not a temporary, or one that a running process on
// this machine may still rename).
std::optional<std::filesystem::path> abandonedTemporaryTarget(const std::filesystem::path& file);

// write(2) until every byte is written, retrying EINTR; false with errno set otherwise
// (a short write followed by a failure reports the failure). For what is written in place:
// the batch manifest, appended to, and standard output; files go through StagedFile.
bool writeAll(int fd, const void* data, std::size_t size);

}  // namespace microrelief
