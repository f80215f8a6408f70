// Inputs that live in files: a JSON folder packed back into a BSP, and .pk3 archives read directly
// and through the virtual file system.
#include "fuzz_entries.h"

#include "bspfile.h"
#include "file_io.h"
#include "json_error.h"
#include "json_files.h"
#include "json_stage.h"
#include "log.h"
#include "pk3_archive.h"
#include "sh_grid_lump.h"
#include "synthetic_bsp.h"
#include "vfs.h"

#include <algorithm>
#include <string>
#include <string_view>
#include <vector>

namespace q3::fuzz {
namespace fs = std::filesystem;

namespace {

// The folder -json -unpack writes for a small complete BSP carrying an SH grid in lump 18 and a
// BSPX lump, created once per scratch folder; `work` is a copy the entry edits one file at a time.
struct JsonPackFolders {
    fs::path base;
    fs::path work;
};

JsonPackFolders jsonPackFolders(const FuzzContext& context) {
    const fs::path root = context.scratch / "json_pack";
    JsonPackFolders folders{root / "base", root / "work"};
    const fs::path ready = root / "ready";
    if (fs::exists(ready)) return folders;

    fs::remove_all(root);
    fs::create_directories(folders.base);
    Log log(false);
    json::unpackBsp(jsonPackSourceBsp(), folders.base, json::JsonOptions{}, log);
    fs::copy(folders.base, folders.work, fs::copy_options::recursive);
    writeFileAtomic(ready, std::string("ok"));
    return folders;
}

// The file names an input may replace: exactly the files unpackBsp wrote.
bool isFolderFile(const fs::path& base, std::string_view name) {
    if (name.empty() || name.find('/') != std::string_view::npos || name.find('\0') != std::string_view::npos ||
        name == "." || name == "..")
        return false;
    std::error_code ec;
    return fs::is_regular_file(base / std::string(name), ec);
}

// The VFS' view of one file: every way of reading it, errors being FileError.
void readThroughVfs(const Vfs& vfs, const std::string& path) {
    try {
        vfs.exists(path);
        vfs.read(path);
        vfs.readAll(path);
        vfs.sourceOf(path);
    } catch (const FileError&) {
    }
}

}  // namespace

bsp::Bsp jsonPackSourceBsp() {
    bsp::Bsp source = bsp::test::makeSyntheticBsp();
    source.lightmaps.clear();
    for (bsp::Surface& surface : source.surfaces)
        if (surface.lightmapNum >= 0) surface.lightmapNum = bsp::kLightmapByVertex;
    bsp::attachShGrid(source, bsp::test::makeShGridLump(2, 2, 2));
    source.setBspx("FUZZ_EXTRA", {1, 2, 3, 4, 5});
    return source;
}

void fuzzJsonPack(std::span<const uint8_t> input, const FuzzContext& context) {
    const std::string_view text(reinterpret_cast<const char*>(input.data()), input.size());
    const size_t split = text.find(kJsonPackSeparator);
    if (split == std::string_view::npos) return;
    const std::string name(text.substr(0, split));
    const JsonPackFolders folders = jsonPackFolders(context);
    if (!isFolderFile(folders.base, name)) return;

    const fs::path edited = folders.work / name;
    writeFileAtomic(edited, std::string(text.substr(split + 1)));
    Log log(false);
    try {
        bsp::Bsp packed = json::packFolder(folders.work, json::JsonOptions{}, log);
        bsp::serializeBsp(packed, "fuzz_json_pack.bsp");
    } catch (const json::JsonError&) {
    } catch (const bsp::BspError&) {
    } catch (const FileError&) {
    }
    // Put the original back so the next input edits a valid folder.
    fs::copy_file(folders.base / name, edited, fs::copy_options::overwrite_existing);
}

void fuzzPk3(std::span<const uint8_t> input, const FuzzContext& context) {
    const fs::path root = context.scratch / "pk3";
    const fs::path archivePath = root / "baseq3" / "fuzz.pk3";
    fs::create_directories(archivePath.parent_path());
    writeFileAtomic(archivePath, input);

    // The archive on its own: table of contents, then every entry in name order.
    std::vector<std::string> names;
    std::string error;
    if (std::optional<Pk3Archive> archive = Pk3Archive::open(archivePath, error)) {
        for (const auto& [key, entry] : archive->entries()) names.push_back(key);
        std::sort(names.begin(), names.end());
        for (const std::string& key : names) {
            const Pk3Archive::Entry* entry = archive->find(key);
            if (!entry) throw PropertyViolation("Pk3Archive::find misses listed entry " + key);
            try {
                archive->read(*entry);
            } catch (const FileError&) {
            }
        }
    }

    // The same archive as part of a game folder.
    VfsOptions options;
    options.game = "quake3";
    options.basePaths = {root};
    Log log(false);
    Vfs vfs(options, log);
    for (const std::string& key : names) readThroughVfs(vfs, key);
    for (const char* dir : {"scripts", "maps", "textures", ""}) vfs.list(dir, "");
    readThroughVfs(vfs, "scripts/shaderlist.txt");
    readThroughVfs(vfs, "Scripts\\Missing.Shader");
}

}  // namespace q3::fuzz
