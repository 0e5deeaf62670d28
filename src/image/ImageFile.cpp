#include "image/ImageFile.h"

#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>

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
    const std::string name = "." + target.stem().string() + ".tmp-" + std::to_string(::getpid()) + "-" +
                             std::to_string(counter++) + target.extension().string();
    return target.parent_path() / name;
}

}  // namespace

void checkImageExtension(const std::filesystem::path& file) {
    const std::string extension = file.extension().string();
    if (extension.empty()) throwBadInput(file.string() + ": no extension to choose an image format by");
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
        if (ec) throwRuntime(file.string() + ": cannot create the folder " + folder.string() + " (" + ec.message() + ")");
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
    const bool ok =
        output->open(temporary.string(), spec) && output->write_image(type, image.pixels) && output->close();
    if (!ok) {
        const std::string reason = oneLine(output->geterror());
        throwRuntime(file.string() + ": cannot write (" + (reason.empty() ? "unknown error" : reason) + ")");
    }
}

void ImageWriteBatch::commit() {
    for (const Staged& s : staged_) {
        std::error_code ec;
        std::filesystem::rename(s.temporary, s.target, ec);
        if (ec) throwRuntime(s.target.string() + ": cannot move the finished file into place (" + ec.message() + ")");
    }
    staged_.clear();
}

void writeImageAtomically(const std::filesystem::path& file, const ImageData& image) {
    ImageWriteBatch batch;
    batch.write(file, image);
    batch.commit();
}

}  // namespace microrelief
