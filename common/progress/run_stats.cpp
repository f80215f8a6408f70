#include "run_stats.h"

#include <cmath>
#include <rapidjson/prettywriter.h>
#include <rapidjson/stringbuffer.h>

#include "file_io.h"

namespace q3 {

void RunStats::recordPhases(const PhaseTimer& timer) {
    phases = timer.phases();
    totalSeconds = timer.elapsedSeconds();
}

namespace {

using Writer = rapidjson::PrettyWriter<rapidjson::StringBuffer>;

double finiteOrZero(double value) { return std::isfinite(value) ? value : 0.0; }

void writeKey(Writer& w, const char* key) { w.Key(key); }

void writeString(Writer& w, const std::string& text) {
    w.String(text.data(), static_cast<rapidjson::SizeType>(text.size()), true);
}

void writeGrid(Writer& w, const char* key, const std::optional<GridDimensions>& grid) {
    writeKey(w, key);
    if (!grid) {
        w.Null();
        return;
    }
    w.StartObject();
    writeKey(w, "size");
    w.StartArray();
    w.Int(grid->x);
    w.Int(grid->y);
    w.Int(grid->z);
    w.EndArray();
    writeKey(w, "points");
    w.Uint64(grid->points());
    w.EndObject();
}

}  // namespace

std::string runStatsToJson(const RunStats& stats) {
    rapidjson::StringBuffer buffer;
    Writer w(buffer);
    w.SetIndent(' ', 2);
    w.StartObject();
    writeKey(w, "format");
    w.Int(kRunStatsFormat);
    writeKey(w, "stage");
    writeString(w, stats.stage);
    writeKey(w, "map");
    writeString(w, stats.map);
    writeKey(w, "threads");
    w.Int(stats.threads);
    writeKey(w, "totalSeconds");
    w.Double(finiteOrZero(stats.totalSeconds));
    writeKey(w, "phases");
    w.StartArray();
    for (const PhaseTime& phase : stats.phases) {
        w.StartObject();
        writeKey(w, "name");
        writeString(w, phase.name);
        writeKey(w, "seconds");
        w.Double(finiteOrZero(phase.seconds));
        w.EndObject();
    }
    w.EndArray();
    writeKey(w, "raysTraced");
    w.Uint64(stats.raysTraced);
    writeKey(w, "luxels");
    w.Uint64(stats.luxels);
    writeKey(w, "warnings");
    w.Int(stats.warnings);
    writeKey(w, "grids");
    w.StartObject();
    writeGrid(w, "legacy", stats.legacyGrid);
    writeGrid(w, "sh", stats.shGrid);
    w.EndObject();
    writeKey(w, "counters");
    w.StartObject();
    for (const auto& [name, value] : stats.counters) {
        w.Key(name.data(), static_cast<rapidjson::SizeType>(name.size()), true);
        w.Int64(value);
    }
    w.EndObject();
    w.EndObject();
    return std::string(buffer.GetString(), buffer.GetSize()) + "\n";
}

void writeRunStats(const std::filesystem::path& path, const RunStats& stats) {
    writeFileAtomic(path, runStatsToJson(stats));
}

}  // namespace q3
