// The entity lump parser and writer.
#include "bspfile.h"

#include <gtest/gtest.h>

namespace q3::bsp {
namespace {

constexpr const char* kName = "maps/ents.bsp";

void expectEntityError(std::string_view text, const std::string& fragment) {
    try {
        (void)parseEntities(text, kName);
        ADD_FAILURE() << "no error; expected \"" << fragment << "\"";
    } catch (const BspError& e) {
        const std::string message = e.what();
        EXPECT_EQ(message.rfind(std::string(kName) + ": entities: line ", 0), 0u) << message;
        EXPECT_NE(message.find(fragment), std::string::npos) << "message: " << message << "\nexpected: " << fragment;
    }
}

TEST(Entities, ParsesPairsInOrderWithDuplicates) {
    const std::string text = std::string(
                                 "{\n\"classname\" \"worldspawn\"\n\"message\" \"Two words\"\n}\n"
                                 "{\n\"classname\" \"target_speaker\"\n\"noise\" \"a.wav\"\n\"noise\" \"b.wav\"\n}\n") +
                             '\0';
    const std::vector<Entity> ents = parseEntities(text, kName);
    ASSERT_EQ(ents.size(), 2u);
    EXPECT_EQ(ents[0].classname(), "worldspawn");
    EXPECT_EQ(ents[0].value("message"), "Two words");
    ASSERT_EQ(ents[1].pairs.size(), 3u);
    EXPECT_EQ(ents[1].pairs[1], (std::pair<std::string, std::string>{"noise", "a.wav"}));
    EXPECT_EQ(ents[1].pairs[2], (std::pair<std::string, std::string>{"noise", "b.wav"}));
    EXPECT_EQ(*ents[1].find("NOISE"), "a.wav");  // first value, key compared without case
}

TEST(Entities, AcceptsCommentsBareTokensAndEmptyValues) {
    const std::vector<Entity> ents = parseEntities(
        "// header comment\n{ classname light /* block\ncomment */ \"light\" 200 \"target\" \"\" }{}", kName);
    ASSERT_EQ(ents.size(), 2u);
    EXPECT_EQ(ents[0].classname(), "light");
    EXPECT_EQ(ents[0].value("light"), "200");
    ASSERT_NE(ents[0].find("target"), nullptr);
    EXPECT_EQ(*ents[0].find("target"), "");
    EXPECT_TRUE(ents[1].pairs.empty());
}

TEST(Entities, NulEndsTheText) {
    const std::string text = std::string("{ \"classname\" \"worldspawn\" }\n") + '\0' + "garbage {";
    EXPECT_EQ(parseEntities(text, kName).size(), 1u);
    EXPECT_TRUE(parseEntities("", kName).empty());
    EXPECT_TRUE(parseEntities(std::string(1, '\0'), kName).empty());
}

TEST(Entities, ValueSetErase) {
    Entity e;
    EXPECT_EQ(e.value("missing", "dflt"), "dflt");
    EXPECT_EQ(e.classname(), "");
    e.set("classname", "info_null");
    e.set("origin", "1 2 3");
    e.set("Origin", "4 5 6");  // replaces, keeping the original key spelling and position
    ASSERT_EQ(e.pairs.size(), 2u);
    EXPECT_EQ(e.pairs[1].first, "origin");
    EXPECT_EQ(e.pairs[1].second, "4 5 6");
    EXPECT_TRUE(e.erase("ORIGIN"));
    EXPECT_FALSE(e.erase("origin"));
    EXPECT_EQ(e.pairs.size(), 1u);
}

TEST(Entities, UnparseWritesTheQ3map2Layout) {
    Entity world;
    world.pairs = {{"classname", "worldspawn"}, {"_color", "1 0.5 0"}};
    Entity empty;
    const std::string text = unparseEntities({world, empty});
    EXPECT_EQ(text, std::string("{\n\"classname\" \"worldspawn\"\n\"_color\" \"1 0.5 0\"\n}\n{\n}\n") + '\0');
    const std::vector<Entity> back = parseEntities(text, kName);
    ASSERT_EQ(back.size(), 2u);
    EXPECT_EQ(back[0].pairs, world.pairs);
    EXPECT_TRUE(back[1].pairs.empty());
    EXPECT_EQ(unparseEntities({}), std::string(1, '\0'));
}

TEST(Entities, ErrorsNameTheLine) {
    expectEntityError("{\n\"classname\" \"worldspawn\n}\n", "line 2: unterminated quoted string");
    expectEntityError("{\n\"classname\" \"worldspawn\"\n\"message\"\n}\n", "line 3: key \"message\" has no value");
    expectEntityError("{\n\"classname\" \"worldspawn\"\n", "line 1: entity 0 is not closed by '}'");
    expectEntityError("{ \"a\" \"b\" }\n\n\"classname\" \"light\"", "line 3: expected '{' but found \"classname\"");
    expectEntityError("{ \"a\" \"b\"\n{ \"c\" \"d\" }", "line 2: '{' inside an entity");
    expectEntityError("{ \"a\" \"b\" }\n/* never closed", "line 2: unterminated /* comment");
    expectEntityError("{ \"multi\nline\" \"value\" }\n}", "line 3: expected '{' but found \"}\"");
}

}  // namespace
}  // namespace q3::bsp
