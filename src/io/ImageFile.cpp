#include "microrelief/io/ImageFile.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <cstddef>
#include <limits>
#include <optional>
#include <vector>

#include "io/CheckedImageInput.h"
#include "microrelief/core/Error.h"

namespace microrelief {

namespace {

// OpenImageIO 2.4's PNG, BMP and TGA writers do not check what fwrite returns, and their
// close() cannot tell: on a full disk they report success over a cut-off file; libjpeg's
// error handler prints its own message and exits the process. So no writer
// is given a file to open: each writes through this proxy into a StagedFile, which checks
// every write and keeps the first failure, and StagedFile::finish reports it. The proxy
// tells the writer every write succeeded, so that no writer takes an error path of its
// own (libjpeg's exit among them); what it writes after a failure goes nowhere. Streamed
// rather than encoded into memory first (OpenImageIO's IOVecOutput would also do): a
// 16384 x 16384 map costs no second copy. Byte for byte what each writer puts in a file
// of its own (compared for every format checkImageExtension lets through).
class StagedFileProxy final : public OIIO::Filesystem::IOProxy {
public:
    explicit StagedFileProxy(StagedFile& file)
        : IOProxy(file.target().string(), IOProxy::Write), file_(file) {}
    const char* proxytype() const override { return "microrelief::StagedFile"; }
    size_t write(const void* data, size_t size) override {
        const size_t written = pwrite(data, size, m_pos);
        m_pos += static_cast<int64_t>(written);
        return written;
    }
    size_t pwrite(const void* data, size_t size, int64_t offset) override {
        file_.writeAt(data, size, static_cast<std::uint64_t>(offset));
        return size;
    }
    size_t read(void* data, size_t size) override {
        const size_t got = pread(data, size, m_pos);
        m_pos += static_cast<int64_t>(got);
        return got;
    }
    size_t pread(void* data, size_t size, int64_t offset) override {
        return file_.readAt(data, size, static_cast<std::uint64_t>(offset));
    }
    size_t size() const override { return static_cast<size_t>(file_.size()); }

private:
    StagedFile& file_;
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
    // Without a proxy the writer opens the file itself, and some report success on a full
    // disk: a format whose every byte cannot be checked is not written.
    if (!output->supports("ioproxy")) {
        throwBadInput(file.string() + ": OpenImageIO's " + output->format_name() +
                      " writer cannot write through a checked stream, so a full disk could go "
                      "unnoticed (write .png, .exr, .tif, .jpg, .bmp or .tga)");
    }
}

void ImageWriteBatch::write(const std::filesystem::path& file, const ImageData& image) {
    StagedFile& staged = files_.stage(file);
    auto output = OIIO::ImageOutput::create(file.string());
    if (!output) throwBadInput(file.string() + ": no image format for this extension");
    const OIIO::TypeDesc type = image.type == PixelType::Float    ? OIIO::TypeDesc::FLOAT
                                : image.type == PixelType::UInt16 ? OIIO::TypeDesc::UINT16
                                                                  : OIIO::TypeDesc::UINT8;
    OIIO::ImageSpec spec(image.width, image.height, image.channels, type);
    if (!image.channelNames.empty()) spec.channelnames = image.channelNames;
    const bool namedAlpha = image.channelNames.size() > 3 && image.channelNames[3] == "A";
    if (image.channels == 4 || namedAlpha) spec.alpha_channel = 3;
    StagedFileProxy proxy(staged);
    const bool ok = output->set_ioproxy(&proxy) && output->open(file.string(), spec) &&
                    output->write_image(type, image.pixels) && output->close();
    const std::string reason = ok ? std::string() : oneLine(output->geterror());
    output.reset();  // a writer's destructor may still write (through the proxy)
    // The proxy's failure first (finish() throws it): it is what went wrong, whatever the
    // writer made of it.
    if (!ok && !staged.failed()) {
        throwRuntime(file.string() + ": cannot write (" +
                     (reason.empty() ? "unknown error" : reason) + ")");
    }
    staged.finish();
}

void checkOutputTargets(const std::vector<std::filesystem::path>& files) {
    std::vector<FileIdentity> identities;
    for (std::size_t k = 0; k < files.size(); ++k) {
        std::error_code ec;
        checkReplaceable(files[k]);
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

std::optional<std::string> imageFileDefect(const std::filesystem::path& file) {
    try {
        // The checks every input gets (a regular file; a PNG's chunks, CRCs and inflated
        // data; an OpenEXR header within the file), then what a decoder misses.
        auto input = openCheckedImage(file, std::numeric_limits<int>::max(), "an image");
        std::vector<std::byte> pixels(input->spec().image_bytes(true));
        if (!input->read_image(0, 0, 0, -1, OIIO::TypeUnknown, pixels.data())) {
            const std::string reason = oneLine(input->geterror());
            return "cannot decode every pixel (" + (reason.empty() ? "unknown error" : reason) +
                   ")";
        }
        return std::nullopt;
    } catch (const Error& e) {
        // openCheckedImage's messages name the file first; the caller names it again.
        const std::string message = e.what(), name = file.string() + ": ";
        return message.rfind(name, 0) == 0 ? message.substr(name.size()) : message;
    } catch (const std::bad_alloc&) {
        return "too large to decode in memory";
    }
}

}  // namespace microrelief
