#include "engine_run.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <stdexcept>

#include "test_data.h"

namespace q3::enginetest {
namespace fs = std::filesystem;

namespace {

std::string fromEnvironment(const char* variable, const char* fallback) {
    const char* value = std::getenv(variable);
    return value && *value ? value : fallback;
}

RunResult run(std::string command) {
    RunResult result;
    result.command = std::move(command);
    result.status = test::runCommand(result.command, &result.output);
    return result;
}

fs::path requireFile(const fs::path& path, const std::string& what) {
    if (!fs::is_regular_file(path)) {
        ADD_FAILURE() << what << " missing: " << path;
        throw std::runtime_error(what + " missing");
    }
    return path;
}

}  // namespace

fs::path engineToolsDir() {
    const fs::path dir = fromEnvironment("Q3_ENGINE_TOOLS", Q3MAP_ENGINE_TOOLS);
    requireFile(dir / "q3-load-check", "engine check script q3-load-check (set Q3_ENGINE_TOOLS)");
    requireFile(dir / "q3-screenshot", "engine check script q3-screenshot (set Q3_ENGINE_TOOLS)");
    return dir;
}

fs::path engineDataRoot() { return fromEnvironment("Q3_ENGINE_DATA", Q3MAP_ENGINE_DATA); }

fs::path oacmpPk3() {
    return requireFile(test::openArenaBase() / "baseoa" / "z_oacmp-volume1-v3.pk3", "oacmp package");
}

fs::path stageOacmpMap(const fs::path& root, const std::string& name) {
    const fs::path gameDir = root / "baseoa";
    fs::create_directories(gameDir / "maps");
    fs::path source;
    for (const fs::path& p : test::oacmpMapSources())
        if (p.stem() == name) source = p;
    requireFile(source, name + ".map source");
    fs::copy_file(test::realBsp(name), gameDir / "maps" / (name + ".bsp"), fs::copy_options::overwrite_existing);
    fs::copy_file(source, gameDir / "maps" / (name + ".map"), fs::copy_options::overwrite_existing);
    return gameDir;
}

namespace {
// One shell command from words, each quoted.
std::string commandLine(const std::vector<std::string>& words) {
    std::string line;
    for (const std::string& word : words) {
        if (!line.empty()) line += ' ';
        line += shellQuote(word);
    }
    return line;
}

// Engine scripts are run again after a failure that is not about the map, up to this many times in
// all. DarkPlaces' client (Debian 20180908 under Xvfb and llvmpipe) segfaults at random right after
// connecting, on shipped maps as on ours and in every screenshot mode, at times in every second
// run; engines started elsewhere on the machine can also race this one for an X display or a port.
constexpr int kEngineAttempts = 6;

// Only exit status 1 (an engine failed) is retried, and not for a strict complaint about the map;
// a fault of the map itself fails every attempt. 2 (usage) and 3 (a program or data missing) are
// final. The output keeps the failed attempts ahead of the last one.
RunResult runEngineScript(const std::vector<std::string>& words, const std::string& environment = {}) {
    std::string earlier;
    for (int attempt = 1;; ++attempt) {
        RunResult result = run(environment + commandLine(words));
        const bool done = result.status != 1 || result.output.find("strict:") != std::string::npos ||
                           attempt == kEngineAttempts;
        if (done) {
            result.output = earlier + result.output;
            return result;
        }
        earlier += "(attempt " + std::to_string(attempt) + " failed:\n" + result.output + ")\n";
    }
}
}  // namespace

RunResult runLight(const fs::path& gameDir, const std::string& name, const std::vector<std::string>& options) {
    std::vector<std::string> words = {test::q3map2Exe().string(), "-fs_basepath", test::openArenaBase().string(),
                                      "-fs_game", "baseoa", "-light"};
    words.insert(words.end(), options.begin(), options.end());
    words.push_back("maps/" + name + ".bsp");
    std::string command = "cd ";
    command += shellQuote(gameDir.string());
    command += " && ";
    command += commandLine(words);
    return run(command);
}

fs::path relightOacmpMap(const fs::path& root, const std::string& name, const std::vector<std::string>& options,
                         std::string* output) {
    const fs::path gameDir = stageOacmpMap(root, name);
    RunResult r = runLight(gameDir, name, options);
    if (r.status != 0) {
        ADD_FAILURE() << r.command << " exited with " << r.status << "\n" << r.output;
        throw std::runtime_error("q3map2 -light failed");
    }
    if (output) *output = std::move(r.output);
    return gameDir / "maps" / (name + ".bsp");
}

RunResult expectLoads(const fs::path& bsp, const std::string& engines, const fs::path& logDir) {
    RunResult load = runLoadCheck(bsp, engines, logDir);
    std::cout << load.output;
    EXPECT_EQ(load.status, 0) << load.command;
    const size_t engineCount = size_t(std::count(engines.begin(), engines.end(), ',')) + 1;
    EXPECT_EQ(linesWith(load.output, " OK ").size(), engineCount) << "every engine ran: " << engines;
    return load;
}

RunResult runLoadCheck(const fs::path& bsp, const std::string& engines, const fs::path& logDir) {
    fs::create_directories(logDir);
    return runEngineScript({(engineToolsDir() / "q3-load-check").string(), "-s", "-e", engines, "-b",
                            engineDataRoot().string(), "-p", oacmpPk3().string(), "-l", logDir.string(),
                            bsp.string()});
}

RunResult runScreenshot(const fs::path& bsp, const std::string& engines, const std::string& modes,
                        const fs::path& prefix, const fs::path& logDir) {
    return runScreenshotWith(bsp, engines, modes, prefix, logDir, {});
}

RunResult runScreenshotWith(const fs::path& bsp, const std::string& engines, const std::string& modes,
                            const fs::path& prefix, const fs::path& logDir, const std::vector<std::string>& options,
                            const fs::path& ioq3) {
    fs::create_directories(logDir);
    // 640x480 keeps the software rasteriser quick; the measures are shares and means, not sizes.
    std::vector<std::string> words = {(engineToolsDir() / "q3-screenshot").string(), "-s", "-e", engines, "-m", modes,
                                      "-S", "640x480", "-b", engineDataRoot().string(), "-p", oacmpPk3().string(),
                                      "-o", prefix.string(), "-l", logDir.string()};
    words.insert(words.end(), options.begin(), options.end());
    words.push_back(bsp.string());
    return runEngineScript(words, ioq3.empty() ? std::string() : "IOQ3=" + shellQuote(ioq3.string()) + " ");
}

fs::path screenshotPath(const fs::path& prefix, const std::string& engine, const std::string& mode) {
    fs::path path = prefix;
    path += "-";
    path += engine;
    path += "-";
    path += mode;
    path += ".png";
    return path;
}

std::vector<std::string> linesWith(const std::string& text, const std::string& needle) {
    std::vector<std::string> found;
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);)
        if (line.find(needle) != std::string::npos) found.push_back(line);
    return found;
}

std::vector<double> darkPlacesGridSums(const std::string& text, const std::string& marker) {
    std::vector<double> sums;
    for (const std::string& line : linesWith(text, marker)) {
        const size_t at = line.rfind("= '");
        float r, g, b;
        if (at != std::string::npos && std::sscanf(line.c_str() + at + 3, "%f %f %f", &r, &g, &b) == 3)
            sums.push_back(double(r) + g + b);
    }
    return sums;
}

std::filesystem::path copyForEngines(const std::filesystem::path& bsp, const std::filesystem::path& engineDir,
                                     const std::string& name) {
    std::filesystem::create_directories(engineDir);
    const std::filesystem::path copy = engineDir / (name + ".bsp");
    std::filesystem::copy_file(bsp, copy, std::filesystem::copy_options::overwrite_existing);
    return copy;
}

}  // namespace q3::enginetest
