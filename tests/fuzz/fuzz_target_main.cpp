// The libFuzzer harness, compiled once per target with Q3_FUZZ_ENTRY naming its entry
// (fuzz_entries.h). The scratch folder is made under $TMPDIR on start and removed on a normal exit.
#include "fuzz_entries.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

#ifndef Q3_FUZZ_ENTRY
#error "Q3_FUZZ_ENTRY must name the entry this target runs"
#endif

namespace {

struct Harness {
    const q3::fuzz::FuzzEntry* entry = nullptr;
    q3::fuzz::FuzzContext context;
};

void removeScratch();

// libFuzzer's C interface leaves no other place for the per-process state than a static.
Harness& harness() {
    static Harness instance = [] {
        Harness h;
        h.entry = q3::fuzz::findFuzzEntry(Q3_FUZZ_ENTRY);
        if (!h.entry) {
            std::fprintf(stderr, "fuzz target: no entry named '%s'\n", Q3_FUZZ_ENTRY);
            std::abort();
        }
        const char* tmp = std::getenv("TMPDIR");
        std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/q3fuzz-" + Q3_FUZZ_ENTRY + "-XXXXXX";
        if (!::mkdtemp(pattern.data())) {
            std::perror("fuzz target: cannot create a scratch folder");
            std::abort();
        }
        h.context.scratch = pattern;
        std::atexit(removeScratch);
        return h;
    }();
    return instance;
}

void removeScratch() {
    std::error_code ec;
    std::filesystem::remove_all(harness().context.scratch, ec);
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    harness();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    Harness& h = harness();
    h.entry->run(std::span<const uint8_t>(data, size), h.context);
    return 0;
}
