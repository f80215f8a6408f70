// The q3map2 executable with -connect against a real TCP listener on 127.0.0.1, as NetRadiant's
// build monitor sees it: a well-formed q3map_feedback document carrying the run's lines by level;
// a refused command line still reaching the editor; and a listener that goes away mid-run, after
// which the run finishes on the console and says so once.
#include <gtest/gtest.h>

#include <filesystem>
#include <libxml/parser.h>
#include <libxml/tree.h>
#include <string>
#include <vector>

#include "tcp_listener.h"
#include "test_data.h"

namespace q3::test {
namespace {

namespace fs = std::filesystem;

struct Message {
    std::string level;
    std::string text;
};

// The <message> elements of the received document; fails the test when it is not well-formed or
// not a q3map_feedback document.
std::vector<Message> messagesOf(const std::string& xml) {
    std::vector<Message> messages;
    xmlDocPtr doc = xmlReadMemory(xml.data(), static_cast<int>(xml.size()), "feedback.xml", nullptr,
                                  XML_PARSE_NONET | XML_PARSE_NOERROR | XML_PARSE_NOWARNING);
    EXPECT_NE(doc, nullptr) << "not well-formed XML:\n" << xml;
    if (!doc) return messages;
    xmlNodePtr root = xmlDocGetRootElement(doc);
    EXPECT_EQ(std::string(reinterpret_cast<const char*>(root->name)), "q3map_feedback");
    for (xmlNodePtr node = root->children; node; node = node->next) {
        if (node->type != XML_ELEMENT_NODE || xmlStrcmp(node->name, BAD_CAST "message") != 0) continue;
        Message m;
        xmlChar* level = xmlGetProp(node, BAD_CAST "level");
        m.level = level ? reinterpret_cast<const char*>(level) : "";
        xmlFree(level);
        xmlChar* text = xmlNodeGetContent(node);
        m.text = text ? reinterpret_cast<const char*>(text) : "";
        xmlFree(text);
        messages.push_back(m);
    }
    xmlFreeDoc(doc);
    return messages;
}

const Message* findMessage(const std::vector<Message>& messages, const std::string& part) {
    for (const Message& m : messages)
        if (m.text.find(part) != std::string::npos) return &m;
    return nullptr;
}

std::string connectTo(const TcpListener& listener) {
    return shellQuote(q3map2Exe()) + " -connect 127.0.0.1:" + std::to_string(listener.port()) + " ";
}

size_t occurrences(const std::string& text, const std::string& part) {
    size_t n = 0;
    for (size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
    return n;
}

TEST(FeedbackExecutable, RunStreamsItsLinesAsOneDocument) {
    TcpListener listener({});
    std::string console;
    int status = runCommand(connectTo(listener) + "-info " + shellQuote(realBsp("oacmpdm1")) + " </dev/null", &console);
    listener.join();
    EXPECT_EQ(status, 0) << console;
    EXPECT_TRUE(listener.framingErrors().empty());
    std::vector<Message> messages = messagesOf(listener.joined());
    const Message* header = findMessage(messages, "IBSP version 46");
    ASSERT_NE(header, nullptr) << listener.joined();
    EXPECT_EQ(header->level, "1");
    EXPECT_NE(console.find("IBSP version 46"), std::string::npos);  // and on the console as well
}

TEST(FeedbackExecutable, RefusedCommandLineReachesTheEditorAsAnError) {
    TcpListener listener({});
    std::string console;
    int status = runCommand(connectTo(listener) + "-bsp -custinfoparms /maps/x.map </dev/null", &console);
    listener.join();
    EXPECT_EQ(status, 2);
    const std::string error = "-custinfoparms is a q3map2 option this build does not implement yet";
    EXPECT_EQ(console, "ERROR: " + error + "\n");
    std::vector<Message> messages = messagesOf(listener.joined());
    const Message* m = findMessage(messages, error);
    ASSERT_NE(m, nullptr) << listener.joined();
    EXPECT_EQ(m->level, "3");
}

TEST(FeedbackExecutable, ListenerGoingAwayMidRunIsSaidOnceAndTheRunFinishes) {
    const fs::path dir = tempDir();
    fs::copy_file(realBsp("oacmpdm1"), dir / "oacmpdm1.bsp");
    // Loading the game's shaders takes a moment: the listener is gone well before the later
    // phases print.
    TcpListener listener({.closeAfterChunks = 1});
    std::string console;
    int status = runCommand(connectTo(listener) + "-fs_basepath " + shellQuote(openArenaBase()) +
                                " -fs_game baseoa -light -fast -nolm -nogrid " + shellQuote(dir / "oacmpdm1.bsp") +
                                " </dev/null",
                            &console);
    listener.join();
    EXPECT_EQ(status, 0) << console;
    EXPECT_EQ(occurrences(console, "lost connection to NetRadiant; continuing"), 1u) << console;
    EXPECT_NE(console.find("seconds elapsed"), std::string::npos) << console;  // ran to the end
    EXPECT_NE(console.find("wrote "), std::string::npos) << console;
}

}  // namespace
}  // namespace q3::test
