// Atomic writes: the target is either the old or the new content, never a mixture or a leftover.
#include "file_io.h"
#include "test_data.h"

#include <gtest/gtest.h>

#include <sys/stat.h>

namespace q3 {
namespace {
namespace fs = std::filesystem;

size_t filesIn(const fs::path& dir) {
    size_t n = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++n;
    return n;
}

TEST(FileIo, WriteFileAtomicReplacesAndKeepsPermissions) {
    fs::path dir = test::tempDir();
    fs::path target = dir / "out.bin";
    writeFileAtomic(target, std::string("old"));
    ::chmod(target.c_str(), 0600);
    writeFileAtomic(target, std::string("new content"));
    EXPECT_EQ(readFileText(target), "new content");
    struct stat st {};
    ASSERT_EQ(::stat(target.c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 0777, 0600u);
    EXPECT_EQ(filesIn(dir), 1u);
}

TEST(FileIo, StreamingWriterCommitsLargeOutput) {
    fs::path dir = test::tempDir();
    fs::path target = dir / "big.txt";
    writeFileAtomic(target, std::string("old"));
    std::string expected;
    {
        AtomicFileWriter writer(target);
        for (int i = 0; i < 200000; ++i) {
            std::string piece = std::to_string(i) + ",";
            writer.write(piece.data(), piece.size());
            expected += piece;
            if (i == 1000) EXPECT_EQ(readFileText(target), "old");  // untouched until commit
        }
        std::string huge(3 << 20, 'x');  // larger than the writer's buffer
        writer.write(huge.data(), huge.size());
        expected += huge;
        writer.commit();
        EXPECT_THROW(writer.write("a", 1), FileError);
    }
    EXPECT_EQ(readFileText(target), expected);
    EXPECT_EQ(filesIn(dir), 1u);
}

TEST(FileIo, AbandonedWriterLeavesTargetAndNoTemporary) {
    fs::path dir = test::tempDir();
    fs::path target = dir / "keep.txt";
    writeFileAtomic(target, std::string("original"));
    try {
        AtomicFileWriter writer(target);
        writer.write("partial", 7);
        throw std::runtime_error("interrupted");
    } catch (const std::runtime_error&) {
    }
    EXPECT_EQ(readFileText(target), "original");
    EXPECT_EQ(filesIn(dir), 1u);
}

TEST(FileIo, StaleTemporariesAreRemoved) {
    fs::path dir = test::tempDir();
    fs::path target = dir / "map.bsp";
    writeFileAtomic(target, std::string("bsp"));
    writeFileAtomic(dir / (atomicTempPrefix(target) + "123-0"), std::string("left by a killed run"));
    writeFileAtomic(dir / "other.tmp-1", std::string("not ours"));
    EXPECT_EQ(removeStaleTemporaries(target), 1);
    EXPECT_EQ(filesIn(dir), 2u);
}

TEST(FileIo, ErrorsNameTheFile) {
    fs::path missing = test::tempDir() / "no" / "such" / "file.bsp";
    try {
        readFileBytes(missing);
        FAIL() << "no error";
    } catch (const FileError& e) {
        EXPECT_NE(std::string(e.what()).find(missing.string()), std::string::npos) << e.what();
    }
    EXPECT_THROW(writeFileAtomic(missing, std::string("x")), FileError);
}

}  // namespace
}  // namespace q3
