// The pure facts of the feedback protocol: levels, addresses, text cleaning and wire framing.
#include <gtest/gtest.h>

#include "feedback_protocol.h"

namespace q3 {
namespace {

TEST(FeedbackProtocol, LevelsAreQ3map2SysLevels) {
    EXPECT_EQ(static_cast<int>(feedbackLevelFor(LogLevel::Verbose)), 0);  // SYS_VRB
    EXPECT_EQ(static_cast<int>(feedbackLevelFor(LogLevel::Info)), 1);     // SYS_STD
    EXPECT_EQ(static_cast<int>(feedbackLevelFor(LogLevel::Warning)), 2);  // SYS_WRN
    EXPECT_EQ(static_cast<int>(feedbackLevelFor(LogLevel::Error)), 3);    // SYS_ERR
    EXPECT_EQ(feedbackLevelText(FeedbackLevel::Error), "3");
    EXPECT_EQ(kFeedbackStreamVersion, "1");
    EXPECT_EQ(kNetRadiantPort, 39000);
}

TEST(FeedbackProtocol, ParsesAddresses) {
    auto a = parseFeedbackAddress("127.0.0.1:39000");
    ASSERT_TRUE(a);
    EXPECT_EQ(a->host, "127.0.0.1");
    EXPECT_EQ(a->port, 39000);

    auto b = parseFeedbackAddress("localhost");
    ASSERT_TRUE(b);
    EXPECT_EQ(b->host, "localhost");
    EXPECT_EQ(b->port, kNetRadiantPort);

    auto c = parseFeedbackAddress("[::1]:4000");
    ASSERT_TRUE(c);
    EXPECT_EQ(c->host, "::1");
    EXPECT_EQ(c->port, 4000);

    auto d = parseFeedbackAddress("[::1]");
    ASSERT_TRUE(d);
    EXPECT_EQ(d->port, kNetRadiantPort);

    for (const char* bad : {"", ":39000", "host:", "host:0", "host:65536", "host:12x", "::1:80",
                            "[::1", "[]:80", "[::1]x", "[::1]:", "a b:80"})
        EXPECT_FALSE(parseFeedbackAddress(bad)) << bad;
}

TEST(FeedbackProtocol, XmlTextKeepsUtf8AndReadsOtherBytesAsLatin1) {
    EXPECT_EQ(toXmlText("plain\ttext\r\n"), "plain\ttext\r\n");
    EXPECT_EQ(toXmlText("caf\xC3\xA9"), "caf\xC3\xA9");             // valid UTF-8 kept
    EXPECT_EQ(toXmlText("caf\xE9"), "caf\xC3\xA9");                 // Latin-1 e-acute converted
    EXPECT_EQ(toXmlText(std::string("a\0b\x01\x1F" "c", 6)), "abc");  // control characters dropped
    EXPECT_EQ(toXmlText("\xC0\xAF"), "\xC3\x80\xC2\xAF");           // overlong form is not UTF-8
    EXPECT_EQ(toXmlText("\xED\xA0\x80"), "\xC3\xAD\xC2\xA0\xC2\x80");  // surrogate is not UTF-8
    EXPECT_EQ(toXmlText("\xF0\x9F\x98\x80"), "\xF0\x9F\x98\x80");  // 4-byte sequence kept
    EXPECT_EQ(toXmlText("<&>"), "<&>");  // escaping is the writer's job
}

TEST(FeedbackProtocol, FramesChunksAsLnet) {
    std::string frame = frameChunk("abc");
    ASSERT_EQ(frame.size(), 8u);
    EXPECT_EQ(frame.substr(0, 4), std::string("\x04\x00\x00\x00", 4));  // text + NUL, little-endian
    EXPECT_EQ(frame.substr(4), std::string("abc\0", 4));

    std::string text(2 * kMaxChunkText + 5, 'x');
    std::string frames = frameChunks(text);
    EXPECT_EQ(frames.size(), text.size() + 3 * 5);  // three chunks of prefix + NUL
    EXPECT_EQ(static_cast<unsigned char>(frames[0]) | (static_cast<unsigned char>(frames[1]) << 8),
              int(kMaxChunkText + 1));
    EXPECT_TRUE(frameChunks("").empty());
}

}  // namespace
}  // namespace q3
