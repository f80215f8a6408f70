// Tokenizer for id-style text: .shader scripts, .map files, .srf files, arena files.
// Tokens are separated by white space; "quoted strings" are one token; // and /* */ are comments;
// the characters { } ( ) are tokens of their own only when `splitPunctuation` is on (shaders and
// .map files write them separated by spaces anyway, but hand-written files do not always).
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

#include "ascii_case.h"

namespace q3 {

// "<file>:<line>: <what is wrong>"
struct ScriptError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

class Script {
public:
    Script(std::string_view text, std::string name, bool splitPunctuation = true);

    // Reads the next token. With crossLine == false it stops at the end of the current line and
    // returns false there (the line's remaining tokens are exhausted). Returns false at the end.
    bool next(bool crossLine = true);
    // True when another token exists on the current line.
    bool tokenAvailableOnLine();
    // Skips the rest of the current line.
    void skipLine();
    // Skips a balanced { ... } block; the current token must be "{".
    void skipBracedBlock();

    const std::string& token() const { return token_; }
    bool tokenWasQuoted() const { return quoted_; }
    int line() const { return tokenLine_; }
    const std::string& name() const { return name_; }

    // Requires a next token (anywhere) and returns it; throws "unexpected end of file" otherwise.
    const std::string& expectAny(std::string_view what);
    // Requires the next token to equal `text` (case-insensitive).
    void expect(std::string_view text);
    // Next token parsed as a number; throws naming `what` when it is not one.
    double expectNumber(std::string_view what);
    int expectInt(std::string_view what);

    [[noreturn]] void fail(std::string_view message) const;

private:
    bool skipSpaceAndComments(bool crossLine);

    std::string_view text_;
    std::string name_;
    bool splitPunctuation_;
    size_t pos_ = 0;
    int line_ = 1;
    int tokenLine_ = 1;
    std::string token_;
    bool quoted_ = false;
};

// Parses a whole string as a number (no trailing garbage); false when it is not one.
bool parseNumber(std::string_view s, double& out);

}  // namespace q3
