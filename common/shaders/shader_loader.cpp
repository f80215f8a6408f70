#include "shader_loader.h"

#include <oneapi/tbb/parallel_for.h>

#include <algorithm>
#include <cctype>
#include <exception>
#include <map>
#include <unordered_map>
#include <unordered_set>

#include "script.h"
#include "shader_parser.h"

namespace q3 {
namespace {

bool containsNoCase(const std::vector<std::string>& list, std::string_view item) {
    return std::any_of(list.begin(), list.end(), [&](const std::string& s) { return equalsNoCase(s, item); });
}

// Whether `text` holds `word` in any case.
bool containsNoCase(std::string_view text, std::string_view word) {
    return std::search(text.begin(), text.end(), word.begin(), word.end(),
                       [](char a, char b) { return asciiLower(a) == asciiLower(b); }) != text.end();
}

// Lower-case names already taken: lists may name tens of thousands of files, so membership tests
// must not scan the list.
class NoCaseSet {
public:
    // True when `name` was not in the set yet.
    bool insert(std::string_view name) { return keys_.insert(toLower(name)).second; }
    bool contains(std::string_view name) const { return keys_.count(toLower(name)) != 0; }

private:
    std::unordered_set<std::string> keys_;
};

}  // namespace

std::vector<std::string> parseShaderList(std::string_view text, const std::string& fileName,
                                         const std::string& scriptDir) {
    std::vector<std::string> names;
    NoCaseSet seen;
    Script script(text, fileName, false);
    while (script.next(true)) {
        std::string name = script.token();
        constexpr std::string_view kExt = ".shader";
        bool hasExt = name.size() >= kExt.size() &&
                      equalsNoCase(std::string_view(name).substr(name.size() - kExt.size()), kExt);
        if (!hasExt) name += kExt;
        std::string path = scriptDir + "/" + name;
        if (seen.insert(path)) names.push_back(std::move(path));
    }
    return names;
}

std::vector<std::string> shaderScriptLoadOrder(const std::vector<std::string>& available,
                                               const std::vector<std::string>& listed, Log& log) {
    // First spelling of each available file, by lower-case name (the first match wins, as a
    // front-to-back search would find it).
    std::unordered_map<std::string, const std::string*> availableByKey;
    for (const std::string& name : available) availableByKey.emplace(toLower(name), &name);
    std::vector<std::string> order;
    NoCaseSet ordered;
    for (const std::string& name : listed) {
        const auto it = availableByKey.find(toLower(name));
        if (it == availableByKey.end()) {
            log.warning("shaderlist.txt names " + name + ", which does not exist");
            continue;
        }
        if (ordered.insert(*it->second)) order.push_back(*it->second);
    }
    for (const std::string& name : available)
        if (ordered.insert(name)) order.push_back(name);
    return order;
}

ShaderTable buildShaderTable(const std::vector<ShaderScriptSource>& scripts, const std::vector<std::string>& listed,
                             bool shaderListFound, Log& log) {
    ShaderTable table;
    table.setHasShaderList(shaderListFound);
    NoCaseSet listedSet;
    for (const std::string& name : listed) listedSet.insert(name);
    // The scripts are parsed in parallel, each with its messages held back, and taken into the
    // table in order, their messages (and a fatal error) passed on as a sequential parse would.
    // A script with q3map_baseShader may copy a shader of an earlier script: it is parsed in turn,
    // once the table holds every earlier one.
    struct Parsed {
        bool inTurn = false;
        std::vector<std::unique_ptr<ShaderInfo>> shaders;  // on the heap and keyed beside the others
        std::vector<std::string> keys;                     // shaderKey of each
        Log messages{false};
        std::exception_ptr error;
    };
    auto own = [](Parsed& p, std::vector<ShaderInfo> shaders, const std::string& path) {
        p.shaders.reserve(shaders.size());
        p.keys.reserve(shaders.size());
        for (ShaderInfo& shader : shaders) {
            shader.sourceFile = path;
            p.keys.push_back(shaderKey(shader.name));
            p.shaders.push_back(std::make_unique<ShaderInfo>(std::move(shader)));
        }
    };
    std::vector<Parsed> parsed(scripts.size());
    tbb::parallel_for(size_t(0), scripts.size(), [&](size_t i) {
        Parsed& p = parsed[i];
        p.inTurn = containsNoCase(scripts[i].text, "q3map_baseShader");
        if (p.inTurn) return;
        p.messages.setVerbose(log.verbose());
        p.messages.holdMessages();
        try {
            own(p, parseShaderScript(scripts[i].text, scripts[i].displayName, p.messages, nullptr), scripts[i].path);
        } catch (...) {
            p.error = std::current_exception();
        }
    });
    size_t total = 0;
    for (const Parsed& p : parsed) total += p.shaders.size();
    table.reserve(total);
    for (size_t i = 0; i < scripts.size(); ++i) {
        const ShaderScriptSource& script = scripts[i];
        Parsed& p = parsed[i];
        if (p.inTurn) {
            own(p, parseShaderScript(script.text, script.displayName, log, &table), script.path);
        } else {
            p.messages.replayInto(log);
            if (p.error) std::rethrow_exception(p.error);
        }
        ShaderTable::SourceFile file;
        file.path = script.path;
        file.inShaderList = listedSet.contains(script.path);
        file.shaderCount = static_cast<int>(p.shaders.size());
        table.addFile(std::move(file));
        for (size_t k = 0; k < p.shaders.size(); ++k) {
            // A duplicate is freed by add: what its message names is kept first (only with -v).
            const std::string name = log.verbose() ? p.shaders[k]->name : std::string();
            const int line = p.shaders[k]->sourceLine;
            if (!table.add(std::move(p.shaders[k]), std::move(p.keys[k])))
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
