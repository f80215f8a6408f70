// lightcompare: compares a BSP lit by the reference q3map2 with the same input lit by ours.
//   lightcompare REF.bsp OURS.bsp [--ref2 REF_OTHER_THREADS.bsp] [--map NAME.map]
//                [--basepath DATA --game baseoa] [--json] [--worst N]
// Exit codes: 0 compared, 1 an input could not be read or does not match, 2 usage.
#include <cstdlib>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "light_compare.h"

namespace {

const char* kUsage =
    "usage: lightcompare REF.bsp OURS.bsp [--ref2 REF2.bsp] [--map NAME.map] [--basepath DIR]... [--game GAME]\n"
    "                    [--json] [--worst N]\n"
    "  REF.bsp   lit by the reference q3map2;  OURS.bsp  the same input lit by ours\n"
    "  --ref2    the same input lit again by the reference (another -threads): masks the grid points it repeats\n"
    "  --map     the .map source (light entity origins for the near-light class)\n"
    "  --basepath, --game  the game data (shader scripts for the area-lit and sky-lit classes)\n"
    "  --json    print the figures as JSON;  --worst N  surfaces listed (default 15)\n";

int usage(const std::string& problem) {
    std::cerr << "lightcompare: " << problem << "\n" << kUsage;
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    using namespace q3::conformance;
    std::vector<std::string> positional;
    std::string ref2, mapSource, game = "baseoa";
    std::vector<std::filesystem::path> basePaths;
    bool json = false;
    int worst = 15;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        auto value = [&]() -> std::optional<std::string> {
            if (i + 1 >= argc) return std::nullopt;
            return std::string(argv[++i]);
        };
        if (arg == "--json") {
            json = true;
        } else if (arg == "--ref2" || arg == "--map" || arg == "--basepath" || arg == "--game" || arg == "--worst") {
            std::optional<std::string> v = value();
            if (!v) return usage(arg + " needs a value");
            if (arg == "--ref2") ref2 = *v;
            else if (arg == "--map") mapSource = *v;
            else if (arg == "--basepath") basePaths.emplace_back(*v);
            else if (arg == "--game") game = *v;
            else {
                char* end = nullptr;
                const long n = std::strtol(v->c_str(), &end, 10);
                if (*end || n < 0) return usage("--worst needs a count, got '" + *v + "'");
                worst = int(n);
            }
        } else if (arg == "-h" || arg == "--help") {
            std::cout << kUsage;
            return 0;
        } else if (!arg.empty() && arg[0] == '-') {
            return usage("unknown option " + arg);
        } else {
            positional.push_back(arg);
        }
    }
    if (positional.size() != 2) return usage("expected REF.bsp and OURS.bsp");

    try {
        const LitBsp reference = loadLitBsp(positional[0]);
        const LitBsp ours = loadLitBsp(positional[1]);
        std::optional<LitBsp> reference2;
        if (!ref2.empty()) reference2 = loadLitBsp(ref2);
        const ClassInputs classes = loadClassInputs(reference.bsp, mapSource, basePaths, game);
        CompareOptions options;
        options.worstCount = std::max(worst, 25);
        const Comparison c =
            compareLitBsps(reference, ours, reference2 ? &*reference2 : nullptr, classes, options);
        std::cout << (json ? toJson(c) : toText(c, worst));
    } catch (const std::exception& e) {
        std::cerr << "lightcompare: ERROR: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
