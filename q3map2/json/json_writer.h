// Writing q3map2-style JSON: 4-space indentation, arrays on one line, floats in the shortest form
// that reads back to the same bits.
#pragma once

#include "file_io.h"

#include <rapidjson/prettywriter.h>
#include <rapidjson/stringbuffer.h>

#include <cstdint>
#include <string>
#include <string_view>

namespace q3::json {

class Writer {
public:
    // Without a sink the text accumulates in memory (finish() returns it); with one it is passed
    // on in large pieces as records complete (drain()), so big lumps stream to disk.
    explicit Writer(AtomicFileWriter* sink = nullptr);

    void startObject() { writer_.StartObject(); }
    void endObject() { writer_.EndObject(); }
    void startArray() { writer_.StartArray(); }
    void endArray() { writer_.EndArray(); }
    void key(std::string_view name) { writer_.Key(name.data(), static_cast<rapidjson::SizeType>(name.size())); }
    // "Prefix#index" member names, as q3map2 names records.
    void indexedKey(std::string_view prefix, size_t index);

    void integer(int64_t v) { writer_.Int64(v); }
    void number(float v);
    void string(std::string_view s) { writer_.String(s.data(), static_cast<rapidjson::SizeType>(s.size())); }

    void floats(const float* v, int n);
    template <typename T>
    void integers(const T* v, int n) {
        startArray();
        for (int i = 0; i < n; ++i) integer(static_cast<int64_t>(v[i]));
        endArray();
    }

    // Passes the text written so far to the sink once it is large; call between records.
    void drain();
    // The finished document, ending with a newline (empty when it went to the sink).
    std::string finish();

private:
    AtomicFileWriter* sink_;
    rapidjson::StringBuffer buffer_;
    rapidjson::PrettyWriter<rapidjson::StringBuffer> writer_;
};

// Bits of the NaN that "NaN" in JSON stands for; other NaNs are written as "0x7FC00001"-style strings.
constexpr uint32_t kCanonicalNaNBits = 0x7FC00000u;

// Shortest text that parses back to exactly `v` ("1.0", "0.1", "NaN", "-Infinity").
std::string formatFloat(float v);

}  // namespace q3::json
