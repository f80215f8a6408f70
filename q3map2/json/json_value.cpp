#include "json_value.h"

#include "json_error.h"

#include <rapidjson/error/en.h>
#include <rapidjson/reader.h>

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>

namespace q3::json {

namespace {

constexpr unsigned kParseFlags = rapidjson::kParseCommentsFlag | rapidjson::kParseTrailingCommasFlag |
                                 rapidjson::kParseNanAndInfFlag | rapidjson::kParseNumbersAsStringsFlag |
                                 rapidjson::kParseStopWhenDoneFlag;

// Builds the tree from SAX events. The stream position at each event locates the value.
class TreeBuilder {
public:
    TreeBuilder(const rapidjson::StringStream& stream, const SourceText* source) : stream_(stream), source_(source) {}

    bool Null() { add(Value::Kind::Null); return true; }
    bool Bool(bool b) { add(Value::Kind::Bool).boolean = b; return true; }
    bool Int(int) { return false; }  // numbers arrive as strings (kParseNumbersAsStringsFlag)
    bool Uint(unsigned) { return false; }
    bool Int64(int64_t) { return false; }
    bool Uint64(uint64_t) { return false; }
    bool Double(double) { return false; }
    bool RawNumber(const char* str, rapidjson::SizeType length, bool) {
        add(Value::Kind::Number).text.assign(str, length);
        return true;
    }
    bool String(const char* str, rapidjson::SizeType length, bool) {
        add(Value::Kind::String).text.assign(str, length);
        return true;
    }
    bool StartObject() { open(Value::Kind::Object); return true; }
    bool Key(const char* str, rapidjson::SizeType length, bool) {
        stack_.back()->keys.emplace_back(str, length);
        return true;
    }
    bool EndObject(rapidjson::SizeType) { stack_.pop_back(); return true; }
    bool StartArray() { open(Value::Kind::Array); return true; }
    bool EndArray(rapidjson::SizeType) { stack_.pop_back(); return true; }

    Value root;

private:
    Value& add(Value::Kind kind) {
        Value* target;
        if (stack_.empty()) {
            target = &root;
        } else {
            stack_.back()->items.emplace_back();
            target = &stack_.back()->items.back();
        }
        target->kind = kind;
        target->offset = stream_.Tell();
        target->source = source_;
        return *target;
    }
    void open(Value::Kind kind) {
        Value& v = add(kind);
        stack_.push_back(&v);
    }

