// The option table: one entry per command-line option of a stage (or of the common options),
// describing its names, arguments, default, help text and whether this build implements it, and
// binding it to a field of a typed options struct. The parser and the -help text are both
// generated from such a table, so they cannot disagree.
#pragma once

#include <functional>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace q3::cli {

// A malformed command line. main prints the message and exits with code 2.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

enum class ArgKind { Int, Float, Text };

// Allowed values of a numeric argument; both ends optional.
struct Range {
    std::optional<double> min, max;
    bool minExclusive = false;
    bool maxExclusive = false;

    static Range any() { return {}; }
    static Range positive() { return {0.0, std::nullopt, true, false}; }
    static Range atLeast(double v) { return {v, std::nullopt, false, false}; }
    static Range atMost(double v) { return {std::nullopt, v, false, false}; }
    static Range between(double lo, double hi) { return {lo, hi, false, false}; }

    bool contains(double v) const;
    std::string describe() const;  // "must be > 0", "must be between 1 and 8", ...
};

struct ArgSpec {
    ArgKind kind = ArgKind::Float;
    std::string placeholder;  // shown in help: "N", "F", "path"
    Range range;
};

// A parsed argument: the text as given and, for numeric kinds, its value.
struct ArgValue {
    std::string text;
    double number = 0;
};

// The part of an option that the parser and the help text need; independent of the options type.
struct OptionInfo {
    std::vector<std::string> names;  // primary name first, then aliases, each with its leading '-'
    std::vector<ArgSpec> args;
    int requiredArgs = 0;            // args past this count are optional (taken when they parse)
    std::string defaultText;         // shown as "(default: ...)"
    std::string help;
    bool implemented = true;

    const std::string& name() const { return names.front(); }
    std::string usage() const;  // "-gridsh <X> <Y> <Z>", optional ones in brackets
};

constexpr bool kImplemented = true;
constexpr bool kNotImplemented = false;

template <class Options>
struct Option {
    OptionInfo info;
    // Stores the parsed values into the options struct. May throw UsageError for checks that
    // involve more than one value (a power of two, a relation between two arguments).
    std::function<void(Options&, std::span<const ArgValue>)> apply;
};

template <class Options>
using OptionTable = std::vector<Option<Options>>;

template <class Options>
std::vector<OptionInfo> describe(const OptionTable<Options>& table) {
    std::vector<OptionInfo> out;
    out.reserve(table.size());
    for (const Option<Options>& o : table) out.push_back(o.info);
    return out;
}

// Shortest text that reads back as the same value ("0.25", "7500", "1e-05").
std::string formatNumber(double value);

// Table builders. Defaults are read from a default-constructed Options, so the struct's member
// initialisers are the one place where a default lives.
template <class Options>
Option<Options> flag(std::vector<std::string> names, bool Options::*member, std::string help, bool implemented,
                     bool value = true) {
    // "on" when the default state is the one this flag selects (-nofastpoint: off, -nodeluxe: on).
    OptionInfo info{std::move(names), {}, 0, (Options{}.*member) == value ? "on" : "off", std::move(help),
                    implemented};
    return {std::move(info), [member, value](Options& o, std::span<const ArgValue>) { o.*member = value; }};
}

template <class Options>
Option<Options> floatValue(std::vector<std::string> names, float Options::*member, Range range, std::string help,
                           bool implemented, std::string placeholder = "F") {
    OptionInfo info{std::move(names), {{ArgKind::Float, std::move(placeholder), range}}, 1,
                    formatNumber(Options{}.*member), std::move(help), implemented};
    return {std::move(info),
            [member](Options& o, std::span<const ArgValue> v) { o.*member = static_cast<float>(v[0].number); }};
}

template <class Options>
Option<Options> intValue(std::vector<std::string> names, int Options::*member, Range range, std::string help,
                         bool implemented, std::string placeholder = "N") {
    OptionInfo info{std::move(names), {{ArgKind::Int, std::move(placeholder), range}}, 1,
                    formatNumber(Options{}.*member), std::move(help), implemented};
    return {std::move(info),
            [member](Options& o, std::span<const ArgValue> v) { o.*member = static_cast<int>(v[0].number); }};
}

template <class Options>
Option<Options> textValue(std::vector<std::string> names, std::string Options::*member, std::string help,
                          bool implemented, std::string placeholder, std::string defaultText) {
    OptionInfo info{std::move(names), {{ArgKind::Text, std::move(placeholder), {}}}, 1, std::move(defaultText),
                    std::move(help), implemented};
    return {std::move(info), [member](Options& o, std::span<const ArgValue> v) { o.*member = v[0].text; }};
}

// Anything else: explicit argument list, default text and store function.
template <class Options>
Option<Options> custom(std::vector<std::string> names, std::vector<ArgSpec> args, int requiredArgs,
                       std::string defaultText, std::string help, bool implemented,
                       std::function<void(Options&, std::span<const ArgValue>)> apply) {
    OptionInfo info{std::move(names), std::move(args), requiredArgs, std::move(defaultText), std::move(help),
                    implemented};
    return {std::move(info), std::move(apply)};
}

}  // namespace q3::cli
