#include "num_file.h"

#include "json_error.h"
#include "json_value.h"

#include <rapidjson/error/en.h>
#include <rapidjson/reader.h>

#include <charconv>

namespace q3::json {

namespace {

// Runs a RapidJSON SAX parse of `text` (comments, trailing commas, numbers as strings) into
// `handler`; a failure becomes one JsonError at its line and column, with the handler's own message
// when it gave one.
template <typename Handler>
void parseStreaming(const std::string& name, const std::string& text, Handler& handler) {
    constexpr unsigned flags = rapidjson::kParseCommentsFlag | rapidjson::kParseTrailingCommasFlag |
                               rapidjson::kParseNumbersAsStringsFlag | rapidjson::kParseStopWhenDoneFlag;
    rapidjson::StringStream stream(text.c_str());
    rapidjson::Reader reader;
    rapidjson::ParseResult result = reader.Parse<flags>(stream, handler);
    if (result.IsError()) {
        SourceText source{name, text};
        std::string what = handler.error.empty() ? rapidjson::GetParseError_En(result.Code()) : handler.error;
        throw JsonError(source.where(result.Offset()) + ": " + what);
    }
}

}  // namespace

namespace {

// Accepts exactly: { (key: { "Num": integer })* }
class NumHandler : public rapidjson::BaseReaderHandler<rapidjson::UTF8<>, NumHandler> {
public:
    NumHandler(int64_t minValue, int64_t maxValue) : min_(minValue), max_(maxValue) {}

    bool Default() { return fail("unexpected value"); }
    bool StartObject() {
        if (depth_ == 0) { depth_ = 1; return true; }
        if (depth_ == 1 && state_ == State::AfterKey) { depth_ = 2; state_ = State::InRecord; return true; }
        return fail("unexpected object");
    }
    bool EndObject(rapidjson::SizeType) {
        if (depth_ == 2) {
            if (state_ != State::HaveNum) return fail("record " + record_ + " has no \"Num\" member");
            depth_ = 1;
            state_ = State::BetweenRecords;
            return true;
        }
        if (depth_ == 1 && state_ != State::AfterKey) { depth_ = 0; done_ = true; return true; }
        return fail("unexpected end of object");
    }
    bool Key(const char* str, rapidjson::SizeType length, bool) {
        if (depth_ == 1) { record_.assign(str, length); state_ = State::AfterKey; return true; }
        if (depth_ == 2 && state_ == State::InRecord && std::string_view(str, length) == "Num") {
            state_ = State::ExpectNum;
            return true;
        }
        return fail("record " + record_ + ": unexpected member \"" + std::string(str, length) + "\"");
    }
    bool RawNumber(const char* str, rapidjson::SizeType length, bool) {
        if (depth_ != 2 || state_ != State::ExpectNum) return fail("unexpected number");
        int64_t v = 0;
        auto r = std::from_chars(str, str + length, v);
        if (r.ec != std::errc() || r.ptr != str + length)
            return fail("record " + record_ + ": \"Num\" must be an integer, found " + std::string(str, length));
        if (v < min_ || v > max_)
            return fail("record " + record_ + ": \"Num\" " + std::to_string(v) + " is out of range " +
                        std::to_string(min_) + ".." + std::to_string(max_));
        values.push_back(v);
        state_ = State::HaveNum;
        return true;
    }

    std::vector<int64_t> values;
    std::string error;
    bool done_ = false;

private:
    enum class State { BetweenRecords, AfterKey, InRecord, ExpectNum, HaveNum };
    bool fail(std::string message) {
        error = std::move(message);
        return false;
    }
    int64_t min_, max_;
    int depth_ = 0;
    State state_ = State::BetweenRecords;
    std::string record_;
};

}  // namespace

std::vector<int64_t> readNumFile(const std::string& name, const std::string& text, int64_t minValue, int64_t maxValue) {
    NumHandler handler(minValue, maxValue);
    parseStreaming(name, text, handler);
    return std::move(handler.values);
}

}  // namespace q3::json

namespace q3::json {

const std::vector<int64_t>* FlatRecord::find(std::string_view key) const {
    for (const auto& [k, v] : members)
        if (k == key) return &v;
    return nullptr;
}

namespace {

// Accepts exactly: { (key: { (key: integer | nested arrays of integers)* })* }
class FlatRecordHandler : public rapidjson::BaseReaderHandler<rapidjson::UTF8<>, FlatRecordHandler> {
public:
    explicit FlatRecordHandler(const std::function<std::string(const FlatRecord&)>& onRecord) : onRecord_(onRecord) {}

    bool Default() { return fail("unexpected value"); }
    bool StartObject() {
        if (depth_ == 0) { depth_ = 1; return true; }
        if (depth_ == 1 && haveName_) { depth_ = 2; record_.members.clear(); return true; }
        return fail(record_.name + ": unexpected object");
    }
    bool Key(const char* str, rapidjson::SizeType length, bool) {
        if (depth_ == 1) { record_.name.assign(str, length); haveName_ = true; return true; }
        if (depth_ == 2 && arrayDepth_ == 0) {
            record_.members.emplace_back(std::string(str, length), std::vector<int64_t>{});
            inMember_ = true;
            return true;
        }
        return fail(record_.name + ": unexpected member");
    }
    bool StartArray() {
        if (!inMember_) return fail(record_.name + ": unexpected array");
        ++arrayDepth_;
        return true;
    }
    bool EndArray(rapidjson::SizeType) {
        if (--arrayDepth_ == 0) inMember_ = false;
        return true;
    }
    bool RawNumber(const char* str, rapidjson::SizeType length, bool) {
        if (!inMember_) return fail(record_.name + ": unexpected number");
        int64_t v = 0;
        auto r = std::from_chars(str, str + length, v);
        if (r.ec != std::errc() || r.ptr != str + length)
            return fail(record_.name + "." + record_.members.back().first + ": expected an integer, found " +
                        std::string(str, length));
        record_.members.back().second.push_back(v);
        if (arrayDepth_ == 0) inMember_ = false;
        return true;
    }
    bool EndObject(rapidjson::SizeType) {
        if (depth_ == 2) {
            depth_ = 1;
            haveName_ = false;
            std::string problem = onRecord_(record_);
            return problem.empty() ? true : fail(problem);
        }
        depth_ = 0;
        return true;
    }

    std::string error;

private:
    bool fail(std::string message) {
        error = std::move(message);
        return false;
    }
    const std::function<std::string(const FlatRecord&)>& onRecord_;
    FlatRecord record_;
    int depth_ = 0;
    int arrayDepth_ = 0;
    bool haveName_ = false;
    bool inMember_ = false;
};

}  // namespace

void readFlatRecords(const std::string& name, const std::string& text,
                     const std::function<std::string(const FlatRecord&)>& onRecord) {
    FlatRecordHandler handler(onRecord);
    parseStreaming(name, text, handler);
}

}  // namespace q3::json
