// The virtual file system: game folders made of loose files and .pk3 archives, searched in Quake 3
// order. Built once from options; every query is const and safe to call from worker threads.
//
// Priority, highest first:
//   mod folders (-fs_game, the last given first) above the base game folder; within one game, the
//   home path above the base paths (the first -fs_basepath above later ones; a folder given twice
//   is searched once); inside one <root>/<game> folder, loose files above archives, and archives
//   later in case-insensitive name order above earlier ones. A "<name>.pk3dir" folder is an
//   unpacked archive and takes its place in that name order.
// Look-ups are case-insensitive (inside archives and in loose folders) and use '/' separators.
//
// A .pk3 that cannot be opened as a zip (corrupt, truncated, not a zip) is skipped with a warning
// naming it (q3map2 skips such archives too); its files are simply not there. An entry of a readable archive that
// fails to decompress is an error (FileError naming the archive and the entry).
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "file_io.h"
#include "log.h"

namespace q3 {

// One -game profile: which folder holds the base game's data.
struct GameProfile {
    std::string_view name;      // -game value
    std::string_view baseGame;  // default base game folder ("baseq3")
};
// The known profiles (quake3 is the default).
std::span<const GameProfile> gameProfiles();
// nullptr when unknown.
const GameProfile* findGameProfile(std::string_view name);

struct VfsOptions {
    std::string game = "quake3";                     // -game
    std::vector<std::filesystem::path> basePaths;    // -fs_basepath, repeatable, first wins
    std::vector<std::string> gameDirs;               // -fs_game, repeatable, last wins
    std::string baseGame;                            // -fs_basegame; empty = the profile's
    std::filesystem::path homePath;                  // -fs_homepath; empty = none
    // The map being compiled. When no base path is given it is derived from this path
    // (see detectGamePaths); a detected game folder other than the base game becomes a mod folder.
    std::filesystem::path mapPath;
};

// q3map2's base path detection: ".../<root>/<game>/maps/x.bsp" gives root and game. The last
// "maps" component of the absolute, normalised path is used. nullopt when there is none.
struct DetectedGamePaths {
    std::filesystem::path basePath;
    std::string gameDir;
};
std::optional<DetectedGamePaths> detectGamePaths(const std::filesystem::path& mapPath);

// One place files come from, in the order searched (highest priority first).
struct VfsSource {
    enum class Kind { Folder, Archive };
    Kind kind = Kind::Folder;
    std::filesystem::path location;  // the <root>/<game> folder, a .pk3dir folder or the .pk3 file
    std::string gameDir;             // "baseq3", "baseoa", a mod name
};

class Vfs {
public:
    // Loose folders are listed once each, on the first look-up in them: files added to them
    // afterwards are not seen by this Vfs.
    // Throws FileError for an unknown game profile. Missing folders are skipped silently; unreadable
    // archives are skipped with a warning on `log`.
    Vfs(const VfsOptions& options, Log& log);
    ~Vfs();
    Vfs(Vfs&&) noexcept;
    Vfs& operator=(Vfs&&) noexcept;
    Vfs(const Vfs&) = delete;
    Vfs& operator=(const Vfs&) = delete;

    bool exists(std::string_view path) const;
    // The highest-priority copy of `path`, or nullopt when no source has it.
    std::optional<std::vector<uint8_t>> read(std::string_view path) const;
    // Every copy of `path`, lowest priority first (q3map2 merges every shaderlist.txt this way).
    std::vector<std::vector<uint8_t>> readAll(std::string_view path) const;
    // Files directly inside `dir` (not below) whose extension is `ext` ("shader" or ".shader";
    // empty = any), over all sources, each once, as "dir/name.ext", sorted case-insensitively.
    // The spelling is that of the highest-priority copy (as stored in its archive or on disk).
    std::vector<std::string> list(std::string_view dir, std::string_view ext) const;
    // Where `path` would be read from, for messages: "/q3/baseq3/pak0.pk3:textures/a/b.tga" or the
    // loose file's full path. nullopt when absent.
    std::optional<std::string> sourceOf(std::string_view path) const;

    // The sources in search order, highest priority first.
    const std::vector<VfsSource>& sources() const;
    // The base paths in use (given or detected).
    const std::vector<std::filesystem::path>& basePaths() const;

    struct Impl;

private:
    std::unique_ptr<Impl> impl_;
};

// "Textures\\A//b.TGA" -> "textures/a/b.tga": the key used for every look-up.
std::string normalizeVfsPath(std::string_view path);

}  // namespace q3
