// Running the reference and our compiler for conformance runs, and the fresh-compile cache.
#include "conformance_pipeline.h"

#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <stdexcept>

#include "file_io.h"
#include "test_data.h"

namespace q3::conformance {
namespace fs = std::filesystem;

namespace {

std::string tail(const std::string& text, size_t lines) {
    size_t pos = text.size();
    for (size_t n = 0; n <= lines && pos > 0; ++n) {
        pos = text.rfind('\n', pos - 1);
        if (pos == std::string::npos) return text;
    }
    return text.substr(pos + 1);
}

ToolRun run(const std::string& commandLine) {
    ToolRun r;
    const auto start = std::chrono::steady_clock::now();
    r.exitCode = test::runCommand(commandLine, &r.output);
    r.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return r;
}

std::string joined(const std::vector<std::string>& args) {
    std::string out;
    for (const std::string& a : args) {
        out += ' ';
        out += test::shellQuote(a);
    }
    return out;
}

void runOrThrow(const std::string& what, const std::string& commandLine, const fs::path& logFile) {
    const ToolRun r = run(commandLine);
    writeFileAtomic(logFile, r.output);
    if (r.exitCode != 0)
        throw std::runtime_error(what + " failed (exit " + std::to_string(r.exitCode) + ", log " + logFile.string() +
                                 "): " + tail(r.output, 5));
}

// Only the inputs of -light stay in a compile's maps/ folder (the portal file and the like go).
void keepLightInputs(const fs::path& maps) {
    for (const fs::directory_entry& e : fs::directory_iterator(maps)) {
        const std::string ext = e.path().extension().string();
        if (ext != ".bsp" && ext != ".srf" && ext != ".map") fs::remove_all(e.path());
    }
}

// `tool` ("ours"/"reference", for messages) runs as `common` (binary and base path options): -bsp
// -meta of a copy of `mapSource` in `work`/maps, then -vis -fast; only the inputs of -light stay.
void compileForLight(const std::string& tool, const std::string& common, const fs::path& mapSource,
                     const fs::path& work) {
    const std::string name = mapSource.stem().string();
    const fs::path map = work / "maps" / (name + ".map");
    fs::copy_file(mapSource, map);
    runOrThrow(tool + " -bsp -meta on " + mapSource.string(),
               "cd " + test::shellQuote(work) + " && " + common + " -bsp -meta " + test::shellQuote(map),
               work / "bsp.log");
    const fs::path bsp = work / "maps" / (name + ".bsp");
    runOrThrow(tool + " -vis -fast on " + bsp.string(),
               "cd " + test::shellQuote(work) + " && " + common + " -vis -fast " + test::shellQuote(bsp),
               work / "vis.log");
    keepLightInputs(work / "maps");
}

}  // namespace

fs::path referenceBinary(const fs::path& fallback) {
    const char* env = std::getenv("Q3MAP2_REFERENCE");
    return env && *env ? fs::path(env) : fallback;
}

std::string fileHash(const fs::path& path) {
    const std::vector<uint8_t> bytes = readFileBytes(path);
    uint64_t h = 0xcbf29ce484222325ull;
    for (uint8_t b : bytes) {
        h ^= b;
        h *= 0x100000001b3ull;
    }
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
    return buf;
}

std::string referenceHash(const fs::path& reference) {
    // Everything in the reference's folder (the wrapper and the binary it runs), by name: a copy
    // with new timestamps keeps its cache, a changed binary gets a new one.
    const fs::path folder = fs::absolute(reference).parent_path();
    std::vector<fs::path> files;
    std::error_code error;
    for (const fs::directory_entry& entry : fs::directory_iterator(folder, error))
        if (entry.is_regular_file()) files.push_back(entry.path());
    if (error || files.empty()) throw FileError(folder.string() + ": cannot list the reference q3map2's folder");
    std::sort(files.begin(), files.end());
    uint64_t h = 0xcbf29ce484222325ull;
    auto mix = [&h](uint8_t b) {
        h ^= b;
        h *= 0x100000001b3ull;
    };
    for (const fs::path& file : files) {
        for (char c : file.filename().string()) mix(static_cast<uint8_t>(c));
        mix(0);
        for (uint8_t b : readFileBytes(file)) mix(b);
    }
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
    return buf;
}

std::string freshCacheKey(const fs::path& reference, const fs::path& mapSource) {
    return mapSource.stem().string() + "-" + referenceHash(reference) + "-" + fileHash(mapSource);
}

fs::path freshCompile(const fs::path& reference, const fs::path& gameBase, const fs::path& dataCache,
                      const fs::path& mapSource) {
    const std::string name = mapSource.stem().string();
    const fs::path root = dataCache / "conformance" / "fresh";
    const fs::path final = root / freshCacheKey(reference, mapSource);
    if (fs::exists(final / "maps" / (name + ".bsp"))) return final;

    std::random_device entropy;
    const fs::path work = root / (".tmp-" + name + "-" + std::to_string(::getpid()) + "-" + std::to_string(entropy()));
    fs::remove_all(work);
    fs::create_directories(work / "maps");
    const std::string common = test::shellQuote(reference) + " -game quake3 -fs_basepath " +
                               test::shellQuote(gameBase) + " -fs_basegame baseoa -threads 2";
    try {
        compileForLight("reference", common, mapSource, work);
    } catch (...) {
        fs::remove_all(work);
        throw;
    }
    std::error_code ec;
    fs::rename(work, final, ec);
    if (ec) fs::remove_all(work);  // another process put its compile there first
    if (!fs::exists(final / "maps" / (name + ".bsp")))
        throw std::runtime_error(final.string() + ": the fresh compile of " + mapSource.string() + " is missing");
    return final;
}

fs::path ownFreshCompile(const fs::path& ours, const fs::path& gameBase, const fs::path& mapSource,
                         const fs::path& dest) {
    fs::remove_all(dest);
    fs::create_directories(dest / "maps");
    compileForLight("ours", test::shellQuote(ours) + " -threads 2 -fs_basepath " + test::shellQuote(gameBase) +
                                " -fs_game baseoa",
                    mapSource, dest);
    return dest;
}

fs::path stageFresh(const fs::path& fresh, const fs::path& dest, const std::string& mapName) {
    fs::remove_all(dest);
    fs::create_directories(dest / "maps");
    for (const char* ext : {".bsp", ".srf", ".map"}) {
        const fs::path from = fresh / "maps" / (mapName + ext);
        if (fs::exists(from)) fs::copy_file(from, dest / "maps" / (mapName + ext));
    }
    return dest / "maps" / (mapName + ".bsp");
}

ToolRun lightWithReference(const fs::path& reference, const fs::path& gameBase, const fs::path& bsp,
                           const std::vector<std::string>& args, int threads) {
    return run(test::shellQuote(reference) + " -game quake3 -fs_basepath " + test::shellQuote(gameBase) +
               " -fs_basegame baseoa -threads " + std::to_string(threads) + " -light" + joined(args) + " " +
               test::shellQuote(bsp));
}

ToolRun lightWithOurs(const fs::path& ours, const fs::path& gameBase, const fs::path& bsp,
                      const std::vector<std::string>& args, int threads) {
    return run(test::shellQuote(ours) + " -threads " + std::to_string(threads) + " -fs_basepath " +
               test::shellQuote(gameBase) + " -fs_game baseoa -light" + joined(args) + " " + test::shellQuote(bsp));
}

}  // namespace q3::conformance
