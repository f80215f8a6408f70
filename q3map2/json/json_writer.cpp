#include "json_writer.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace q3::json {

Writer::Writer(AtomicFileWriter* sink) : sink_(sink), writer_(buffer_) {
    writer_.SetIndent(' ', 4);
    writer_.SetFormatOptions(rapidjson::kFormatSingleLineArray);
}

void Writer::indexedKey(std::string_view prefix, size_t index) {
    std::string name(prefix);
    name += '#';
    name += std::to_string(index);
    key(name);
}

std::string formatFloat(float v) {
    if (std::isnan(v)) return "NaN";
    if (std::isinf(v)) return v > 0 ? "Infinity" : "-Infinity";
    char buf[32];
    auto result = std::to_chars(buf, buf + sizeof(buf), v);
    std::string text(buf, result.ptr);
    // Keep integral values recognisable as floats, as q3map2 writes them ("160.0").
    if (text.find_first_of(".e") == std::string::npos) text += ".0";
    return text;
}

void Writer::number(float v) {
    // A NaN with a payload other than the default one cannot be told apart in JSON's NaN, so its
    // bits are written as a hex string (some maps carry such values in unused fields).
    uint32_t bits;
    std::memcpy(&bits, &v, sizeof(bits));
    if (std::isnan(v) && bits != kCanonicalNaNBits) {
        char hex[16];
        std::snprintf(hex, sizeof(hex), "0x%08X", bits);
        string(hex);
        return;
    }
    std::string text = formatFloat(v);
    writer_.RawValue(text.data(), text.size(), rapidjson::kNumberType);
}

void Writer::floats(const float* v, int n) {
    startArray();
    for (int i = 0; i < n; ++i) number(v[i]);
    endArray();
}

void Writer::drain() {
    constexpr size_t kPiece = 1 << 20;
    if (!sink_ || buffer_.GetSize() < kPiece) return;
    sink_->write(buffer_.GetString(), buffer_.GetSize());
    buffer_.Clear();
}

std::string Writer::finish() {
    std::string out(buffer_.GetString(), buffer_.GetSize());
    out += '\n';
    if (!sink_) return out;
    sink_->write(out.data(), out.size());
    buffer_.Clear();
    return {};
}

}  // namespace q3::json
