#include "progress_format.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace q3 {

int pacifierStep(std::size_t done, std::size_t total) {
    if (total == 0 || done >= total) return kPacifierSteps;
    // 40 * done fits easily: total is a count of work items.
    return static_cast<int>((static_cast<unsigned long long>(kPacifierSteps) * done) / total);
}

std::string pacifierMarks(int fromStep, int toStep) {
    std::string out;
    toStep = std::min(toStep, kPacifierSteps);
    for (int step = std::max(fromStep + 1, 0); step <= toStep; ++step)
        out += step % 4 == 0 ? std::to_string(step / 4) : std::string(".");
    return out;
}

std::string pacifierLine(long wholeSeconds) {
    return pacifierMarks(-1, kPacifierSteps) + " (" + std::to_string(wholeSeconds) + ")\n";
}

std::string formatDuration(double seconds) {
    if (!std::isfinite(seconds) || seconds < 0) return "--:--";
    long total = static_cast<long>(std::floor(seconds));
    long h = total / 3600, m = (total / 60) % 60, s = total % 60;
    char buffer[48];
    if (h > 0) std::snprintf(buffer, sizeof buffer, "%ld:%02ld:%02ld", h, m, s);
    else std::snprintf(buffer, sizeof buffer, "%ld:%02ld", m, s);
    return buffer;
}

std::string formatProgressBar(double fraction, double elapsedSeconds, int barWidth) {
    if (!std::isfinite(fraction)) fraction = 0;
    fraction = std::clamp(fraction, 0.0, 1.0);
    barWidth = std::max(barWidth, 1);
    int filled = static_cast<int>(std::floor(fraction * barWidth));
    std::string bar = "[" + std::string(filled, '#') + std::string(barWidth - filled, '.') + "]";
    double eta = fraction > 0 ? elapsedSeconds * (1 - fraction) / fraction : -1;
    char percent[16];
    std::snprintf(percent, sizeof percent, "%4d%%", static_cast<int>(std::floor(fraction * 100)));
    return bar + " " + percent + "  " + formatDuration(elapsedSeconds) + " elapsed, ETA " +
           formatDuration(eta);
}

}  // namespace q3
