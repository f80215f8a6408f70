// Loading every shader script of the game, and the check that a shaderlist.txt does not leave out
// scripts a map depends on.
//
// Policy (documented difference from q3map2): q3map2 parses only the files a shaderlist.txt names
// and ignores every other script, so a map using a shader from an unlisted file silently loses its
// surfaceparms and lights. Here every scripts/*.shader is loaded, as the engines do: the files the
// shader lists name come first, in list order (lists merged lowest priority first, each file
// once), then all other scripts in case-insensitive name order. Among duplicate shader names the
// first definition in that order wins, which matches q3map2 whenever q3map2 loads both.
// warnShadersOutsideShaderList() reports where q3map2 would have compiled differently.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "log.h"
#include "shader_info.h"

namespace q3 {

class Vfs;

// One script to load: its VFS path ("scripts/sky.shader"), the name used in messages (for example
// the archive holding it) and its text.
struct ShaderScriptSource {
    std::string path;
    std::string displayName;
    std::string text;
};

// File names a shaderlist.txt names, as "scripts/<name>.shader" (".shader" added when missing),
// each once (case-insensitive), in order.
std::vector<std::string> parseShaderList(std::string_view text, const std::string& fileName,
                                         const std::string& scriptDir = "scripts");

// The order in which scripts are parsed: the listed ones that exist, in list order, then the
// others in the order given (callers pass them sorted). Listed files that do not exist are
// reported on `log` and skipped.
std::vector<std::string> shaderScriptLoadOrder(const std::vector<std::string>& available,
                                               const std::vector<std::string>& listed, Log& log);

// Parses `scripts` in the given order into a table. `listed` marks the files named by a shader
// list (hasShaderList is set when `shaderListFound`). Throws ScriptError for a fatal script error.
ShaderTable buildShaderTable(const std::vector<ShaderScriptSource>& scripts, const std::vector<std::string>& listed,
                             bool shaderListFound, Log& log);

// Every scripts/*.shader of the VFS, ordered as described above. Logs how many files and shaders
// were loaded.
ShaderTable loadShaderTable(const Vfs& vfs, Log& log);

// For a game with a shaderlist.txt: one warning per script file that the list leaves out but that
// defines shaders in `usedShaders` (names as in the BSP). Returns the number of warnings.
int warnShadersOutsideShaderList(const ShaderTable& table, std::span<const std::string> usedShaders, Log& log);

}  // namespace q3
