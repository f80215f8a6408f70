#include "help_text.h"

#include <sstream>

namespace q3::cli {

namespace {

constexpr size_t kTextColumn = 28;
constexpr size_t kLineWidth = 80;

std::vector<std::string> splitWords(const std::string& text) {
    std::vector<std::string> words;
    std::istringstream in(text);
    for (std::string w; in >> w;) words.push_back(w);
    return words;
}

// "  <head><padding><text wrapped at kLineWidth, continued at kTextColumn>"
std::string formatEntry(const std::string& head, const std::string& text) {
    std::string out = "  " + head;
    size_t column = out.size();
    if (column + 2 > kTextColumn) {
        out += "  ";
        column += 2;
    } else {
        out.append(kTextColumn - column, ' ');
        column = kTextColumn;
    }
    bool lineStart = true;
    for (const std::string& word : splitWords(text)) {
        if (!lineStart && column + 1 + word.size() > kLineWidth) {
            out += "\n" + std::string(kTextColumn, ' ');
            column = kTextColumn;
            lineStart = true;
        }
        if (!lineStart) {
            out += ' ';
            ++column;
        }
        out += word;
        column += word.size();
        lineStart = false;
    }
    return out + "\n";
}

std::string usageHeader() {
    return "Usage: q3map2 [common options...] -STAGE [stage options...] MAPFILE\n"
           "       q3map2 -help [stage]\n\n";
}

std::string commonSection(std::span<const OptionInfo> common) {
    std::string out = "Common Options:\n";
    for (const OptionInfo& o : common) out += formatOptionEntry(o);
    return out;
}

}  // namespace

std::string formatOptionEntry(const OptionInfo& option) {
    std::string head;
    for (const std::string& name : option.names) {
        if (!head.empty()) head += ", ";
        OptionInfo alias = option;
        alias.names = {name};
        head += alias.usage();
    }
    std::string text = option.help + " (default: " + option.defaultText + ")";
    if (!option.implemented) text += " [not implemented yet]";
    return formatEntry(head, text);
}

std::string formatGeneralHelp(std::span<const OptionInfo> common, std::span<const StageDescription> stages) {
    std::string out = usageHeader() + commonSection(common) + "\nStages:\n";
    for (const StageDescription& s : stages)
        out += formatEntry(s.name, s.title + (s.available ? "" : " [not implemented yet]"));
    return out;
}

std::string formatStageHelp(std::span<const OptionInfo> common, const StageDescription& stage) {
    std::string out = usageHeader() + commonSection(common) + "\n" + stage.title + ":\n";
    out += formatEntry(stage.name + " [options] " + stage.fileUsage,
                       std::string("Switch that enters this stage") + (stage.available ? "" : " [not implemented yet]"));
    for (const OptionInfo& o : stage.options) out += formatOptionEntry(o);
    return out;
}

}  // namespace q3::cli
