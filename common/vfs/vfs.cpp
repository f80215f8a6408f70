// The search path: sources in priority order, and look-ups that walk it.
#include "vfs.h"

#include <oneapi/tbb/parallel_for.h>

#include <algorithm>
#include <map>
#include <memory>
#include <mutex>

#include "ascii_case.h"
#include "pk3_archive.h"

namespace fs = std::filesystem;

namespace q3 {

namespace {

// Splits a normalised path into its components; rejects ".." so nothing escapes a game folder.
std::optional<std::vector<std::string>> splitComponents(const std::string& normalized) {
    std::vector<std::string> parts;
    size_t start = 0;
    while (start < normalized.size()) {
        size_t slash = normalized.find('/', start);
        if (slash == std::string::npos) slash = normalized.size();
        std::string part = normalized.substr(start, slash - start);
        if (part == "..") return std::nullopt;
        if (!part.empty() && part != ".") parts.push_back(std::move(part));
        start = slash + 1;
    }
    return parts;
}

bool hasExtension(const std::string& lowerName, const std::string& lowerExt) {
    if (lowerExt.empty()) return true;
    return lowerName.size() > lowerExt.size() + 1 && lowerName.ends_with(lowerExt) &&
           lowerName[lowerName.size() - lowerExt.size() - 1] == '.';
}

}  // namespace

struct Vfs::Impl {
    std::vector<VfsSource> sources;                 // highest priority first
    std::vector<std::optional<Pk3Archive>> archives;  // parallel to sources; set for archives
    std::vector<fs::path> basePaths;

    // A folder's entries by lower-case name, each the lower-case spelling when it is there, else the
    // smallest spelling of that name (so the choice does not depend on directory order). Read once,
    // on the first look-up in the folder: every shader file of a game is looked for in the loose
    // game folder first, and listing it each time cost milliseconds.
    using Listing = std::map<std::string, std::string, std::less<>>;
    mutable std::mutex listingsMutex;
    mutable std::map<fs::path, std::shared_ptr<const Listing>> listings;

    std::shared_ptr<const Listing> listingOf(const fs::path& folder) const {
        std::lock_guard lock(listingsMutex);
        std::shared_ptr<const Listing>& cached = listings[folder];
        if (cached) return cached;
        auto listing = std::make_shared<Listing>();
        std::error_code ec;
        for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
            std::string name = it->path().filename().string();
            std::string lower = toLower(name);
            auto [slot, added] = listing->try_emplace(lower, name);
            if (!added && slot->second != lower && (name == lower || name < slot->second))
                slot->second = std::move(name);
        }
        cached = std::move(listing);
        return cached;
    }

    // The entry of `folder` named `lowerName` ignoring case: the name itself when it is there,
    // else the smallest spelling that differs from it only in case.
    std::optional<fs::path> findIgnoringCase(const fs::path& folder, const std::string& lowerName) const {
        const std::shared_ptr<const Listing> listing = listingOf(folder);
        const auto it = listing->find(lowerName);
        if (it == listing->end()) return std::nullopt;
        return folder / it->second;
    }

    // The path below `folder` matching `normalized` case-insensitively, component by component.
    std::optional<fs::path> resolveIgnoringCase(const fs::path& folder, const std::string& normalized) const {
        auto parts = splitComponents(normalized);
        if (!parts || parts->empty()) return std::nullopt;
        fs::path current = folder;
        for (const std::string& part : *parts) {
            auto next = findIgnoringCase(current, part);
            if (!next) return std::nullopt;
            current = *next;
        }
        return current;
    }

    std::optional<fs::path> resolveLoose(const fs::path& folder, const std::string& normalized) const {
        auto found = resolveIgnoringCase(folder, normalized);
        std::error_code ec;
        if (!found || !fs::is_regular_file(*found, ec)) return std::nullopt;
        return found;
    }

    std::optional<fs::path> resolveLooseFolder(const fs::path& folder, const std::string& normalized) const {
        auto found = resolveIgnoringCase(folder, normalized);
        std::error_code ec;
        if (!found || !fs::is_directory(*found, ec)) return std::nullopt;
        return found;
    }

    // Where `normalized` lives in source `index`: for folders the file, for archives the entry.
    struct Hit {
        size_t source;
        std::optional<fs::path> loose;
        const Pk3Archive::Entry* entry = nullptr;
    };

