// Option tables of -shprobe / -shimage and their positional command-line forms.
#include <cmath>
#include <cstdlib>

#include "sh_tools.h"

namespace q3::shtools {
namespace {

// A finite number, or a usage error naming the stage and what was expected.
float parseCoordinate(const std::string& text, const char* stage, const char* what) {
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(v))
        throw cli::UsageError(std::string(stage) + ": " + what + " \"" + text + "\" is not a number");
    return static_cast<float>(v);
}

}  // namespace

const cli::OptionTable<ShProbeOptions>& shProbeOptionTable() {
    using O = ShProbeOptions;
    using cli::ArgKind;
    using cli::Range;
    static const cli::OptionTable<O> table = {
        cli::custom<O>({"-pos"}, {{ArgKind::Float, "X", Range::any()}, {ArgKind::Float, "Y", Range::any()},
                                  {ArgKind::Float, "Z", Range::any()}},
                       3, "required", "World position of the probe (or give X Y Z after the map)", cli::kImplemented,
                       [](O& o, std::span<const cli::ArgValue> v) {
                           for (int i = 0; i < 3; ++i) o.position[i] = static_cast<float>(v[size_t(i)].number);
                           o.positionSet = true;
                       }),
    };
    return table;
}

const cli::OptionTable<ShImageOptions>& shImageOptionTable() {
    using O = ShImageOptions;
    using cli::ArgKind;
    using cli::Range;
    static const cli::OptionTable<O> table = {
        cli::textValue<O>({"-out"}, &O::output, "PNG file to write (or give it after the map)", cli::kImplemented,
                          "file", "required"),
        cli::custom<O>({"-z"}, {{ArgKind::Float, "Z", Range::any()}}, 1, "middle of the grid",
                       "World height of the probes drawn (interpolated between grid layers)", cli::kImplemented,
                       [](O& o, std::span<const cli::ArgValue> v) {
                           o.height = static_cast<float>(v[0].number);
                           o.heightSet = true;
                       }),
        cli::intValue<O>({"-probesize"}, &O::probePixels, Range::between(4, 256),
                         "Pixels per probe (each side of its square)", cli::kImplemented),
        cli::floatValue<O>({"-exposure"}, &O::exposure, Range::positive(),
                           "Tone mapping: displayed = 1 - exp(-F * irradiance)", cli::kImplemented),
    };
    return table;
}

std::string parseShProbeArguments(std::span<const std::string> args, ShProbeOptions& options) {
    if (args.size() != 4) throw cli::UsageError("-shprobe: expected MAP.bsp X Y Z");
    for (int i = 0; i < 3; ++i) options.position[i] = parseCoordinate(args[size_t(i) + 1], "-shprobe", "coordinate");
    options.positionSet = true;
    return args[0];
}

std::string parseShImageArguments(std::span<const std::string> args, ShImageOptions& options) {
    if (args.size() != 2 && args.size() != 3) throw cli::UsageError("-shimage: expected MAP.bsp OUT.png [Z]");
    options.output = args[1];
    if (args.size() == 3) {
        options.height = parseCoordinate(args[2], "-shimage", "height");
        options.heightSet = true;
    }
    return args[0];
}

}  // namespace q3::shtools
