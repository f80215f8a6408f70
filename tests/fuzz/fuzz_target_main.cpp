// The libFuzzer harness, compiled once per target with Q3_FUZZ_ENTRY naming its entry
// (fuzz_entries.h). The scratch folder is made under $TMPDIR on start and removed when the process
// ends normally (libFuzzer finishes with exit(), which destroys statics); tools/fuzz.sh points
// TMPDIR at a folder it removes itself, for runs that end in a crash.
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

class Harness {
public:
    Harness() : entry_(q3::fuzz::findFuzzEntry(Q3_FUZZ_ENTRY)) {
        if (!entry_) {
            std::fprintf(stderr, "fuzz target: no entry named '%s'\n", Q3_FUZZ_ENTRY);
            std::abort();
        }
        const char* tmp = std::getenv("TMPDIR");
        std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/q3fuzz-" + Q3_FUZZ_ENTRY + "-XXXXXX";
        if (!::mkdtemp(pattern.data())) {
            std::perror("fuzz target: cannot create a scratch folder");
            std::abort();
        }
        context_.scratch = pattern;
    }
    ~Harness() {
        std::error_code ec;
        std::filesystem::remove_all(context_.scratch, ec);
    }
    Harness(const Harness&) = delete;
    Harness& operator=(const Harness&) = delete;

    void run(const uint8_t* data, size_t size) const { entry_->run(std::span<const uint8_t>(data, size), context_); }

private:
    const q3::fuzz::FuzzEntry* entry_;
    q3::fuzz::FuzzContext context_;
};

// libFuzzer's C interface leaves no other place for the per-process state than a static.
const Harness& harness() {
    static const Harness instance;
    return instance;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    harness();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    harness().run(data, size);
    return 0;
}