    std::optional<Hit> findIn(size_t index, const std::string& normalized) const {
        if (archives[index]) {
            if (const auto* entry = archives[index]->find(normalized)) return Hit{index, std::nullopt, entry};
            return std::nullopt;
        }
        if (auto file = resolveLoose(sources[index].location, normalized)) return Hit{index, file, nullptr};
        return std::nullopt;
    }

    std::optional<Hit> find(std::string_view path) const {
        const std::string normalized = normalizeVfsPath(path);
        if (normalized.empty()) return std::nullopt;
        for (size_t i = 0; i < sources.size(); ++i)
            if (auto hit = findIn(i, normalized)) return hit;
        return std::nullopt;
    }

    std::vector<uint8_t> load(const Hit& hit) const {
        if (hit.entry) return archives[hit.source]->read(*hit.entry);
        return readFileBytes(*hit.loose);
    }

    void addGameFolder(const fs::path& root, const std::string& game, Log& log) {
        std::error_code ec;
        const fs::path folder = root / game;
        if (!fs::is_directory(folder, ec)) return;
        sources.push_back({VfsSource::Kind::Folder, folder, game});
        archives.emplace_back();
        // Archives and .pk3dir folders (unpacked archives) share one name order; later names win,
        // so the search order is descending, ties broken by exact spelling.
        std::vector<fs::path> packages;
        for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
            std::error_code typeError;
            const std::string ext = toLower(it->path().extension().string());
            if ((ext == ".pk3" && it->is_regular_file(typeError)) || (ext == ".pk3dir" && it->is_directory(typeError)))
                packages.push_back(it->path());
        }
        std::sort(packages.begin(), packages.end(), [](const fs::path& a, const fs::path& b) {
            std::string la = toLower(a.filename().string()), lb = toLower(b.filename().string());
            return la != lb ? la > lb : a.filename().string() > b.filename().string();
        });
        // The archives' directories are read side by side (a game's pk3s hold thousands of entries),
        // then taken in search order with their messages.
        struct Opened {
            std::optional<Pk3Archive> archive;
            std::string error;
        };
        std::vector<Opened> opened(packages.size());
        tbb::parallel_for(size_t(0), packages.size(), [&](size_t i) {
            if (toLower(packages[i].extension().string()) != ".pk3dir")
                opened[i].archive = Pk3Archive::open(packages[i], opened[i].error);
        });
        for (size_t i = 0; i < packages.size(); ++i) {
            const fs::path& pk3 = packages[i];
            if (toLower(pk3.extension().string()) == ".pk3dir") {
                sources.push_back({VfsSource::Kind::Folder, pk3, game});
                archives.emplace_back();
                continue;
            }
            const std::string& error = opened[i].error;
            std::optional<Pk3Archive>& archive = opened[i].archive;
            if (!archive) {
                log.warning(pk3.string() + ": " + error + "; archive skipped");
                continue;
            }
            log.debug("VFS: " + pk3.string() + " (" + std::to_string(archive->entries().size()) + " files)");
            sources.push_back({VfsSource::Kind::Archive, pk3, game});
            archives.push_back(std::move(archive));
        }
    }
};

Vfs::Vfs(const VfsOptions& options, Log& log) : impl_(std::make_unique<Impl>()) {
    const GameProfile* profile = findGameProfile(options.game);
    if (!profile) {
        std::string known;
        for (const GameProfile& p : gameProfiles()) known += (known.empty() ? "" : ", ") + std::string(p.name);
        throw FileError("-game " + options.game + ": unknown game (known: " + known + ")");
    }
    const std::string baseGame = options.baseGame.empty() ? std::string(profile->baseGame) : options.baseGame;

    std::vector<std::string> mods;
    auto addMod = [&](const std::string& mod) {
        if (mod.empty() || equalsNoCase(mod, baseGame)) return;
        for (const std::string& known : mods)
            if (equalsNoCase(known, mod)) return;
        mods.push_back(mod);
    };

    impl_->basePaths = options.basePaths;
    if (impl_->basePaths.empty()) {
        if (auto detected = detectGamePaths(options.mapPath)) {
            log.debug("VFS: base path " + detected->basePath.string() + " and game " + detected->gameDir +
                      " detected from " + options.mapPath.string());
            impl_->basePaths.push_back(detected->basePath);
            // A map inside a folder other than the base game (OpenArena's baseoa, a mod) makes that
            // folder a mod below any given with -fs_game.
            addMod(detected->gameDir);
        } else {
            log.debug("VFS: no base path given and none found in the map path");
        }
    }
    for (const std::string& mod : options.gameDirs) addMod(mod);

    std::vector<fs::path> roots;  // highest priority first; a folder given twice is searched once
    auto sameFolder = [](const fs::path& a, const fs::path& b) {
        auto canonicalForm = [](const fs::path& p) {
            fs::path normal = p.lexically_normal();
            return normal.has_filename() ? normal : normal.parent_path();  // drop a trailing '/'
        };
        return canonicalForm(a) == canonicalForm(b);
    };
    auto addRoot = [&](const fs::path& root) {
        for (const fs::path& known : roots)
            if (sameFolder(known, root)) return;
        roots.push_back(root);
    };
    if (!options.homePath.empty()) addRoot(options.homePath);
    for (const fs::path& base : impl_->basePaths) addRoot(base);

    std::vector<std::string> games = {baseGame};
    games.insert(games.end(), mods.begin(), mods.end());
    for (auto game = games.rbegin(); game != games.rend(); ++game)
        for (const fs::path& root : roots) impl_->addGameFolder(root, *game, log);
}

