// The machine-readable summary a stage writes with -stats FILE.json: phase times, work counts,
// warnings, grid sizes and free-form counters. The format is described by docs/stats-schema.json
// (JSON Schema draft 4); keys always come out in the same order, counters sorted by name.
//
//   q3::RunStats stats;
//   stats.stage = "light"; stats.map = bspPath.string();
//   ...
//   stats.recordPhases(timer); stats.warnings = log.warningCount();
//   q3::writeRunStats(options.statsPath, stats);
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "phase_timer.h"

namespace q3 {

// The "format" member, raised when the layout changes incompatibly.
inline constexpr int kRunStatsFormat = 1;

struct GridDimensions {
    int x = 0, y = 0, z = 0;
    uint64_t points() const { return uint64_t(x) * uint64_t(y) * uint64_t(z); }
};

struct RunStats {
    std::string stage;  // "light", "bsp", ...
    std::string map;    // the map or BSP the stage worked on
    int threads = 0;
    std::vector<PhaseTime> phases;
    double totalSeconds = 0;
    uint64_t raysTraced = 0;
    uint64_t luxels = 0;
    int warnings = 0;
    std::optional<GridDimensions> legacyGrid;  // the classic light grid (lump 15)
    std::optional<GridDimensions> shGrid;      // the L2 SH grid (lump 18)
    std::map<std::string, int64_t> counters;   // anything else worth counting

    // Copies the timer's phases and its elapsed time.
    void recordPhases(const PhaseTimer& timer);
};

// The summary as JSON text (two-space indented, ending with a newline). Non-finite times are
// written as 0 so that the file always validates.
std::string runStatsToJson(const RunStats& stats);
// Writes the summary through writeFileAtomic; throws FileError when it cannot.
void writeRunStats(const std::filesystem::path& path, const RunStats& stats);

}  // namespace q3
