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

// Past its first buffer (1 MiB) the writer goes on with direct I/O and writes a short last buffer
// through the page cache: every length around those edges, in pieces of odd sizes, reads back whole.
TEST(FileIo, StreamingWriterKeepsEveryByteAroundItsBufferEdges) {
    fs::path dir = test::tempDir();
    fs::path target = dir / "edges.bin";
    constexpr size_t kMiB = size_t(1) << 20;
    for (size_t size : {size_t(0), size_t(1), size_t(4095), size_t(4096), kMiB - 1, kMiB, kMiB + 1, 2 * kMiB,
                        3 * kMiB + 4097}) {
        std::vector<uint8_t> bytes(size);
        for (size_t i = 0; i < size; ++i) bytes[i] = uint8_t((i * 2654435761u) >> 13);
        AtomicFileWriter writer(target);
        for (size_t at = 0, piece = 1; at < size; piece = piece * 3 % 200003 + 1) {
            const size_t n = std::min(piece, size - at);
            writer.write(bytes.data() + at, n);
            at += n;
        }
        writer.commit();
        EXPECT_EQ(readFileBytes(target), bytes) << size << " bytes";
    }
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
