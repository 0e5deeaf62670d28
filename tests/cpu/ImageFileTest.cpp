// Writing outputs whole or not at all (scene-and-cli.md, "Outputs"; issues 15 and 25): the
// same file in two spellings refused up front, a failed batch taking away the folders it
// made, a signal in the middle of a batch leaving nothing behind, every format failing
// whole past a file size limit (a full disk without privileges), a user's files never
// touched, and cut-off files of every format found before --skip-existing keeps them.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <csignal>
#include <cstdint>
#include <random>
#include <vector>

#include "TestSupport.h"
#include "microrelief/core/Error.h"
#include "microrelief/io/ImageFile.h"
#include "microrelief/io/AtomicFile.h"

using namespace microrelief;

namespace {

std::vector<std::string> namesIn(const std::filesystem::path& folder) {
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(folder))
        names.push_back(e.path().filename());
    std::sort(names.begin(), names.end());
    return names;
}

const std::vector<std::uint8_t> kPixels(4 * 4 * 3, 128);
const ImageData kImage{4, 4, 3, PixelType::UInt8, kPixels.data(), {}};

void expectRefusedAsOneFile(const std::filesystem::path& a, const std::filesystem::path& b) {
    try {
        checkOutputTargets({a, b});
        ADD_FAILURE() << a << " and " << b << " were not refused";
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::BadInput);
        EXPECT_NE(std::string(e.what()).find("given for two outputs"), std::string::npos)
            << e.what();
    }
}

}  // namespace

TEST(OutputTargets, OneFileInTwoSpellingsIsRefused) {
    test::ScratchDir dir;
    // ".." through a folder that does not exist yet (the batch would make it).
    expectRefusedAsOneFile(dir / "x.exr", dir / "o/../x.exr");
    // A symbolic link to the folder, and a relative spelling of an absolute path.
    std::filesystem::create_directory_symlink(dir.path(), dir / "link");
    expectRefusedAsOneFile(dir / "x.exr", dir / "link/x.exr");
    // A hard link: another name, the same inode.
    test::writeBytes(dir / "x.exr", {'o', 'l', 'd'});
    std::filesystem::create_hard_link(dir / "x.exr", dir / "hard.exr");
    expectRefusedAsOneFile(dir / "x.exr", dir / "hard.exr");
    // Two files that are not one are fine.
    EXPECT_NO_THROW(checkOutputTargets({dir / "x.exr", dir / "y.exr"}));
}

TEST(OutputTargets, AFolderThatIsAFileIsRefusedUpFront) {
    test::ScratchDir dir;
    test::writeBytes(dir / "file.txt", {'x'});
    EXPECT_THROW(checkOutputTargets({dir / "file.txt/deep/x.png"}), Error);
}

// OpenImageIO writers that cannot write through a proxy open the file themselves, where
// no write can be checked: their formats are refused before any work.
TEST(OutputTargets, FormatsWhoseWritesCannotBeCheckedAreRefused) {
    test::ScratchDir dir;
    for (const char* name : {"x.sgi", "x.ico", "x.rla"}) {
        try {
            checkOutputTargets({dir / name});
            ADD_FAILURE() << name << " was not refused";
        } catch (const Error& e) {
            EXPECT_EQ(e.kind(), ErrorKind::BadInput);
            EXPECT_NE(std::string(e.what()).find("cannot write through a checked stream"),
                      std::string::npos)
                << e.what();
        }
    }
}

TEST(ImageWriteBatch, AFailedBatchRemovesTheFoldersItMade) {
    test::ScratchDir dir;
    test::writeBytes(dir / "file.txt", {'x'});
    std::filesystem::create_directory(dir / "old");
    {
        ImageWriteBatch batch;
        batch.write(dir / "new/deep/a.png", kImage);
        batch.write(dir / "old/more/b.png", kImage);
        EXPECT_TRUE(std::filesystem::exists(dir / "new/deep"));
        EXPECT_THROW(batch.write(dir / "file.txt/c.png", kImage), Error);
    }
    EXPECT_EQ(namesIn(dir.path()), (std::vector<std::string>{"file.txt", "old"}));
    EXPECT_TRUE(namesIn(dir / "old").empty()) << "the folder that was there stays, empty";
}

