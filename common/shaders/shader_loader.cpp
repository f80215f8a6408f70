#include "shader_loader.h"

#include <algorithm>
#include <map>

#include "script.h"
#include "shader_parser.h"

namespace q3 {
namespace {

bool containsNoCase(const std::vector<std::string>& list, std::string_view item) {
    return std::any_of(list.begin(), list.end(), [&](const std::string& s) { return equalsNoCase(s, item); });
}

}  // namespace

std::vector<std::string> parseShaderList(std::string_view text, const std::string& fileName,
                                         const std::string& scriptDir) {
    std::vector<std::string> names;
    Script script(text, fileName, false);
    while (script.next(true)) {
        std::string name = script.token();
        constexpr std::string_view kExt = ".shader";
        bool hasExt = name.size() >= kExt.size() &&
                      equalsNoCase(std::string_view(name).substr(name.size() - kExt.size()), kExt);
        if (!hasExt) name += kExt;
        std::string path = scriptDir + "/" + name;
        if (!containsNoCase(names, path)) names.push_back(std::move(path));
    }
    return names;
}

std::vector<std::string> shaderScriptLoadOrder(const std::vector<std::string>& available,
                                               const std::vector<std::string>& listed, Log& log) {
    std::vector<std::string> order;
    for (const std::string& name : listed) {
        auto it = std::find_if(available.begin(), available.end(),
                               [&](const std::string& a) { return equalsNoCase(a, name); });
        if (it == available.end()) {
            log.warning("shaderlist.txt names " + name + ", which does not exist");
            continue;
        }
        if (!containsNoCase(order, *it)) order.push_back(*it);
    }
    for (const std::string& name : available)
        if (!containsNoCase(order, name)) order.push_back(name);
    return order;
}

ShaderTable buildShaderTable(const std::vector<ShaderScriptSource>& scripts, const std::vector<std::string>& listed,
                             bool shaderListFound, Log& log) {
    ShaderTable table;
    table.setHasShaderList(shaderListFound);
    for (const ShaderScriptSource& script : scripts) {
        std::vector<ShaderInfo> shaders = parseShaderScript(script.text, script.displayName, log, &table);
        ShaderTable::SourceFile file;
        file.path = script.path;
        file.inShaderList = containsNoCase(listed, script.path);
        file.shaderCount = static_cast<int>(shaders.size());
        table.addFile(std::move(file));
        for (ShaderInfo& shader : shaders) {
            shader.sourceFile = script.path;
            std::string name = shader.name;
            int line = shader.sourceLine;
            if (!table.add(std::move(shader)))
                log.debug(script.displayName + ":" + std::to_string(line) + ": shader '" + name +
                          "' already defined, first definition kept");
        }
    }
    return table;
}

int warnShadersOutsideShaderList(const ShaderTable& table, std::span<const std::string> usedShaders, Log& log) {
    if (!table.hasShaderList()) return 0;
    // File path -> used shaders it defines, in first-use order.
    std::map<std::string, std::vector<std::string>> byFile;
    for (const std::string& name : usedShaders) {
        const ShaderInfo* shader = table.findExplicit(name);
        if (!shader) continue;
        std::vector<std::string>& names = byFile[shader->sourceFile];
        if (!containsNoCase(names, shader->name)) names.push_back(shader->name);
    }
    int warnings = 0;
    for (const ShaderTable::SourceFile& file : table.files()) {
        if (file.inShaderList) continue;
        auto it = byFile.find(file.path);
        if (it == byFile.end()) continue;
        const std::vector<std::string>& names = it->second;
        std::string message = file.path + " is not named in scripts/shaderlist.txt but defines " +
                              std::to_string(names.size()) + " shader(s) this map uses (" + names.front();
        if (names.size() > 1) message += ", ...";
        message += "); loaded anyway, q3map2 would ignore it";
        log.warning(message);
        ++warnings;
    }
    return warnings;
}

}  // namespace q3
