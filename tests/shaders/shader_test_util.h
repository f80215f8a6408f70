// Helpers shared by the shader tests.
#pragma once

#include <string>
#include <vector>

#include "log.h"

namespace q3::test {

// A silent Log that keeps every warning and info line.
struct CapturedLog {
    Log log{false};
    std::vector<std::string> warnings;
    std::vector<std::string> infos;

    CapturedLog() {
        log.addSink([this](LogLevel level, std::string_view text) {
            if (level == LogLevel::Warning) warnings.emplace_back(text);
            else if (level == LogLevel::Info) infos.emplace_back(text);
        });
    }
    std::string all() const {
        std::string out;
        for (const std::string& w : warnings) out += w;
        return out;
    }
};

}  // namespace q3::test