TEST(ImageWriteBatch, ACommittedBatchKeepsItsFolders) {
    test::ScratchDir dir;
    {
        ImageWriteBatch batch;
        batch.write(dir / "new/a.png", kImage);
        batch.commit();
    }
    EXPECT_EQ(namesIn(dir / "new"), (std::vector<std::string>{"a.png"}));
}

// The handler, in a child process (forked, so it writes into this test's folder) that writes half a
// batch and then gets SIGTERM (or SIGINT): it dies of the signal and leaves no temporary and no
// folder.
TEST(ImageWriteBatchDeathTest, ASignalInTheMiddleOfABatchLeavesNothing) {
    for (int signal : {SIGTERM, SIGINT}) {
        test::ScratchDir dir;
        test::writeBytes(dir / "keep.png", {'o', 'l', 'd'});
        EXPECT_EXIT(
            {
                ImageWriteBatch batch;
                batch.write(dir / "new/deep/a.png", kImage);
                batch.write(dir / "keep.png", kImage);
                std::raise(signal);
            },
            ::testing::KilledBySignal(signal), "");
        EXPECT_EQ(namesIn(dir.path()), (std::vector<std::string>{"keep.png"}));
        EXPECT_EQ(test::readBytes(dir / "keep.png"), (std::vector<std::uint8_t>{'o', 'l', 'd'}));
    }
}

namespace {

// Noise, which no format compresses much: every file below is larger than the limit.
std::vector<std::uint8_t> noisePixels(int width, int height) {
    std::mt19937 random(25);
    std::vector<std::uint8_t> pixels(static_cast<std::size_t>(width) * height * 3);
    for (std::uint8_t& p : pixels) p = static_cast<std::uint8_t>(random());
    return pixels;
}

// Every format checkImageExtension lets through (the writers with a proxy).
const char* const kFormats[] = {"png", "bmp",  "tga", "jpg", "tif", "exr", "hdr",
                                "ppm", "webp", "dpx", "jp2", "iff", "gif"};

// In a death test's child: writes `image` under the limit and exits 0 when that succeeds,
// 1 (printing the message) for Error(Runtime), 2 for another Error.
[[noreturn]] void writeUnderFileSizeLimit(const std::filesystem::path& file, const ImageData& image,
                                          rlim_t bytes) {
    const rlimit limit{bytes, bytes};
    if (::setrlimit(RLIMIT_FSIZE, &limit) != 0) std::_Exit(3);
    try {
        writeImageAtomically(file, image);
    } catch (const Error& e) {
        std::fprintf(stderr, "%s\n", e.what());
        std::_Exit(e.kind() == ErrorKind::Runtime ? 1 : 2);
    }
    std::_Exit(0);
}

}  // namespace

// Past a file size limit (RLIMIT_FSIZE, `ulimit -f`), in a child process: each format's
// write fails with the reason, and leaves the old file and no temporary. SIGXFSZ keeps its
// default here, which would kill the child: the writer ignores it itself.
TEST(ImageWriteBatchDeathTest, EveryFormatFailsWholePastAFileSizeLimit) {
    // The child is forked: thread pools of the parent (OpenEXR's, OpenImageIO's) are not
    // there, and a writer waiting for them would wait forever. Each writes in the calling
    // thread while this test runs (OpenEXR's pool is emptied at its next write, here).
    int threads = 0, exrThreads = 0;
    OIIO::getattribute("threads", threads);
    OIIO::getattribute("exr_threads", exrThreads);
    OIIO::attribute("threads", 1);
    OIIO::attribute("exr_threads", -1);
    const std::vector<std::uint8_t> pixels = noisePixels(128, 128);
    const ImageData image{128, 128, 3, PixelType::UInt8, pixels.data(), {}};
    constexpr rlim_t kLimit = 8192;
    for (const char* format : kFormats) {
        SCOPED_TRACE(format);
        test::ScratchDir dir;
        const auto file = dir / (std::string("x.") + format);
        writeImageAtomically(file, image);  // the premise: whole, larger than the limit
        ASSERT_GT(std::filesystem::file_size(file), kLimit);
        test::writeBytes(file, {'o', 'l', 'd'});
        EXPECT_EXIT(writeUnderFileSizeLimit(file, image, kLimit), ::testing::ExitedWithCode(1),
                    file.string() + ": cannot write \\(File too large\\)");
        EXPECT_EQ(test::readBytes(file), (std::vector<std::uint8_t>{'o', 'l', 'd'}));
        EXPECT_EQ(namesIn(dir.path()), std::vector<std::string>{file.filename().string()});
    }
    OIIO::attribute("threads", threads);
    OIIO::attribute("exr_threads", exrThreads);
}

