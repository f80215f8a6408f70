// Parser of one .shader script into ShaderInfo records.
//
// Tolerance follows q3map2 and the engines on real files:
//  - fatal (ScriptError "<file>:<line>: ..."): an unterminated quoted string, a shader name not
//    followed by '{' (q3map2 stops there too), a directive missing a required argument on its
//    line (q3map2: "Line N is incomplete");
//  - warning "<file>:<line>: ..." and the shader is dropped: end of file inside a shader or stage
//    (the engine cannot use such a shader either);
//  - warning and q3map2's value: a malformed number (read like atof: leading digits, else 0), an
//    unknown surfaceparm or q3map_* directive, a bad q3map_lightmapAxis or q3map_lightmapSize;
//  - silently ignored as by q3map2: every other directive, and the rest of a directive's line.
// Braces and parentheses are tokens of their own even when glued to a word: OpenArena's
// am_cf_models.shader writes "models/mapobjects/cosmoflash/teleporter3{", which q3map2 (and the
// engine's whitespace tokenizer) cannot read but which clearly opens the shader.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "log.h"
#include "shader_info.h"

namespace q3 {

// Shaders of one script in file order, duplicates included. `fileName` is used in messages and
// stored as ShaderInfo::sourceFile. `earlier`, when given, resolves q3map_baseShader names that
// were not defined earlier in the same file.
std::vector<ShaderInfo> parseShaderScript(std::string_view text, const std::string& fileName, Log& log,
                                          const ShaderTable* earlier = nullptr);

}  // namespace q3
