// Checks a -stats summary against docs/stats-schema.json with RapidJSON's schema validator
// (header-only: RapidJSON is header-only too).
#pragma once

#include <gtest/gtest.h>
#include <rapidjson/document.h>
#include <rapidjson/schema.h>
#include <rapidjson/stringbuffer.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace q3::test {

// Parses JSON text; a parse error fails the current test (the document is then empty).
inline rapidjson::Document parseJsonText(const std::string& text, const std::string& what = "text") {
    rapidjson::Document doc;
    doc.Parse(text.c_str(), text.size());
    EXPECT_FALSE(doc.HasParseError()) << what << " is not JSON:\n" << text;
    return doc;
}

inline rapidjson::Document readJsonFile(const std::filesystem::path& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return parseJsonText(text.str(), path.string());
}

// Empty when `doc` follows docs/stats-schema.json, else the broken keyword and where.
inline std::string statsSchemaViolation(const rapidjson::Document& doc) {
    static const rapidjson::Document schemaDoc =
        readJsonFile(std::filesystem::path(Q3MAP_SOURCE_DIR) / "docs/stats-schema.json");
    static const rapidjson::SchemaDocument schema(schemaDoc);
    rapidjson::SchemaValidator validator(schema);
    if (doc.Accept(validator)) return "";
    rapidjson::StringBuffer where;
    validator.GetInvalidDocumentPointer().StringifyUriFragment(where);
    return std::string(validator.GetInvalidSchemaKeyword()) + " at " + where.GetString();
}

}  // namespace q3::test
