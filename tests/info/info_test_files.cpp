#include "info_test_files.h"

#include "test_data.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>

namespace q3::test {
namespace fs = std::filesystem;

Bytes readBytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return Bytes(std::istreambuf_iterator<char>(in), {});
}

void writeBytes(const fs::path& path, const Bytes& bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

int32_t get32(const Bytes& b, size_t at) {
    int32_t v;
    std::memcpy(&v, b.data() + at, 4);
    return v;
}
float getFloat(const Bytes& b, size_t at) {
    float v;
    std::memcpy(&v, b.data() + at, 4);
    return v;
}
void put32(Bytes& b, size_t at, int32_t v) { std::memcpy(b.data() + at, &v, 4); }
void putFloat(Bytes& b, size_t at, float v) { std::memcpy(b.data() + at, &v, 4); }

LumpEntry lumpEntry(const Bytes& file, int lump) {
    size_t at = 8 + static_cast<size_t>(lump) * 8;
    return {get32(file, at), get32(file, at + 4)};
}

void setLumpEntry(Bytes& file, int lump, LumpEntry entry) {
    size_t at = 8 + static_cast<size_t>(lump) * 8;
    put32(file, at, entry.offset);
    put32(file, at + 4, entry.length);
}

Bytes lumpData(const Bytes& file, int lump) {
    LumpEntry e = lumpEntry(file, lump);
    return Bytes(file.begin() + e.offset, file.begin() + e.offset + e.length);
}

size_t endOfLumps(const Bytes& file) {
    size_t end = 0;
    for (int i = 0; i < kQ3Lumps; ++i) {
        LumpEntry e = lumpEntry(file, i);
        if (e.length > 0) end = std::max(end, static_cast<size_t>(e.offset) + static_cast<size_t>(e.length));
    }
    return (end + 3) & ~size_t(3);
}

namespace {

void appendAligned(Bytes& out, const Bytes& data) {
    out.insert(out.end(), data.begin(), data.end());
    while (out.size() % 4) out.push_back(0);
}

}  // namespace

Bytes withShLump(const Bytes& v46, const Bytes& sh) {
    const int entries = 19;
    Bytes out(8 + entries * 8, 0);
    std::memcpy(out.data(), "IBSP", 4);
    put32(out, 4, 47);
    for (int lump = 0; lump < entries; ++lump) {
        Bytes data = lump < kQ3Lumps ? lumpData(v46, lump) : (lump == 18 ? sh : Bytes{});
        LumpEntry e{data.empty() ? 0 : static_cast<int32_t>(out.size()), static_cast<int32_t>(data.size())};
        setLumpEntry(out, lump, e);
        appendAligned(out, data);
    }
    return out;
}

Bytes withBspxLump(const Bytes& v46, const std::string& name, const Bytes& data) {
    Bytes out(v46.begin(), v46.begin() + static_cast<ptrdiff_t>(std::min(v46.size(), endOfLumps(v46))));
    while (out.size() % 4) out.push_back(0);
    size_t directory = out.size();
    out.resize(directory + 8 + 32, 0);
    std::memcpy(out.data() + directory, "BSPX", 4);
    put32(out, directory + 4, 1);
    std::memcpy(out.data() + directory + 8, name.data(), std::min<size_t>(name.size(), 23));
    put32(out, directory + 8 + 24, static_cast<int32_t>(out.size()));
    put32(out, directory + 8 + 28, static_cast<int32_t>(data.size()));
    appendAligned(out, data);
    return out;
}

Bytes shGridLump(const float mins[3], const float size[3], const int32_t bounds[3],
                 const std::vector<std::array<float, 3>>& coeff0) {
    Bytes out(40 + coeff0.size() * 108, 0);
    for (int i = 0; i < 3; ++i) {
        putFloat(out, 4 * i, mins[i]);
        putFloat(out, 12 + 4 * i, size[i]);
        put32(out, 24 + 4 * i, bounds[i]);
    }
    put32(out, 36, static_cast<int32_t>(coeff0.size()));
    for (size_t p = 0; p < coeff0.size(); ++p)
        for (int k = 0; k < 9; ++k)
            for (int c = 0; c < 3; ++c)
                putFloat(out, 40 + p * 108 + static_cast<size_t>(k * 3 + c) * 4,
                         k == 0 ? coeff0[p][c] : coeff0[p][c] * 0.1f);
    return out;
}

RunResult runQ3map2(const std::vector<std::string>& args, const fs::path& scratch) {
    fs::path dir = scratch / "run";
    fs::create_directories(dir);
    std::string command = "'" + q3map2Exe().string() + "'";
    for (const std::string& a : args) command += " '" + a + "'";
    fs::path out = dir / "stdout.txt", err = dir / "stderr.txt";
    RunResult result;
    result.exitCode = runCommand("{ " + command + " >'" + out.string() + "' 2>'" + err.string() + "'; }");
    Bytes o = readBytes(out), e = readBytes(err);
    result.out.assign(o.begin(), o.end());
    result.err.assign(e.begin(), e.end());
    return result;
}

}  // namespace q3::test
