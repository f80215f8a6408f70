// A small JSON tree that remembers where each value came from, so that errors in hand-edited
// files name the file, line, column and member. Numbers keep their source text, so floats read
// back bit-exact. Duplicate member names are kept, in order (entities.json repeats "KeyValue").
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace q3::json {

struct SourceText;

struct Value {
    enum class Kind { Null, Bool, Number, String, Array, Object };
    Kind kind = Kind::Null;
    bool boolean = false;
    std::string text;                 // string value, or the number's source text
    std::vector<Value> items;         // array elements, or object member values
    std::vector<std::string> keys;    // object member names, parallel to items
    size_t offset = 0;                // byte offset in the source, for messages
    const SourceText* source = nullptr;

    bool isObject() const { return kind == Kind::Object; }
    bool isArray() const { return kind == Kind::Array; }
    size_t size() const { return items.size(); }

    // Member access; `context` names the record for messages ("DrawVert#3").
    // Missing members, wrong types and out-of-range numbers throw JsonError.
    const Value& member(std::string_view key, std::string_view context) const;
    const Value* findMember(std::string_view key) const;
    const Value& element(size_t index, std::string_view context) const;

    int32_t asInt(std::string_view context) const;
    uint8_t asByte(std::string_view context) const;
    float asFloat(std::string_view context) const;
    const std::string& asString(std::string_view context) const;
    // An array of exactly n elements (throws otherwise).
    const Value& asArray(size_t n, std::string_view context) const;
    const Value& asObject(std::string_view context) const;

    [[noreturn]] void fail(std::string_view context, std::string_view what) const;
};

// The text of one file and its name; values point back to it for line/column lookups.
struct SourceText {
    std::string name;
    std::string text;
    // "file:line:column"
    std::string where(size_t offset) const;
};

struct Document {
    std::unique_ptr<SourceText> source;
    Value root;
};

// Parses a whole file (comments and trailing commas allowed, as q3map2 does; NaN/Infinity too).
// Syntax errors throw JsonError with file:line:column.
Document parseDocument(std::string name, std::string text);

}  // namespace q3::json