    const rapidjson::StringStream& stream_;
    const SourceText* source_;
    std::vector<Value*> stack_;
};

std::string describe(Value::Kind kind) {
    switch (kind) {
        case Value::Kind::Null: return "null";
        case Value::Kind::Bool: return "a boolean";
        case Value::Kind::Number: return "a number";
        case Value::Kind::String: return "a string";
        case Value::Kind::Array: return "an array";
        case Value::Kind::Object: return "an object";
    }
    return "a value";
}

}  // namespace

std::string SourceText::where(size_t offset) const {
    size_t line = 1, column = 1;
    for (size_t i = 0; i < offset && i < text.size(); ++i) {
        if (text[i] == '\n') {
            ++line;
            column = 1;
        } else {
            ++column;
        }
    }
    return name + ":" + std::to_string(line) + ":" + std::to_string(column);
}

void Value::fail(std::string_view context, std::string_view what) const {
    std::string where = source ? source->where(offset) : std::string("<json>");
    throw JsonError(where + ": " + std::string(context) + ": " + std::string(what));
}

const Value* Value::findMember(std::string_view key) const {
    if (kind != Kind::Object) return nullptr;
    for (size_t i = 0; i < keys.size(); ++i)
        if (keys[i] == key) return &items[i];
    return nullptr;
}

const Value& Value::member(std::string_view key, std::string_view context) const {
    asObject(context);
    const Value* v = findMember(key);
    if (!v) fail(context, "missing member \"" + std::string(key) + "\"");
    return *v;
}

const Value& Value::element(size_t index, std::string_view context) const {
    if (kind != Kind::Array) fail(context, "expected an array, found " + describe(kind));
    if (index >= items.size()) fail(context, "array has " + std::to_string(items.size()) + " elements, expected more");
    return items[index];
}

const Value& Value::asObject(std::string_view context) const {
    if (kind != Kind::Object) fail(context, "expected an object, found " + describe(kind));
    return *this;
}

const Value& Value::asArray(size_t n, std::string_view context) const {
    if (kind != Kind::Array) fail(context, "expected an array of " + std::to_string(n) + ", found " + describe(kind));
    if (items.size() != n)
        fail(context, "expected an array of " + std::to_string(n) + " elements, found " + std::to_string(items.size()));
    return *this;
}

int32_t Value::asInt(std::string_view context) const {
    if (kind != Kind::Number) fail(context, "expected an integer, found " + describe(kind));
    int64_t v = 0;
    auto r = std::from_chars(text.data(), text.data() + text.size(), v);
    if (r.ec != std::errc() || r.ptr != text.data() + text.size())
        fail(context, "expected an integer, found " + text);
    if (v < std::numeric_limits<int32_t>::min() || v > std::numeric_limits<int32_t>::max())
        fail(context, "integer " + text + " is out of range");
    return static_cast<int32_t>(v);
}

uint8_t Value::asByte(std::string_view context) const {
    int32_t v = asInt(context);
    if (v < 0 || v > 255) fail(context, "byte value " + text + " is out of range 0..255");
    return static_cast<uint8_t>(v);
}

float Value::asFloat(std::string_view context) const {
    if (kind == Kind::String && text.size() == 10 && text.compare(0, 2, "0x") == 0) {
        // A NaN with a particular payload, written as its bits.
        uint32_t bits = 0;
        auto r = std::from_chars(text.data() + 2, text.data() + text.size(), bits, 16);
        float v;
        std::memcpy(&v, &bits, sizeof(v));
        if (r.ec == std::errc() && r.ptr == text.data() + text.size() && std::isnan(v)) return v;
        fail(context, "expected a number or the bits of a NaN, found \"" + text + "\"");
    }
    if (kind != Kind::Number) fail(context, "expected a number, found " + describe(kind));
    if (text == "NaN") return std::numeric_limits<float>::quiet_NaN();
    if (text == "Infinity") return std::numeric_limits<float>::infinity();
    if (text == "-Infinity") return -std::numeric_limits<float>::infinity();
    float v = 0;
    auto r = std::from_chars(text.data(), text.data() + text.size(), v);
    if (r.ec == std::errc::result_out_of_range) {
        // from_chars reports subnormals as out of range; strtof rounds them correctly.
        v = std::strtof(text.c_str(), nullptr);
        if (std::isinf(v)) fail(context, "number " + text + " does not fit a float");
        return v;
    }
    if (r.ec != std::errc() || r.ptr != text.data() + text.size()) fail(context, "expected a number, found " + text);
    return v;
}

const std::string& Value::asString(std::string_view context) const {
    if (kind != Kind::String) fail(context, "expected a string, found " + describe(kind));
    return text;
}

Document parseDocument(std::string name, std::string text) {
    Document doc;
    doc.source = std::make_unique<SourceText>(SourceText{std::move(name), std::move(text)});
    rapidjson::StringStream stream(doc.source->text.c_str());
    TreeBuilder builder(stream, doc.source.get());
    rapidjson::Reader reader;
    rapidjson::ParseResult result = reader.Parse<kParseFlags>(stream, builder);
    if (result.IsError()) {
        throw JsonError(doc.source->where(result.Offset()) + ": " +
                        rapidjson::GetParseError_En(result.Code()));
    }
    doc.root = std::move(builder.root);
    return doc;
}

}  // namespace q3::json
