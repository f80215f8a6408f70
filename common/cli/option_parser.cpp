#include "option_parser.h"

#include "ascii_case.h"
#include "edit_distance.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace q3::cli {

namespace {

std::optional<double> parseInteger(const std::string& text) {
    long long value = 0;
    const char* first = text.data();
    const char* last = text.data() + text.size();
    auto [end, ec] = std::from_chars(first, last, value);
    if (ec != std::errc() || end != last || text.empty()) return std::nullopt;
    if (value < std::numeric_limits<int>::min() || value > std::numeric_limits<int>::max()) return std::nullopt;
    return static_cast<double>(value);
}

std::optional<double> parseFloat(const std::string& text) {
    if (text.empty() || std::isspace(static_cast<unsigned char>(text[0]))) return std::nullopt;
    errno = 0;
    char* end = nullptr;
    double value = std::strtod(text.c_str(), &end);
    if (end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(value)) return std::nullopt;
    if (std::fabs(value) > std::numeric_limits<float>::max()) return std::nullopt;
    return value;
}

std::optional<double> parseNumber(ArgKind kind, const std::string& text) {
    return kind == ArgKind::Int ? parseInteger(text) : parseFloat(text);
}

std::vector<std::string> allNames(std::span<const OptionInfo> options) {
    std::vector<std::string> names;
    for (const OptionInfo& o : options) names.insert(names.end(), o.names.begin(), o.names.end());
    return names;
}

std::string valueCountText(const OptionInfo& option) {
    size_t n = static_cast<size_t>(option.requiredArgs);
    return n == 1 ? "1 value" : std::to_string(n) + " values";
}

}  // namespace

int findOption(std::span<const OptionInfo> options, std::string_view name) {
    for (size_t i = 0; i < options.size(); ++i)
        for (const std::string& n : options[i].names)
            if (equalsNoCase(n, name)) return static_cast<int>(i);
    return -1;
}

std::string closestName(std::string_view typed, std::span<const std::string> candidates) {
    std::string best;
    size_t bestDistance = std::numeric_limits<size_t>::max();
    for (const std::string& c : candidates) {
        size_t d = editDistance(typed, c);
        if (d < bestDistance) {
            bestDistance = d;
            best = c;
        }
    }
    // A typo changes a few characters; beyond that a suggestion is noise.
    size_t limit = std::max<size_t>(2, typed.size() / 3);
    return bestDistance <= limit ? best : std::string();
}

std::vector<ArgValue> readValues(const OptionInfo& option, std::span<const std::string> args, size_t& pos) {
    std::vector<ArgValue> values;
    const std::string& name = args[pos];
    ++pos;
    for (size_t k = 0; k < option.args.size(); ++k) {
        const ArgSpec& spec = option.args[k];
        bool required = static_cast<int>(k) < option.requiredArgs;
        if (pos >= args.size()) {
            if (!required) break;
            throw UsageError(name + " needs " + valueCountText(option) + " (" + option.usage() + ")");
        }
        const std::string& text = args[pos];
        ArgValue value{text, 0};
        if (spec.kind != ArgKind::Text) {
            std::optional<double> number = parseNumber(spec.kind, text);
            if (!number) {
                // An optional value is only taken when it is there; anything else is the next option.
                if (!required) break;
                throw UsageError(name + ": '" + text + "' is not " +
                                 (spec.kind == ArgKind::Int ? "an integer" : "a number") + " (" + option.usage() + ")");
            }
            if (!spec.range.contains(*number))
                throw UsageError(name + ": " + text + " is out of range (" + spec.range.describe() + ")");
            value.number = *number;
        } else if (!required && !text.empty() && text[0] == '-') {
            break;
        }
        values.push_back(std::move(value));
        ++pos;
    }
    return values;
}

std::vector<ParsedOption> parseArguments(std::span<const OptionInfo> options, std::span<const std::string> args,
                                         const ParseContext& context) {
    std::vector<ParsedOption> parsed;
    size_t pos = 0;
    while (pos < args.size()) {
        const std::string& token = args[pos];
        if (token.size() < 2 || token[0] != '-')
            throw UsageError("unexpected argument '" + token + "': the map file must be the last argument");
        int index = findOption(options, token);
        if (index < 0) {
            if (!context.stage.empty()) {
                if (findOption(context.commonOptions, token) >= 0)
                    throw UsageError("common option " + token + " must come before the stage switch " + context.stage);
                for (const std::string& s : context.stageSwitches)
                    if (equalsNoCase(s, token))
                        throw UsageError("only one stage per run: " + token + " given after " + context.stage);
            }
            std::vector<std::string> names = allNames(options);
            if (context.stage.empty())  // before the stage switch, a typo may be of a stage name
                names.insert(names.end(), context.stageSwitches.begin(), context.stageSwitches.end());
            std::string suggestion = closestName(token, names);
            if (!suggestion.empty())
                throw UsageError("unknown option '" + token + "'; did you mean '" + suggestion + "'?");
            std::string helpCommand = context.stage.empty() ? "q3map2 -help" : "q3map2 -help " + context.stage.substr(1);
            throw UsageError("unknown option '" + token + "' (see " + helpCommand + ")");
        }
        const OptionInfo& option = options[static_cast<size_t>(index)];
        if (!option.implemented)
            throw UsageError(token + " is a q3map2 option this build does not implement yet");
        ParsedOption item;
        item.index = static_cast<size_t>(index);
        item.values = readValues(option, args, pos);
        parsed.push_back(std::move(item));
    }
    return parsed;
}

}  // namespace q3::cli
