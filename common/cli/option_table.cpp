#include "option_table.h"

#include <array>
#include <charconv>

namespace q3::cli {

bool Range::contains(double v) const {
    if (min && (minExclusive ? v <= *min : v < *min)) return false;
    if (max && (maxExclusive ? v >= *max : v > *max)) return false;
    return true;
}

std::string Range::describe() const {
    if (min && max && !minExclusive && !maxExclusive)
        return "must be between " + formatNumber(*min) + " and " + formatNumber(*max);
    std::string text;
    if (min) text = std::string("must be ") + (minExclusive ? "> " : ">= ") + formatNumber(*min);
    if (max) {
        text += text.empty() ? "must be " : " and ";
        text += std::string(maxExclusive ? "< " : "<= ") + formatNumber(*max);
    }
    return text.empty() ? "any number" : text;
}

std::string OptionInfo::usage() const {
    std::string text = name();
    for (size_t k = 0; k < args.size(); ++k) {
        bool optional = static_cast<int>(k) >= requiredArgs;
        text += optional ? " [<" + args[k].placeholder + ">]" : " <" + args[k].placeholder + ">";
    }
    return text;
}

std::string formatNumber(double value) {
    std::array<char, 64> buffer{};
    // Values come from float fields; printing them as float gives "0.25", not "0.25000000000000".
    float asFloat = static_cast<float>(value);
    auto result = static_cast<double>(asFloat) == value
                      ? std::to_chars(buffer.data(), buffer.data() + buffer.size(), asFloat)
                      : std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
    return std::string(buffer.data(), result.ptr);
}

}  // namespace q3::cli
