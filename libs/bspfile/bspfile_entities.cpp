// The entity lump: "{ "key" "value" ... }" blocks, parsed the way the engines' tokenizer reads them
// (quoted or bare tokens, // and /* */ comments, a NUL ends the text).
#include "ascii_case.h"
#include "bspfile_internal.h"

#include <algorithm>

namespace q3::bsp {

namespace {

struct Token {
    std::string text;
    int line = 0;
    bool quoted = false;
};

// Splits entity text into tokens, tracking line numbers for messages.
class EntityTokenizer {
public:
    EntityTokenizer(std::string_view text, const std::string& name) : text_(text.substr(0, text.find('\0'))), name_(name) {}

    // False at the end of the text.
    bool next(Token& token) {
        skipSpaceAndComments();
        if (pos_ >= text_.size()) return false;
        token.line = line_;
        token.text.clear();
        if (text_[pos_] == '"') {
            token.quoted = true;
            const size_t close = text_.find('"', pos_ + 1);
            if (close == std::string_view::npos) error(token.line, "unterminated quoted string");
            token.text.assign(text_.substr(pos_ + 1, close - pos_ - 1));
            line_ += static_cast<int>(std::count(token.text.begin(), token.text.end(), '\n'));
            pos_ = close + 1;
            return true;
        }
        token.quoted = false;
        if (text_[pos_] == '{' || text_[pos_] == '}') {
            token.text.assign(1, text_[pos_++]);
            return true;
        }
        while (pos_ < text_.size() && !isSpace(text_[pos_]) && text_[pos_] != '"' && text_[pos_] != '{' &&
               text_[pos_] != '}')
            token.text += text_[pos_++];
        return true;
    }

    [[noreturn]] void error(int line, const std::string& what) const {
        detail::failLump(name_, LUMP_ENTITIES, "line " + std::to_string(line) + ": " + what);
    }

    int line() const { return line_; }

private:
    static bool isSpace(char c) { return static_cast<unsigned char>(c) <= ' '; }

    void skipSpaceAndComments() {
        while (pos_ < text_.size()) {
            const char c = text_[pos_];
            if (c == '\n') {
                ++line_;
                ++pos_;
            } else if (isSpace(c)) {
                ++pos_;
            } else if (text_.substr(pos_, 2) == "//") {
                while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
            } else if (text_.substr(pos_, 2) == "/*") {
                const int opened = line_;
                const size_t close = text_.find("*/", pos_ + 2);
                if (close == std::string_view::npos) error(opened, "unterminated /* comment");
                line_ += static_cast<int>(std::count(text_.begin() + static_cast<ptrdiff_t>(pos_),
                                                     text_.begin() + static_cast<ptrdiff_t>(close), '\n'));
                pos_ = close + 2;
            } else {
                return;
            }
        }
    }

    std::string_view text_;
    const std::string& name_;
    size_t pos_ = 0;
    int line_ = 1;
};

bool isBrace(const Token& t, char brace) { return !t.quoted && t.text.size() == 1 && t.text[0] == brace; }

}  // namespace

const std::string* Entity::find(std::string_view key) const {
    for (const auto& [k, v] : pairs)
        if (equalsNoCase(k, key)) return &v;
    return nullptr;
}

std::string Entity::value(std::string_view key, std::string_view fallback) const {
    const std::string* v = find(key);
    return v ? *v : std::string(fallback);
}

void Entity::set(std::string_view key, std::string_view newValue) {
    for (auto& [k, v] : pairs) {
        if (equalsNoCase(k, key)) {
            v.assign(newValue);
            return;
        }
    }
    pairs.emplace_back(std::string(key), std::string(newValue));
}

bool Entity::erase(std::string_view key) {
    auto it = std::find_if(pairs.begin(), pairs.end(), [&](const auto& p) { return equalsNoCase(p.first, key); });
    if (it == pairs.end()) return false;
    pairs.erase(it);
    return true;
}

std::string_view Entity::classname() const {
    const std::string* v = find("classname");
    return v ? std::string_view(*v) : std::string_view();
}

std::vector<Entity> parseEntities(std::string_view text, const std::string& name) {
    EntityTokenizer tokens(text, name);
    std::vector<Entity> entities;
    Token token;
    while (tokens.next(token)) {
        if (!isBrace(token, '{')) tokens.error(token.line, "expected '{' but found \"" + token.text + "\"");
        const int opened = token.line;
        Entity entity;
        for (;;) {
            if (!tokens.next(token))
                tokens.error(opened, "entity " + std::to_string(entities.size()) + " is not closed by '}'");
            if (isBrace(token, '}')) break;
            if (isBrace(token, '{')) tokens.error(token.line, "'{' inside an entity (missing '}'?)");
            std::string key = std::move(token.text);
            const int keyLine = token.line;
            if (!tokens.next(token) || isBrace(token, '}') || isBrace(token, '{'))
                tokens.error(keyLine, "key \"" + key + "\" has no value");
            entity.pairs.emplace_back(std::move(key), std::move(token.text));
        }
        entities.push_back(std::move(entity));
    }
    return entities;
}

std::string unparseEntities(const std::vector<Entity>& entities) {
    std::string out;
    for (const Entity& e : entities) {
        out += "{\n";
        for (const auto& [key, value] : e.pairs) {
            out += '"';
            out += key;
            out += "\" \"";
            out += value;
            out += "\"\n";
        }
        out += "}\n";
    }
    out += '\0';
    return out;
}

void injectCommandLine(Entity& worldspawn, const std::string& commandLine) {
    std::string value = worldspawn.value("_q3map2_cmdline");
    value = value.empty() ? commandLine : value + "; " + commandLine;
    worldspawn.set("_q3map2_cmdline", value);
    worldspawn.set("_q3map2_version", kCompilerVersion);
}

}  // namespace q3::bsp
