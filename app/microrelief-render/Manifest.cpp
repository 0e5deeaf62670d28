#include "Manifest.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <fstream>

#include "Csv.h"
#include "microrelief/core/Error.h"
#include "microrelief/io/AtomicFile.h"

namespace microrelief {

namespace {

std::string systemError() {
    return std::strerror(errno);
}

}  // namespace

std::string manifestLine(const ManifestRow& row) {
    char ms[32];
    std::snprintf(ms, sizeof ms, "%.1f", row.ms);
    return std::to_string(row.frame) + "," + csvField(row.file) + "," + csvField(row.camera) + "," +
           ms + "," + csvField(row.status) + "\n";
}

ManifestWriter::ManifestWriter(const std::filesystem::path& file) : file_(file) {
    std::error_code ec;
    if (!file.parent_path().empty()) {
        std::filesystem::create_directories(file.parent_path(), ec);
        if (ec) throwRuntime(file.string() + ": cannot create its folder (" + ec.message() + ")");
    }
    if (std::filesystem::exists(file, ec) && !std::filesystem::is_regular_file(file, ec))
        throwBadInput(file.string() + ": the manifest is not a regular file");
    // Made here or there before: a new manifest whose header cannot be written goes again.
    bool made = true;
    fd_ = ::open(file.c_str(), O_RDWR | O_CREAT | O_EXCL | O_APPEND | O_CLOEXEC, 0644);
    if (fd_ < 0 && errno == EEXIST) {
        made = false;
        fd_ = ::open(file.c_str(), O_RDWR | O_APPEND | O_CLOEXEC);
    }
    if (fd_ < 0) throwRuntime(file.string() + ": cannot open the manifest (" + systemError() + ")");
    struct stat info {};
    if (::fstat(fd_, &info) != 0 || !S_ISREG(info.st_mode)) {
        ::close(fd_);
        fd_ = -1;
        throwBadInput(file.string() + ": the manifest is not a regular file");
    }
    if (info.st_size == 0) {
        try {
            append(std::string(kManifestHeader) + "\n");
        } catch (const Error&) {
            ::close(fd_);
            fd_ = -1;
            if (made) ::unlink(file.c_str());
            throw;
        }
        return;
    }
    // An existing manifest: ours (its header), and ending in a newline so that the next
    // row starts a line of its own even after a torn write.
    const std::size_t headerSize = std::strlen(kManifestHeader) + 1;
    std::string head(headerSize, '\0');
    const ssize_t got = ::pread(fd_, head.data(), head.size(), 0);
    if (got != static_cast<ssize_t>(head.size()) || head != std::string(kManifestHeader) + "\n") {
        ::close(fd_);
        fd_ = -1;
        throwBadInput(file.string() + ": exists and is not a manifest (its first line is not '" +
                      kManifestHeader + "')");
    }
    char last = '\n';
    if (::pread(fd_, &last, 1, info.st_size - 1) == 1 && last != '\n') {
        try {
            append("\n");
        } catch (const Error&) {
            ::close(fd_);
            fd_ = -1;
            throw;
        }
    }
}

ManifestWriter::~ManifestWriter() {
    if (fd_ >= 0) ::close(fd_);
}

void ManifestWriter::append(const std::string& text) {
    struct stat before {};
    const bool sized = ::fstat(fd_, &before) == 0;
    // On disk before the row counts: a frame is "rendered" once the disk says so.
    if (writeAll(fd_, text.data(), text.size()) && ::fdatasync(fd_) == 0) return;
    const std::string reason = systemError();
    // A row written in part comes off again: the manifest stays as it was, byte for byte.
    if (sized && ::ftruncate(fd_, before.st_size) != 0) {
        // Left torn: readManifest skips a line with no newline, and the next run ends it.
    }
    throwRuntime(file_.string() + ": cannot write (" + reason + ")");
}

void ManifestWriter::append(const ManifestRow& row) {
    append(manifestLine(row));
}

std::vector<ManifestRow> readManifest(const std::filesystem::path& file) {
    std::ifstream in(file);
    if (!in) throwBadInput(file.string() + ": cannot read the manifest");
    std::string line;
    if (!std::getline(in, line) || line != kManifestHeader)
        throwBadInput(file.string() + ": is not a manifest (no header '" +
                      std::string(kManifestHeader) + "')");
    std::vector<ManifestRow> rows;
    while (std::getline(in, line)) {
        if (in.eof()) break;  // no newline: a torn last line
        const auto fields = splitCsvLine(line);
        if (!fields || fields->size() != 5) continue;
        ManifestRow row;
        const std::string& frame = (*fields)[0];
        const auto [ptr, ec] =
            std::from_chars(frame.data(), frame.data() + frame.size(), row.frame);
        if (frame.empty() || ec != std::errc() || ptr != frame.data() + frame.size()) continue;
        row.file = (*fields)[1];
        row.camera = (*fields)[2];
        const std::string& ms = (*fields)[3];
        const auto msEnd = std::from_chars(ms.data(), ms.data() + ms.size(), row.ms);
        if (ms.empty() || msEnd.ec != std::errc() || msEnd.ptr != ms.data() + ms.size()) continue;
        row.status = (*fields)[4];
        rows.push_back(row);
    }
    return rows;
}

}  // namespace microrelief
