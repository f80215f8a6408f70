#include "script.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>

namespace q3 {

Script::Script(std::string_view text, std::string name, bool splitPunctuation)
    : text_(text), name_(std::move(name)), splitPunctuation_(splitPunctuation) {}

bool Script::skipSpaceAndComments(bool crossLine) {
    while (pos_ < text_.size()) {
        char c = text_[pos_];
        if (c == '\n') {
            if (!crossLine) return false;
            ++line_;
            ++pos_;
        } else if (static_cast<unsigned char>(c) <= ' ') {
            ++pos_;
        } else if (c == '/' && pos_ + 1 < text_.size() && text_[pos_ + 1] == '/') {
            while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
        } else if (c == '/' && pos_ + 1 < text_.size() && text_[pos_ + 1] == '*') {
            pos_ += 2;
            while (pos_ < text_.size() && !(text_[pos_] == '*' && pos_ + 1 < text_.size() && text_[pos_ + 1] == '/')) {
                if (text_[pos_] == '\n') {
                    if (!crossLine) return false;
                    ++line_;
                }
                ++pos_;
            }
            pos_ = std::min(pos_ + 2, text_.size());
        } else {
            return true;
        }
    }
    return false;
}

static bool isPunctuation(char c) { return c == '{' || c == '}' || c == '(' || c == ')'; }

bool Script::next(bool crossLine) {
    token_.clear();
    quoted_ = false;
    if (!skipSpaceAndComments(crossLine)) return false;
    tokenLine_ = line_;
    char c = text_[pos_];
    if (c == '"') {
        quoted_ = true;
        const size_t start = ++pos_;
        while (pos_ < text_.size() && text_[pos_] != '"') {
            if (text_[pos_] == '\n') ++line_;
            ++pos_;
        }
        if (pos_ >= text_.size()) fail("unterminated quoted string");
        token_.assign(text_.data() + start, pos_ - start);
        ++pos_;
        return true;
    }
    if (splitPunctuation_ && isPunctuation(c)) {
        token_ = c;
        ++pos_;
        return true;
    }
    const size_t start = pos_;
    while (pos_ < text_.size()) {
        c = text_[pos_];
        if (static_cast<unsigned char>(c) <= ' ') break;
        if (c == '/' && pos_ + 1 < text_.size() && (text_[pos_ + 1] == '/' || text_[pos_ + 1] == '*')) break;
        if (splitPunctuation_ && isPunctuation(c)) break;
        ++pos_;
    }
    token_.assign(text_.data() + start, pos_ - start);
    return true;
}

bool Script::tokenAvailableOnLine() {
    size_t savedPos = pos_;
    int savedLine = line_;
    bool available = skipSpaceAndComments(false);
    pos_ = savedPos;
    line_ = savedLine;
    return available;
}

void Script::skipLine() {
    while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
}

void Script::skipBracedBlock() {
    int depth = 1;
    while (depth > 0) {
        if (!next(true)) fail("unexpected end of file inside a { } block");
        if (quoted_) continue;
        if (token_ == "{") ++depth;
        else if (token_ == "}") --depth;
    }
}

const std::string& Script::expectAny(std::string_view what) {
    if (!next(true)) fail("unexpected end of file, expected " + std::string(what));
    return token_;
}

void Script::expect(std::string_view text) {
    if (!next(true)) fail("unexpected end of file, expected '" + std::string(text) + "'");
    if (!equalsNoCase(token_, text)) fail("expected '" + std::string(text) + "', found '" + token_ + "'");
}

double Script::expectNumber(std::string_view what) {
    if (!next(true)) fail("unexpected end of file, expected " + std::string(what));
    double value = 0;
    if (!parseNumber(token_, value)) fail("expected a number for " + std::string(what) + ", found '" + token_ + "'");
    return value;
}

int Script::expectInt(std::string_view what) {
    double value = expectNumber(what);
    if (value != std::floor(value) || std::fabs(value) > 2147483647.0)
        fail("expected an integer for " + std::string(what) + ", found '" + token_ + "'");
    return static_cast<int>(value);
}

void Script::fail(std::string_view message) const {
    throw ScriptError(name_ + ":" + std::to_string(tokenLine_) + ": " + std::string(message));
}

bool parseNumber(std::string_view s, double& out) {
    if (s.empty()) return false;
    const char* begin = s.data();
    const char* end = s.data() + s.size();
    if (*begin == '+') ++begin;
    auto result = std::from_chars(begin, end, out);
    return result.ec == std::errc() && result.ptr == end && std::isfinite(out);
}

}  // namespace q3
