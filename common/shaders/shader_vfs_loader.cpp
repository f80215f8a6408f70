// The shader table of a game: every scripts/*.shader of the VFS, shader lists first.
#include <oneapi/tbb/parallel_for.h>

#include <algorithm>
#include <unordered_set>

#include "script.h"
#include "shader_loader.h"
#include "vfs.h"

namespace q3 {
namespace {

std::string bytesToText(const std::vector<uint8_t>& bytes) { return std::string(bytes.begin(), bytes.end()); }

}  // namespace

ShaderTable loadShaderTable(const Vfs& vfs, Log& log) {
    const std::string scriptDir = "scripts";
    const std::string listPath = scriptDir + "/shaderlist.txt";

    std::vector<std::string> listed;
    std::unordered_set<std::string> listedKeys;  // lower case; lists may be long
    std::vector<std::vector<uint8_t>> lists = vfs.readAll(listPath);
    for (const std::vector<uint8_t>& bytes : lists)
        for (std::string& name : parseShaderList(bytesToText(bytes), listPath, scriptDir))
            if (listedKeys.insert(toLower(name)).second) listed.push_back(std::move(name));

    std::vector<std::string> order = shaderScriptLoadOrder(vfs.list(scriptDir, "shader"), listed, log);
    // Read (and inflated) in parallel, kept in load order.
    std::vector<std::optional<ShaderScriptSource>> read(order.size());
    tbb::parallel_for(size_t(0), order.size(), [&](size_t i) {
        std::optional<std::vector<uint8_t>> bytes = vfs.read(order[i]);
        if (!bytes) return;
        ShaderScriptSource& source = read[i].emplace();
        source.path = order[i];
        source.displayName = vfs.sourceOf(order[i]).value_or(order[i]);
        source.text = bytesToText(*bytes);
    });
    std::vector<ShaderScriptSource> scripts;
    scripts.reserve(order.size());
    for (std::optional<ShaderScriptSource>& source : read)
        if (source) scripts.push_back(std::move(*source));
    ShaderTable table = buildShaderTable(scripts, listed, !lists.empty(), log);
    if (table.hasShaderList()) {
        size_t named = std::count_if(table.files().begin(), table.files().end(),
                                     [](const ShaderTable::SourceFile& f) { return f.inShaderList; });
        if (named < table.files().size())
            log.info(listPath + " names " + std::to_string(named) + " of " + std::to_string(table.files().size()) +
                     " shader files; all of them are loaded");
    }
    log.info(std::to_string(table.files().size()) + " shader files, " + std::to_string(table.size()) + " shaders" +
             (table.duplicateCount() ? " (" + std::to_string(table.duplicateCount()) + " duplicate definitions ignored)"
                                     : std::string()));
    return table;
}

}  // namespace q3
