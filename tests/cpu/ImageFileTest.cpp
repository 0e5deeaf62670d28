// Writing outputs whole or not at all (scene-and-cli.md, "Outputs"; issue 15): the same
// file in two spellings refused up front, a failed batch taking away the folders it made,
// and a signal in the middle of a batch leaving nothing behind.
#include <gtest/gtest.h>

#include <csignal>
#include <cstdint>
#include <vector>

#include "TestSupport.h"
#include "microrelief/core/Error.h"
#include "microrelief/image/ImageFile.h"

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
