#include "doc_blocks.h"

#include <sstream>
#include <stdexcept>

namespace q3::test {

namespace {

constexpr std::string_view kMarkerStart = "<!-- quick-start creates:";
constexpr std::string_view kMarkerEnd = "-->";

std::vector<std::string> splitLines(std::string_view text) {
    std::vector<std::string> lines;
    std::string current;
    for (char c : text) {
        if (c == '\n') {
            lines.push_back(current);
            current.clear();
        } else if (c != '\r') {
            current += c;
        }
    }
    if (!current.empty()) lines.push_back(current);
    return lines;
}

std::string trimmed(const std::string& s) {
    size_t first = s.find_first_not_of(" \t");
    if (first == std::string::npos) return "";
    size_t last = s.find_last_not_of(" \t");
    return s.substr(first, last - first + 1);
}

}  // namespace

std::vector<QuickStartBlock> quickStartBlocks(std::string_view markdown, const std::string& name) {
    std::vector<std::string> lines = splitLines(markdown);
    std::vector<QuickStartBlock> blocks;
    for (size_t i = 0; i < lines.size(); ++i) {
        std::string marker = trimmed(lines[i]);
        if (marker.rfind(kMarkerStart, 0) != 0) continue;
        auto where = [&](size_t at) { return name + ":" + std::to_string(at + 1) + ": "; };
        if (marker.size() < kMarkerStart.size() + kMarkerEnd.size() ||
            marker.compare(marker.size() - kMarkerEnd.size(), kMarkerEnd.size(), kMarkerEnd) != 0)
            throw std::runtime_error(where(i) + "quick-start marker does not end with -->");
        QuickStartBlock block;
        block.line = static_cast<int>(i + 1);
        std::istringstream files(marker.substr(kMarkerStart.size(),
                                               marker.size() - kMarkerStart.size() - kMarkerEnd.size()));
        for (std::string f; files >> f;) block.creates.push_back(f);
        if (block.creates.empty()) throw std::runtime_error(where(i) + "quick-start marker lists no outputs");
        if (i + 1 >= lines.size() || trimmed(lines[i + 1]) != "```sh")
            throw std::runtime_error(where(i) + "quick-start marker is not followed by a ```sh block");
        size_t end = i + 2;
        while (end < lines.size() && trimmed(lines[end]) != "```") block.script += lines[end++] + "\n";
        if (end == lines.size()) throw std::runtime_error(where(i) + "quick-start block is never closed");
        blocks.push_back(std::move(block));
        i = end;
    }
    return blocks;
}

std::vector<std::string> commandLines(const std::string& script) {
    std::vector<std::string> out;
    for (const std::string& line : splitLines(script)) {
        std::string t = trimmed(line);
        if (!t.empty() && t[0] != '#') out.push_back(t);
    }
    return out;
}

}  // namespace q3::test