// The temporary is a new file (O_EXCL), so no file of the user's is written through: not
// "<target>.tmp", which the bundler once used, nor one named as a temporary of this very
// process (a name taken is skipped).
TEST(AtomicFileDeathTest, NoFileOfTheUsersIsWrittenThrough) {
    test::ScratchDir dir;
    const auto target = dir / "x.txt";
    test::writeBytes(dir / "x.txt.tmp", {'m', 'i', 'n', 'e'});
    EXPECT_EXIT(
        {
            // In a child, whose pid names its temporaries: every name it could take next.
            const std::string prefix = ".x.tmp-" + std::to_string(::getpid()) + "-";
            for (int n = 0; n < 4000; ++n)
                test::writeBytes(dir / (prefix + std::to_string(n) + ".txt"), {'m', 'i', 'n', 'e'});
            writeFileAtomically(target, "new\n");
            for (int n = 0; n < 4000; ++n) {
                if (test::readText(dir / (prefix + std::to_string(n) + ".txt")) != "mine")
                    std::_Exit(2);
            }
            std::_Exit(test::readText(target) == "new\n" ? 0 : 3);
        },
        ::testing::ExitedWithCode(0), "");
    EXPECT_EQ(test::readText(dir / "x.txt.tmp"), "mine");
}

TEST(AtomicFile, AFolderOrFifoAtTheTargetIsRefusedAndStays) {
    test::ScratchDir dir;
    std::filesystem::create_directory(dir / "d.png");
    ASSERT_EQ(::mkfifo((dir / "f.png").c_str(), 0600), 0);
    for (const char* name : {"d.png", "f.png"}) {
        try {
            writeFileAtomically(dir / name, "new");
            ADD_FAILURE() << name << " was written";
        } catch (const Error& e) {
            EXPECT_EQ(e.kind(), ErrorKind::BadInput) << e.what();
        }
        EXPECT_THROW(writeImageAtomically(dir / name, kImage), Error) << name;
        EXPECT_THROW(checkOutputTargets({dir / name}), Error) << name;
    }
    EXPECT_TRUE(std::filesystem::is_directory(dir / "d.png"));
    EXPECT_TRUE(std::filesystem::is_fifo(dir / "f.png"));
    EXPECT_EQ(namesIn(dir.path()), (std::vector<std::string>{"d.png", "f.png"}));
}

// What --skip-existing asks before it keeps a frame: a whole file passes; one cut off at
// the end, in the middle or after its header, or a PNG with one byte wrong, does not.
TEST(ImageFileDefect, CutOffFilesAreFoundInEveryFormat) {
    test::ScratchDir dir;
    const std::vector<std::uint8_t> pixels = noisePixels(96, 64);
    for (const char* format : kFormats) {
        SCOPED_TRACE(format);
        const auto file = dir / (std::string("x.") + format);
        writeImageAtomically(file, {96, 64, 3, PixelType::UInt8, pixels.data(), {}});
        EXPECT_EQ(imageFileDefect(file), std::nullopt);
        const std::vector<std::uint8_t> whole = test::readBytes(file);
        for (const std::size_t size : {whole.size() - 1, whole.size() / 2, std::size_t{40}}) {
            test::writeBytes(file, {whole.begin(), whole.begin() + size});
            EXPECT_NE(imageFileDefect(file), std::nullopt) << size << " of " << whole.size();
        }
    }
    const auto png = dir / "x.png";
    writeImageAtomically(png, {96, 64, 3, PixelType::UInt8, pixels.data(), {}});
    std::vector<std::uint8_t> bytes = test::readBytes(png);
    bytes[bytes.size() / 2] ^= 0x01;
    test::writeBytes(png, bytes);
    const auto defect = imageFileDefect(png);
    ASSERT_NE(defect, std::nullopt);
    EXPECT_NE(defect->find("CRC"), std::string::npos) << *defect;
    EXPECT_NE(imageFileDefect(dir / "missing.png"), std::nullopt);
}
