#include "feedback_protocol.h"

#include <charconv>

namespace q3 {

FeedbackLevel feedbackLevelFor(LogLevel level) {
    switch (level) {
    case LogLevel::Verbose: return FeedbackLevel::Verbose;
    case LogLevel::Info: return FeedbackLevel::Standard;
    case LogLevel::Warning: return FeedbackLevel::Warning;
    case LogLevel::Error: return FeedbackLevel::Error;
    }
    return FeedbackLevel::Standard;
}

std::string feedbackLevelText(FeedbackLevel level) { return std::to_string(static_cast<int>(level)); }

static std::optional<uint16_t> parsePort(std::string_view text) {
    if (text.empty()) return std::nullopt;
    unsigned value = 0;
    auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size() || value == 0 || value > 65535)
        return std::nullopt;
    return static_cast<uint16_t>(value);
}

std::optional<FeedbackAddress> parseFeedbackAddress(std::string_view text) {
    FeedbackAddress address;
    std::string_view portText;
    if (!text.empty() && text.front() == '[') {
        size_t close = text.find(']');
        if (close == std::string_view::npos || close == 1) return std::nullopt;
        address.host = std::string(text.substr(1, close - 1));
        std::string_view rest = text.substr(close + 1);
        if (!rest.empty()) {
            if (rest.front() != ':') return std::nullopt;
            portText = rest.substr(1);
            if (portText.empty()) return std::nullopt;
        }
    } else {
        size_t colon = text.rfind(':');
        // More than one colon without brackets is ambiguous (a bare IPv6 address with a port).
        if (colon != std::string_view::npos && text.find(':') != colon) return std::nullopt;
        address.host = std::string(text.substr(0, colon));
        if (colon != std::string_view::npos) {
            portText = text.substr(colon + 1);
            if (portText.empty()) return std::nullopt;
        }
    }
    if (address.host.empty() || address.host.find_first_of("[] \t") != std::string::npos)
        return std::nullopt;
    if (!portText.empty()) {
        auto port = parsePort(portText);
        if (!port) return std::nullopt;
        address.port = *port;
    }
    return address;
}

// Length of the valid UTF-8 sequence starting at s[i], or 0 when there is none.
static size_t utf8SequenceLength(std::string_view s, size_t i) {
    auto byte = [&](size_t k) { return static_cast<unsigned char>(s[k]); };
    unsigned char lead = byte(i);
    size_t length;
    uint32_t code;
    if (lead < 0x80) return 1;
    if (lead >= 0xC2 && lead <= 0xDF) { length = 2; code = lead & 0x1F; }
    else if (lead >= 0xE0 && lead <= 0xEF) { length = 3; code = lead & 0x0F; }
    else if (lead >= 0xF0 && lead <= 0xF4) { length = 4; code = lead & 0x07; }
    else return 0;
    if (i + length > s.size()) return 0;
    for (size_t k = 1; k < length; ++k) {
        if ((byte(i + k) & 0xC0) != 0x80) return 0;
        code = (code << 6) | (byte(i + k) & 0x3F);
    }
    // Overlong forms, surrogates and code points past U+10FFFF are not valid UTF-8.
    if ((length == 3 && code < 0x800) || (length == 4 && (code < 0x10000 || code > 0x10FFFF)))
        return 0;
    if (code >= 0xD800 && code <= 0xDFFF) return 0;
    // U+FFFE and U+FFFF are not XML characters.
    if (code == 0xFFFE || code == 0xFFFF) return 0;
    return length;
}

std::string toXmlText(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (size_t i = 0; i < text.size();) {
        unsigned char c = static_cast<unsigned char>(text[i]);
        if (c < 0x20) {
            if (c == '\t' || c == '\n' || c == '\r') out += static_cast<char>(c);
            ++i;
            continue;
        }
        size_t length = utf8SequenceLength(text, i);
        if (length > 0) {
            out.append(text.substr(i, length));
            i += length;
        } else {
            // Latin-1 byte: U+0080..U+00FF in two bytes.
            out += static_cast<char>(0xC0 | (c >> 6));
            out += static_cast<char>(0x80 | (c & 0x3F));
            ++i;
        }
    }
    return out;
}

std::string frameChunk(std::string_view text) {
    uint32_t length = static_cast<uint32_t>(text.size() + 1);
    std::string out;
    out.reserve(4 + length);
    for (int shift = 0; shift < 32; shift += 8) out += static_cast<char>((length >> shift) & 0xFF);
    out.append(text);
    out += '\0';
    return out;
}

std::string frameChunks(std::string_view text) {
    std::string out;
    for (size_t pos = 0; pos < text.size(); pos += kMaxChunkText)
        out += frameChunk(text.substr(pos, kMaxChunkText));
    return out;
}

}  // namespace q3
