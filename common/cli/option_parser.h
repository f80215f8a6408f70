// Parsing an argument list against an option table. The generic part works on OptionInfo only;
// parseOptions() then stores the values through the table's bindings, in command-line order (so a
// later option overrides an earlier one, as in q3map2).
#pragma once

#include "option_table.h"

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace q3::cli {

// What the parser needs to know about the surroundings to word its errors.
struct ParseContext {
    std::string stage;                       // "-light"; empty for the common options
    std::vector<OptionInfo> commonOptions;   // to say "must come before the stage switch"
    std::vector<std::string> stageSwitches;  // to say "only one stage per run"
};

struct ParsedOption {
    size_t index = 0;  // into the table
    std::vector<ArgValue> values;
};

// Case-insensitive lookup of an option by any of its names (q3map2 compares names that way).
// Returns -1 when absent.
int findOption(std::span<const OptionInfo> options, std::string_view name);

// The name among `candidates` closest to `typed` when it is close enough to be a plausible typo,
// else an empty string.
std::string closestName(std::string_view typed, std::span<const std::string> candidates);

// Reads the values of `option`, whose name is at args[pos]; advances pos past them.
// Throws UsageError for missing values, non-numbers and values out of range.
std::vector<ArgValue> readValues(const OptionInfo& option, std::span<const std::string> args, size_t& pos);

// Parses the whole list (no map path in it). Throws UsageError on the first problem.
std::vector<ParsedOption> parseArguments(std::span<const OptionInfo> options, std::span<const std::string> args,
                                         const ParseContext& context);

template <class Options>
void parseOptions(const OptionTable<Options>& table, std::span<const std::string> args, const ParseContext& context,
                  Options& out) {
    std::vector<OptionInfo> infos = describe(table);
    for (const ParsedOption& parsed : parseArguments(infos, args, context))
        table[parsed.index].apply(out, parsed.values);
}

}  // namespace q3::cli