Vfs::~Vfs() = default;
Vfs::Vfs(Vfs&&) noexcept = default;
Vfs& Vfs::operator=(Vfs&&) noexcept = default;

bool Vfs::exists(std::string_view path) const { return impl_->find(path).has_value(); }

std::optional<std::vector<uint8_t>> Vfs::read(std::string_view path) const {
    auto hit = impl_->find(path);
    if (!hit) return std::nullopt;
    return impl_->load(*hit);
}

std::vector<std::vector<uint8_t>> Vfs::readAll(std::string_view path) const {
    std::vector<std::vector<uint8_t>> copies;
    const std::string normalized = normalizeVfsPath(path);
    if (normalized.empty()) return copies;
    for (size_t i = impl_->sources.size(); i-- > 0;)
        if (auto hit = impl_->findIn(i, normalized)) copies.push_back(impl_->load(*hit));
    return copies;
}

std::vector<std::string> Vfs::list(std::string_view dir, std::string_view ext) const {
    std::string lowerDir = normalizeVfsPath(dir);
    while (!lowerDir.empty() && lowerDir.back() == '/') lowerDir.pop_back();
    std::string lowerExt = toLower(ext);
    if (!lowerExt.empty() && lowerExt.front() == '.') lowerExt.erase(0, 1);
    const std::string prefix = lowerDir.empty() ? "" : lowerDir + "/";

    std::map<std::string, std::string> found;  // key -> spelling of the highest-priority copy
    for (size_t i = 0; i < impl_->sources.size(); ++i) {
        if (impl_->archives[i]) {
            for (const auto& [key, entry] : impl_->archives[i]->entries()) {
                if (!key.starts_with(prefix) || key.find('/', prefix.size()) != std::string::npos) continue;
                if (hasExtension(key, lowerExt)) found.try_emplace(key, entry.name);
            }
            continue;
        }
        fs::path folder = impl_->sources[i].location;
        std::string storedDir;  // the folder's spelling on disk, relative to the game folder
        if (!lowerDir.empty()) {
            auto sub = impl_->resolveLooseFolder(folder, lowerDir);
            if (!sub) continue;
            folder = *sub;
            storedDir = sub->lexically_relative(impl_->sources[i].location).generic_string() + "/";
        }
        std::error_code ec;
        for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
            std::error_code typeError;
            if (!it->is_regular_file(typeError)) continue;
            const std::string name = it->path().filename().string();
            const std::string key = prefix + toLower(name);
            if (hasExtension(key, lowerExt))
                found.try_emplace(key, storedDir + name);
        }
    }
    std::vector<std::string> names;
    names.reserve(found.size());
    for (auto& [key, spelling] : found) names.push_back(std::move(spelling));
    return names;
}

std::optional<std::string> Vfs::sourceOf(std::string_view path) const {
    auto hit = impl_->find(path);
    if (!hit) return std::nullopt;
    if (hit->entry) return impl_->sources[hit->source].location.string() + ":" + hit->entry->name;
    return hit->loose->string();
}

const std::vector<VfsSource>& Vfs::sources() const { return impl_->sources; }
const std::vector<fs::path>& Vfs::basePaths() const { return impl_->basePaths; }

}  // namespace q3
