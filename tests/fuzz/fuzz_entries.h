// The fuzz entry points: one function per input format, shared by the libFuzzer targets
// (fuzz_target_main.cpp) and the regression test that replays every input that once crashed
// (tests/fuzz_regressions). An entry returns normally when the library accepted the input or
// rejected it with its documented exception type; anything else (a crash, a sanitizer report, an
// undocumented exception, a broken invariant) escapes and fails the run.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <stdexcept>
#include <string_view>

#include "bspfile.h"

namespace q3::fuzz {

// Where an entry may write files (pk3 archives, JSON folders). One per process, emptied by nobody
// but its owner; entries only create and overwrite files below it.
struct FuzzContext {
    std::filesystem::path scratch;
};

// Thrown when an input breaks a property the libraries promise (e.g. a read-write-read round trip
// that is not stable). Deliberately not one of the libraries' error types, so it is never caught.
struct PropertyViolation : std::logic_error {
    using std::logic_error::logic_error;
};

using EntryFunction = void (*)(std::span<const uint8_t> input, const FuzzContext& context);

struct FuzzEntry {
    std::string_view name;    // target name: fuzz_<name> executable, regressions/<name>/ folder
    EntryFunction run;
    std::string_view covers;  // one line for docs and --help
};

// Every entry, in a fixed order.
std::span<const FuzzEntry> fuzzEntries();
// nullptr when there is no entry of that name.
const FuzzEntry* findFuzzEntry(std::string_view name);

// The entries themselves (fuzz_entries_*.cpp).
void fuzzBsp(std::span<const uint8_t> input, const FuzzContext& context);
void fuzzShRuntime(std::span<const uint8_t> input, const FuzzContext& context);
void fuzzMap(std::span<const uint8_t> input, const FuzzContext& context);
void fuzzMapBsp(std::span<const uint8_t> input, const FuzzContext& context);
void fuzzShader(std::span<const uint8_t> input, const FuzzContext& context);
void fuzzJson(std::span<const uint8_t> input, const FuzzContext& context);
void fuzzJsonPack(std::span<const uint8_t> input, const FuzzContext& context);
void fuzzPk3(std::span<const uint8_t> input, const FuzzContext& context);
void fuzzPrt(std::span<const uint8_t> input, const FuzzContext& context);
void fuzzWorldLights(std::span<const uint8_t> input, const FuzzContext& context);
void fuzzLightCache(std::span<const uint8_t> input, const FuzzContext& context);

// Throws PropertyViolation when -vis's reader refuses `text` (a portal file -bsp wrote).
void checkPortalFileReads(std::string_view text);

// The BSP whose unpacked JSON folder json_pack edits (and whose files seed the json targets): the
// bspfile tests' synthetic map with an SH grid in lump 18, an extra BSPX lump, and no lightmap
// pages (LightBytes.json would be megabytes).
bsp::Bsp jsonPackSourceBsp();

// The json_pack input format: the first line names one file of the folder, the rest replaces its
// content. Split here so the seed tool writes exactly what the entry reads.
constexpr char kJsonPackSeparator = '\n';

}  // namespace q3::fuzz
