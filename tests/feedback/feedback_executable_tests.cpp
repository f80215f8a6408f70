// The q3map2 executable with -connect against a real TCP listener on 127.0.0.1, as NetRadiant's
// build monitor sees it: a well-formed q3map_feedback document carrying the run's lines by level;
// a refused command line still reaching the editor; and a listener that goes away mid-run, after
// which the run finishes on the console and says so once.
#include <gtest/gtest.h>

#include <filesystem>
#include <libxml/parser.h>
#include <libxml/tree.h>
#include <sstream>
#include <string>
#include <vector>

#include "file_io.h"

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

// Children of the document root named `name`: their text content and, for each, the texts of its
// element children.
struct Element {
    std::string level, text;
    std::vector<std::pair<std::string, std::string>> children;  // name, text
};

std::vector<Element> elementsOf(const std::string& xml, const char* name) {
    std::vector<Element> out;
    xmlDocPtr doc = xmlReadMemory(xml.data(), static_cast<int>(xml.size()), "feedback.xml", nullptr,
                                  XML_PARSE_NONET | XML_PARSE_NOERROR | XML_PARSE_NOWARNING);
    EXPECT_NE(doc, nullptr) << "not well-formed XML:\n" << xml;
    if (!doc) return out;
    auto text = [](xmlNodePtr node) {
        xmlChar* t = xmlNodeGetContent(node);
        std::string s = t ? reinterpret_cast<const char*>(t) : "";
        xmlFree(t);
        return s;
    };
    for (xmlNodePtr node = xmlDocGetRootElement(doc)->children; node; node = node->next) {
        if (node->type != XML_ELEMENT_NODE || xmlStrcmp(node->name, BAD_CAST name) != 0) continue;
        Element e;
        xmlChar* level = xmlGetProp(node, BAD_CAST "level");
        e.level = level ? reinterpret_cast<const char*>(level) : "";
        xmlFree(level);
        e.text = text(node);
        for (xmlNodePtr child = node->children; child; child = child->next) {
            if (child->type != XML_ELEMENT_NODE) continue;
            if (xmlStrcmp(child->name, BAD_CAST "polyline") == 0) {
                for (xmlNodePtr point = child->children; point; point = point->next)
                    if (point->type == XML_ELEMENT_NODE) e.children.emplace_back("point", text(point));
            } else {
                e.children.emplace_back(reinterpret_cast<const char*>(child->name), text(child));
            }
        }
        out.push_back(e);
    }
    xmlFreeDoc(doc);
    return out;
}

// -bsp on a leaking map with a doubled plane: the editor gets the leak line (the .lin's points) as
// a level-3 polyline, and selections of the leaking entity and of the brush.
TEST(FeedbackExecutable, BspSendsTheLeakLineAndProblemBrushes) {
    const fs::path dir = tempDir();
    const std::string face = " base/wall 0 0 0 0.5 0.5 0 0 0\n";
    const std::string floor = "( 0 0 0 ) ( 0 1 0 ) ( 1 0 0 )" + face;
    const std::string map = "{\n\"classname\" \"worldspawn\"\n{\n( -256 0 0 ) ( -256 1 0 ) ( -256 0 1 )" + face +
                            "( 256 0 0 ) ( 256 0 1 ) ( 256 1 0 )" + face + "( 0 -256 0 ) ( 0 -256 1 ) ( 1 -256 0 )" +
                            face + "( 0 256 0 ) ( 1 256 0 ) ( 0 256 1 )" + face + "( 0 0 -16 ) ( 1 0 -16 ) ( 0 1 -16 )" +
                            face + floor + floor + "}\n}\n{\n\"classname\" \"info_player_deathmatch\"\n\"origin\" \"0 0 64\"\n}\n";
    writeFileAtomic(dir / "leak.map", map);
    TcpListener listener({});
    std::string console;
    const int status = runCommand(connectTo(listener) + "-fs_basepath " + shellQuote(dir) + " -bsp " +
                                      shellQuote(dir / "leak.map") + " </dev/null",
                                  &console);
    listener.join();
    EXPECT_EQ(status, 0) << console;
    const std::string xml = listener.joined();
    std::vector<std::string> linePoints;
    std::istringstream lin(readFileText(dir / "leak.lin"));
    for (std::string line; std::getline(lin, line);) linePoints.push_back(line);
    ASSERT_GE(linePoints.size(), 2u);
    std::vector<std::string> sentPoints;
    for (const Element& e : elementsOf(xml, "message"))
        if (e.text.rfind("MAP LEAKED", 0) == 0) {
            EXPECT_EQ(e.level, "3");
            for (const auto& [name, value] : e.children) sentPoints.push_back(value);
        }
    EXPECT_EQ(sentPoints, linePoints) << xml;
    std::vector<std::string> selections;
    for (const Element& e : elementsOf(xml, "select"))
        for (const auto& [name, value] : e.children) selections.push_back(e.text.substr(0, e.text.size() - value.size()) + " [" + value + "]");
    EXPECT_EQ(selections, (std::vector<std::string>{"Entity 0, Brush 0: duplicate plane [0 0]",
                                                    "Entity 1, Brush 0: Entity leaked [1 0]"}))
        << xml;
    EXPECT_EQ(occurrences(xml, "duplicate plane"), 1u) << xml;  // not a second time as a console line
}

}  // namespace
}  // namespace q3::test
