#include "test_data.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <sys/wait.h>
#include <unistd.h>

namespace q3::test {
namespace fs = std::filesystem;

namespace {

std::vector<fs::path> findFiles(const fs::path& root, const std::string& extension, const std::string& folder) {
    std::vector<fs::path> out;
    std::error_code ec;
    for (auto it = fs::recursive_directory_iterator(root, ec); !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
        const fs::path& p = it->path();
        if (!it->is_regular_file()) continue;
        std::string ext = p.extension().string();
        std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
        if (ext == extension && p.parent_path().filename() == folder) out.push_back(p);
    }
    std::sort(out.begin(), out.end());
    return out;
}

fs::path cacheRoot() {
    const char* env = std::getenv("Q3MAP_DATA_CACHE");
    fs::path root;
    if (env && *env) root = env;
    else if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) root = fs::path(xdg) / "q3map2-data";
    else root = fs::path(std::getenv("HOME") ? std::getenv("HOME") : "/root") / ".cache" / "q3map2-data";
    return root;
}

}  // namespace

fs::path dataCache() {
    fs::path root = cacheRoot();
    if (!fs::exists(root / ".complete-v2")) {
        ADD_FAILURE() << "OpenArena test data missing at " << root << ": run tools/fetch-openarena.sh";
        throw std::runtime_error("test data missing");
    }
    return root;
}

fs::path openArenaBase() { return dataCache() / "openarena"; }

std::vector<fs::path> realBspsForRegistration() {
    fs::path root = cacheRoot();
    if (!fs::exists(root / ".complete-v2")) return {};
    std::vector<fs::path> all = findFiles(root / "loose", ".bsp", "maps");
    const int stride = Q3MAP_TEST_MAP_STRIDE;
    if (stride <= 1 || all.empty()) return all;
    std::vector<fs::path> sample;
    size_t largest = 0;
    for (size_t i = 0; i < all.size(); ++i) {
        if (fs::file_size(all[i]) > fs::file_size(all[largest])) largest = i;
        if (i % static_cast<size_t>(stride) == 0) sample.push_back(all[i]);
    }
    if (largest % static_cast<size_t>(stride) != 0) sample.push_back(all[largest]);
    return sample;
}

bool realBspsAreSampled() { return Q3MAP_TEST_MAP_STRIDE > 1; }

std::vector<fs::path> allRealBsps() { return findFiles(dataCache() / "loose", ".bsp", "maps"); }

std::vector<fs::path> oacmpMapSources() { return findFiles(dataCache() / "loose", ".map", "maps"); }

std::vector<fs::path> oacmpMapSourcesForRegistration() {
    const fs::path root = cacheRoot();
    if (!fs::exists(root / ".complete-v2")) return {};
    return findFiles(root / "loose", ".map", "maps");
}

fs::path realBsp(const std::string& mapName) {
    for (const fs::path& p : allRealBsps())
        if (p.stem() == mapName) return p;
    ADD_FAILURE() << "no real BSP named " << mapName;
    throw std::runtime_error("missing map " + mapName);
}

std::vector<fs::path> allShaderScripts() { return findFiles(dataCache() / "loose", ".shader", "scripts"); }

fs::path tempDir() {
    const ::testing::UnitTest* unit = ::testing::UnitTest::GetInstance();
    const ::testing::TestInfo* info = unit->current_test_info();
    std::string name;
    if (info) {
        name = std::string(info->test_suite_name()) + "." + info->name();
    } else {
        // Suite-level set-up: ctest may run several tests of the suite at once, each in its own
        // process, so the folder is made unique per process.
        const ::testing::TestSuite* suite = unit->current_test_suite();
        name = std::string(suite ? suite->name() : "global") + ".setup-" + std::to_string(::getpid());
    }
    std::replace(name.begin(), name.end(), '/', '_');
    fs::path dir = fs::path(Q3MAP_BINARY_DIR) / "test-tmp" / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

fs::path q3map2Exe() { return fs::path(Q3MAP_BINARY_DIR) / "q3map2" / "q3map2"; }

int runCommand(const std::string& commandLine, std::string* output) {
    std::string cmd = commandLine + " 2>&1";
    FILE* pipe = ::popen(cmd.c_str(), "r");
    if (!pipe) return -1;
    std::array<char, 4096> buffer{};
    std::string text;
    size_t n;
    while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) text.append(buffer.data(), n);
    int status = ::pclose(pipe);
    if (output) *output = text;
    if (WIFEXITED(status)) return WEXITSTATUS(status);
    return WIFSIGNALED(status) ? 128 + WTERMSIG(status) : -1;
}

std::string shellQuote(const std::string& word) {
    std::string quoted = "'";
    for (char c : word) {
        if (c == '\'') quoted += "'\\''";
        else quoted += c;
    }
    return quoted + "'";
}

}  // namespace q3::test
