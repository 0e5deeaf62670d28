#include "image/ImageFile.h"

#include <OpenImageIO/imageio.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <vector>

#include "core/Error.h"

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
    for (const Staged& s : staged_) {
        std::error_code ignored;
        std::filesystem::remove(s.temporary, ignored);
    }
}

void ImageWriteBatch::write(const std::filesystem::path& file, const ImageData& image) {
    std::error_code ec;
    const std::filesystem::path folder = file.parent_path();
    if (!folder.empty()) {
        std::filesystem::create_directories(folder, ec);
        if (ec)
            throwRuntime(file.string() + ": cannot create the folder " + folder.string() + " (" +
                         ec.message() + ")");
    }
    const std::filesystem::path temporary = temporaryBeside(file);
    staged_.push_back({file, temporary});

    auto output = OIIO::ImageOutput::create(file.string());
    if (!output) throwBadInput(file.string() + ": no image format for this extension");
    const OIIO::TypeDesc type = image.type == PixelType::Float    ? OIIO::TypeDesc::FLOAT
                                : image.type == PixelType::UInt16 ? OIIO::TypeDesc::UINT16
                                                                  : OIIO::TypeDesc::UINT8;
    OIIO::ImageSpec spec(image.width, image.height, image.channels, type);
    if (!image.channelNames.empty()) spec.channelnames = image.channelNames;
    if (image.channels == 4) spec.alpha_channel = 3;
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
    // undone: either every target is the new file, or every target is as it was.
    struct Moved {
        std::filesystem::path target, backup;
        bool replaced = false;
    };
    std::vector<Moved> moved;
    auto rollBack = [&moved] {
        for (auto it = moved.rbegin(); it != moved.rend(); ++it) {
            std::error_code ignored;
            if (it->replaced) std::filesystem::remove(it->target, ignored);
            if (!it->backup.empty()) std::filesystem::rename(it->backup, it->target, ignored);
        }
    };
    for (const Staged& s : staged_) {
        Moved m{s.target, {}};
        std::error_code ec;
        if (std::filesystem::exists(s.target, ec)) {
            m.backup = temporaryBeside(s.target);
            std::filesystem::rename(s.target, m.backup, ec);
            if (ec) {
                rollBack();
                throwRuntime(s.target.string() + ": cannot replace the existing file (" +
                             ec.message() + ")");
            }
        }
        moved.push_back(m);
        std::filesystem::rename(s.temporary, s.target, ec);
        if (ec) {
            rollBack();
            throwRuntime(s.target.string() + ": cannot move the finished file into place (" +
                         ec.message() + ")");
        }
        moved.back().replaced = true;
    }
    for (const Moved& m : moved) {
        std::error_code ignored;
        if (!m.backup.empty()) std::filesystem::remove(m.backup, ignored);
    }
    staged_.clear();
}

void checkOutputTargets(const std::vector<std::filesystem::path>& files) {
    for (std::size_t k = 0; k < files.size(); ++k) {
        std::error_code ec;
        if (std::filesystem::is_directory(files[k], ec))
            throwBadInput(files[k].string() + ": is a directory");
        checkImageExtension(files[k]);
        for (std::size_t other = 0; other < k; ++other) {
            if (files[k].lexically_normal() == files[other].lexically_normal()) {
                throwBadInput(files[k].string() + ": given for two outputs");
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
