// The feedback stream against a real TCP listener on 127.0.0.1: what NetRadiant would receive,
// parsed back with libxml2; a listener that goes away or hangs; and a listener that is not there.
#include <gtest/gtest.h>

#include <chrono>
#include <libxml/parser.h>
#include <libxml/tree.h>
#include <mutex>
#include <string>
#include <vector>

#include "feedback_log.h"
#include "tcp_listener.h"

namespace q3 {
namespace {

using test::TcpListener;

struct ParsedNode {
    std::string name;
    std::string level;  // "" when absent
    std::string text;   // the node's own text, children excluded
    std::vector<ParsedNode> children;
};

ParsedNode toParsed(xmlNodePtr node) {
    ParsedNode out;
    out.name = reinterpret_cast<const char*>(node->name);
    if (xmlChar* level = xmlGetProp(node, reinterpret_cast<const xmlChar*>("level"))) {
        out.level = reinterpret_cast<const char*>(level);
        xmlFree(level);
    }
    for (xmlNodePtr c = node->children; c; c = c->next) {
        if (c->type == XML_TEXT_NODE) out.text += reinterpret_cast<const char*>(c->content);
        else if (c->type == XML_ELEMENT_NODE) out.children.push_back(toParsed(c));
    }
    return out;
}

// Parses the whole received stream; fails the test when it is not a well-formed document.
ParsedNode parseStream(const std::string& xml, std::string* version = nullptr) {
    xmlDocPtr doc = xmlReadMemory(xml.data(), static_cast<int>(xml.size()), "feedback.xml", nullptr,
                                  XML_PARSE_NONET | XML_PARSE_NOERROR | XML_PARSE_NOWARNING);
    EXPECT_NE(doc, nullptr) << "not well-formed XML:\n" << xml;
    if (!doc) return {};
    xmlNodePtr root = xmlDocGetRootElement(doc);
    ParsedNode parsed = toParsed(root);
    if (version) {
        xmlChar* v = xmlGetProp(root, reinterpret_cast<const xmlChar*>("version"));
        *version = v ? reinterpret_cast<const char*>(v) : "";
        xmlFree(v);
    }
    xmlFreeDoc(doc);
    return parsed;
}

FeedbackAddress loopback(uint16_t port) { return {"127.0.0.1", port}; }

// Collects notices (the stream's own console lines) for the test to inspect.
struct Notices {
    std::mutex mutex;
    std::vector<std::string> lines;
    std::function<void(std::string_view)> sink() {
        return [this](std::string_view text) {
            std::lock_guard lock(mutex);
            lines.emplace_back(text);
        };
    }
    size_t count() {
        std::lock_guard lock(mutex);
        return lines.size();
    }
};

TEST(FeedbackStream, CompileLikeSequenceArrivesAsOneWellFormedDocument) {
    TcpListener listener({});
    Log log(false);
    log.setVerbose(true);
    Notices notices;
    FeedbackStreamOptions options;
    options.notice = notices.sink();
    auto stream = connectNetRadiant("127.0.0.1:" + std::to_string(listener.port()), log, options);
    ASSERT_NE(stream, nullptr);
    EXPECT_EQ(log.warningCount(), 0);

    std::string longLine(2500, 'L');  // longer than one network chunk
    log.info("--- LightMain ---");
    log.debug("loading shaders");
    log.raw("0...1...");
    log.warning("shader textures/x has no image & <stage>");
    log.info(longLine);
    const Vec3 path[] = {{0, 0, 0}, {64.5f, -32, 16}, {128, 256, 8}};
    reportLeak(log, stream.get(), path);
    std::string brushLine = reportBrushProblem(log, stream.get(), 0, 12, "mixed face contents", false);
    EXPECT_EQ(brushLine, "Entity 0, Brush 12: mixed face contents");
    stream->point("entity in solid", {1.5f, 2, -3});
    const Vec3 quad[] = {{0, 0, 0}, {8, 0, 0}, {8, 8, 0}};
    stream->winding("tiny winding", quad, FeedbackLevel::Warning);
    log.error("caf\xE9 is not UTF-8");
    stream->close();
    listener.join();

    EXPECT_TRUE(listener.framingErrors().empty());
    std::vector<std::string> chunks = listener.chunks();
    ASSERT_FALSE(chunks.empty());
    // The first chunk is q3map2's header: the declaration and the open root with its version.
    // (libxml2 ends the declaration with a newline; q3map2 writes none. Both are the same prolog.)
    EXPECT_EQ(chunks[0], "<?xml version=\"1.0\"?>\n<q3map_feedback version=\"1\">");
    for (const std::string& c : chunks) EXPECT_LE(c.size(), kMaxChunkText);

    std::string version;
    ParsedNode root = parseStream(listener.joined(), &version);
    EXPECT_EQ(root.name, "q3map_feedback");
    EXPECT_EQ(version, "1");
    const auto& n = root.children;
    ASSERT_EQ(n.size(), 10u);

    EXPECT_EQ(n[0].name, "message");
    EXPECT_EQ(n[0].level, "1");
    EXPECT_EQ(n[0].text, "--- LightMain ---\n");
    EXPECT_EQ(n[1].level, "0");
    EXPECT_EQ(n[1].text, "loading shaders\n");
    EXPECT_EQ(n[2].level, "1");
    EXPECT_EQ(n[2].text, "0...1...");
    EXPECT_EQ(n[3].level, "2");
    EXPECT_EQ(n[3].text, "WARNING: shader textures/x has no image & <stage>\n");
    EXPECT_EQ(n[4].text, longLine + "\n");

    // The leak: banner stays on the console, the editor gets the polyline.
    EXPECT_EQ(n[5].name, "message");
    EXPECT_EQ(n[5].level, "3");
    EXPECT_EQ(n[5].text, "MAP LEAKED\n");
    ASSERT_EQ(n[5].children.size(), 1u);
    const ParsedNode& polyline = n[5].children[0];
    EXPECT_EQ(polyline.name, "polyline");
    ASSERT_EQ(polyline.children.size(), 3u);
    EXPECT_EQ(polyline.children[0].name, "point");
    EXPECT_EQ(polyline.children[0].text, "0.000000 0.000000 0.000000");
    EXPECT_EQ(polyline.children[1].text, "64.500000 -32.000000 16.000000");
    EXPECT_EQ(polyline.children[2].text, "128.000000 256.000000 8.000000");

    // The brush warning goes as a select only (its console line is not echoed as a message).
    EXPECT_EQ(n[6].name, "select");
    EXPECT_EQ(n[6].level, "2");
    EXPECT_EQ(n[6].text, "Entity 0, Brush 12: mixed face contents");
    ASSERT_EQ(n[6].children.size(), 1u);
    EXPECT_EQ(n[6].children[0].name, "brush");
    EXPECT_EQ(n[6].children[0].text, "0 12");

    EXPECT_EQ(n[7].name, "pointmsg");
    EXPECT_EQ(n[7].level, "3");
    EXPECT_EQ(n[7].text, "entity in solid");
    ASSERT_EQ(n[7].children.size(), 1u);
    EXPECT_EQ(n[7].children[0].text, "1.5 2 -3");

    EXPECT_EQ(n[8].name, "windingmsg");
    EXPECT_EQ(n[8].level, "2");
    ASSERT_EQ(n[8].children.size(), 1u);
    EXPECT_EQ(n[8].children[0].name, "winding");
    EXPECT_EQ(n[8].children[0].text, "3 (0 0 0)(8 0 0)(8 8 0)");

    EXPECT_EQ(n[9].level, "3");
    EXPECT_EQ(n[9].text, "ERROR: caf\xC3\xA9 is not UTF-8\n");

    EXPECT_EQ(log.warningCount(), 2);  // the shader warning and the brush warning
    EXPECT_EQ(notices.count(), 0u);
}

// What NetRadiant does with the chunks: feed them one by one to a libxml2 push parser while the
// compile is still running. Each element must be complete (its end seen) as soon as it was sent.
struct PushParserView {
    int depth = 0;
    std::vector<std::string> ended;  // names of ended elements at depth 2 (children of the root)
    std::string rootVersion;
};

void onStart(void* ctx, const xmlChar* name, const xmlChar** attrs) {
    auto* view = static_cast<PushParserView*>(ctx);
    if (view->depth == 0 && attrs && attrs[0] && xmlStrcmp(attrs[0], BAD_CAST "version") == 0)
        view->rootVersion = reinterpret_cast<const char*>(attrs[1]);
    ++view->depth;
}
void onEnd(void* ctx, const xmlChar* name) {
    auto* view = static_cast<PushParserView*>(ctx);
    if (--view->depth == 1) view->ended.emplace_back(reinterpret_cast<const char*>(name));
}

bool waitForChunks(const TcpListener& listener, size_t count) {
    auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
    while (listener.chunks().size() < count) {
        if (std::chrono::steady_clock::now() > deadline) return false;
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    return true;
}

TEST(FeedbackStream, EachElementReachesTheEditorAsItIsWritten) {
    TcpListener listener({});
    std::string error;
    auto stream = FeedbackStream::open(loopback(listener.port()), {}, &error);
    ASSERT_NE(stream, nullptr) << error;
    ASSERT_TRUE(waitForChunks(listener, 1));

    xmlSAXHandler sax{};
    sax.startElement = onStart;
    sax.endElement = onEnd;
    PushParserView view;
    std::string header = listener.chunks()[0];
    xmlParserCtxtPtr parser =
        xmlCreatePushParserCtxt(&sax, &view, header.data(), static_cast<int>(header.size()), nullptr);
    ASSERT_NE(parser, nullptr);
    size_t fed = 1;
    auto feedNew = [&] {
        std::vector<std::string> chunks = listener.chunks();
        for (; fed < chunks.size(); ++fed)
            xmlParseChunk(parser, chunks[fed].data(), static_cast<int>(chunks[fed].size()), 0);
    };

    stream->message(FeedbackLevel::Standard, "--- BSP ---\n");
    ASSERT_TRUE(waitForChunks(listener, 2));
    feedNew();
    EXPECT_EQ(view.rootVersion, "1");
    ASSERT_EQ(view.ended.size(), 1u);
    EXPECT_EQ(view.ended[0], "message");

    stream->brushSelect(1, 7, "degenerate plane", false);
    ASSERT_TRUE(waitForChunks(listener, 3));
    feedNew();
    ASSERT_EQ(view.ended.size(), 2u);
    EXPECT_EQ(view.ended[1], "select");

    stream->message(FeedbackLevel::Standard, std::string(3000, 'z'));  // arrives in three chunks
    ASSERT_TRUE(waitForChunks(listener, 6));
    feedNew();
    EXPECT_EQ(view.ended.size(), 3u);

    xmlFreeParserCtxt(parser);
    stream->close();
    listener.join();
}

TEST(FeedbackStream, ConnectsByHostName) {
    TcpListener listener({});
    Log log(false);
    auto stream = connectNetRadiant("localhost:" + std::to_string(listener.port()), log);
    // localhost may resolve to ::1 first; the IPv4 address is tried next.
    ASSERT_NE(stream, nullptr);
    log.info("hello");
    stream->close();  // the log's sink still holds the stream; closing ends the document now
    listener.join();
    ParsedNode root = parseStream(listener.joined());
    ASSERT_GE(root.children.size(), 1u);
    EXPECT_EQ(root.children[0].text, "hello\n");
}

TEST(FeedbackStream, ListenerClosingMidStreamIsReportedOnceAndTheCompileGoesOn) {
    TcpListener listener({.closeAfterChunks = 2});
    Log log(false);
    std::vector<std::string> consoleLines;
    log.addSink([&](LogLevel, std::string_view line) { consoleLines.emplace_back(line); });
    Notices notices;
    FeedbackStreamOptions options;
    options.notice = notices.sink();
    auto stream = connectNetRadiant("127.0.0.1:" + std::to_string(listener.port()), log, options);
    ASSERT_NE(stream, nullptr);

    auto start = std::chrono::steady_clock::now();
    int sent = 0;
    // The peer's close shows up as EPIPE or ECONNRESET a send or two after it happens.
    while (stream->connected() && sent < 20000) {
        log.info("line " + std::to_string(sent++));
        if (sent % 50 == 0) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    EXPECT_FALSE(stream->connected()) << "the loss was never noticed";
    for (int i = 0; i < 100; ++i) log.info("after the loss");
    log.warning("still counted");
    stream->close();
    auto elapsed = std::chrono::steady_clock::now() - start;
    EXPECT_LT(elapsed, std::chrono::seconds(5));

    ASSERT_EQ(notices.count(), 1u);
    EXPECT_EQ(notices.lines[0].rfind(std::string(kLostConnectionNotice), 0), 0u) << notices.lines[0];
    EXPECT_EQ(log.warningCount(), 1);
    EXPECT_EQ(consoleLines.back(), "WARNING: still counted\n");
    listener.join();
    EXPECT_GE(listener.chunks().size(), 1u);
}

TEST(FeedbackStream, ListenerThatStopsReadingTimesOutInsteadOfBlocking) {
    TcpListener listener({.neverRead = true});
    Notices notices;
    FeedbackStreamOptions options;
    options.notice = notices.sink();
    options.sendTimeout = std::chrono::milliseconds(200);
    std::string error;
    auto stream = FeedbackStream::open(loopback(listener.port()), options, &error);
    ASSERT_NE(stream, nullptr) << error;
    std::string big(4000, 'x');
    int sent = 0;  // a send that blocked for good would hang here until the test's own time limit
    while (stream->connected() && sent < 200000) {
        stream->message(FeedbackLevel::Standard, big);
        ++sent;
    }
    EXPECT_FALSE(stream->connected());
    EXPECT_EQ(notices.count(), 1u);
    stream->message(FeedbackLevel::Standard, "ignored");
    EXPECT_EQ(notices.count(), 1u);
}

TEST(FeedbackStream, ClosedPortGivesOneWarningAndNoStream) {
    Log log(false);
    std::vector<std::string> lines;
    log.addSink([&](LogLevel level, std::string_view line) {
        if (level == LogLevel::Warning) lines.emplace_back(line);
    });
    std::string address = "127.0.0.1:" + std::to_string(test::closedPort());
    auto stream = connectNetRadiant(address, log);
    EXPECT_EQ(stream, nullptr);
    EXPECT_EQ(log.warningCount(), 1);
    ASSERT_EQ(lines.size(), 1u);
    EXPECT_NE(lines[0].find(address), std::string::npos) << lines[0];
    EXPECT_NE(lines[0].find("continuing"), std::string::npos) << lines[0];

    // The compile goes on; the report helpers accept the missing stream.
    const Vec3 path[] = {{0, 0, 0}};
    reportLeak(log, nullptr, path);
    EXPECT_EQ(reportBrushProblem(log, nullptr, 1, 2, "bad", true), "Entity 1, Brush 2: bad");
}

TEST(FeedbackStream, MalformedAddressGivesOneWarning) {
    Log log(false);
    EXPECT_EQ(connectNetRadiant("127.0.0.1:notaport", log), nullptr);
    EXPECT_EQ(connectNetRadiant("no-such-host.invalid:39000", log), nullptr);
    EXPECT_EQ(log.warningCount(), 2);
}

TEST(FeedbackStream, ConcurrentWritersProduceWholeElements) {
    TcpListener listener({});
    std::string error;
    auto stream = FeedbackStream::open(loopback(listener.port()), {}, &error);
    ASSERT_NE(stream, nullptr) << error;
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t)
        threads.emplace_back([&, t] {
            for (int i = 0; i < 200; ++i)
                stream->message(FeedbackLevel::Standard, "thread " + std::to_string(t) + std::string(300, '.'));
        });
    for (auto& th : threads) th.join();
    stream->close();
    listener.join();
    ParsedNode root = parseStream(listener.joined());
    EXPECT_EQ(root.children.size(), 800u);
}

}  // namespace
}  // namespace q3
