// Game profiles, base path detection from the map path, and the canonical form of VFS paths.
#include <algorithm>
#include <array>

#include "ascii_case.h"
#include "vfs.h"

namespace q3 {

namespace {

constexpr std::array<GameProfile, 2> kProfiles = {{
    {"quake3", "baseq3"},
    {"quakelive", "baseq3"},
}};

}  // namespace

std::span<const GameProfile> gameProfiles() { return kProfiles; }

const GameProfile* findGameProfile(std::string_view name) {
    for (const GameProfile& profile : kProfiles)
        if (equalsNoCase(profile.name, name)) return &profile;
    return nullptr;
}

std::optional<DetectedGamePaths> detectGamePaths(const std::filesystem::path& mapPath) {
    if (mapPath.empty()) return std::nullopt;
    std::error_code ec;
    std::filesystem::path full = std::filesystem::absolute(mapPath, ec);
    if (ec) return std::nullopt;
    full = full.lexically_normal();
    std::vector<std::filesystem::path> parts(full.begin(), full.end());
    // parts: root, ..., <game>, maps, file. The game folder needs a parent to be the base path.
    for (size_t i = parts.size(); i-- > 2;) {
        if (i + 1 >= parts.size() || !equalsNoCase(parts[i].string(), "maps")) continue;
        std::filesystem::path base;
        for (size_t k = 0; k + 1 < i; ++k) base /= parts[k];
        const std::string game = parts[i - 1].string();
        if (game.empty() || base.empty()) continue;
        return DetectedGamePaths{base, game};
    }
    return std::nullopt;
}

std::string normalizeVfsPath(std::string_view path) {
    std::string out;
    out.reserve(path.size());
    for (char c : path) {
        char lower = c == '\\' ? '/' : asciiLower(c);
        if (lower == '/' && (out.empty() || out.back() == '/')) continue;  // leading and doubled slashes
        out.push_back(lower);
    }
    // "./" segments carry no meaning inside a game folder.
    while (out.rfind("./", 0) == 0) out.erase(0, 2);
    return out;
}

}  // namespace q3
