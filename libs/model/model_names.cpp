// Names q3map2 derives for imported models: shaders of materials, and .skin files.
#include <algorithm>
#include <cctype>
#include <sstream>

#include "ascii_case.h"
#include "model.h"

namespace q3::model {
namespace {

bool startsWithNoCase(std::string_view s, std::string_view prefix) {
    return s.size() >= prefix.size() && equalsNoCase(s.substr(0, prefix.size()), prefix);
}

size_t findNoCase(std::string_view s, std::string_view needle) {
    for (size_t i = 0; i + needle.size() <= s.size(); ++i)
        if (startsWithNoCase(s.substr(i), needle)) return i;
    return std::string_view::npos;
}

std::string forwardSlashes(std::string s) {
    std::replace(s.begin(), s.end(), '\\', '/');
    return s;
}

size_t fileNameStart(std::string_view path) {
    const size_t slash = path.find_last_of("/\\");
    return slash == std::string_view::npos ? 0 : slash + 1;
}

}  // namespace

std::string extensionless(std::string_view path) {
    const size_t dot = path.rfind('.');
    if (dot == std::string_view::npos || dot < fileNameStart(path)) return std::string(path);
    return std::string(path.substr(0, dot));
}

std::string importedShaderName(const std::string& materialName, const std::string& diffuseTexture,
                               const std::string& modelPath) {
    // A material named like a game shader keeps its name even when it has a texture.
    const bool gameShaderName = startsWithNoCase(materialName, "textures/") ||
                                startsWithNoCase(materialName, "textures\\") ||
                                startsWithNoCase(materialName, "models/") || startsWithNoCase(materialName, "models\\");
    std::string shader = forwardSlashes(extensionless(!diffuseTexture.empty() && !gameShaderName ? diffuseTexture
                                                                                                : materialName));
    const std::string folder = forwardSlashes(modelPath.substr(0, fileNameStart(modelPath)));
    if (shader.find('/') == std::string::npos) return folder + shader;  // beside the model
    const bool absolute = shader[0] == '/' || (shader.size() > 1 && shader[1] == ':') ||
                          shader.find("..") != std::string::npos;
    if (!absolute) return shader;
    for (const char* root : {"/models/", "/textures/"})
        if (const size_t at = findNoCase(shader, root); at != std::string::npos) return shader.substr(at + 1);
    return folder + shader.substr(fileNameStart(shader));
}

std::vector<SkinRemap> parseSkin(std::string_view text) {
    std::vector<SkinRemap> out;
    size_t pos = 0;
    while (pos < text.size()) {
        size_t end = text.find_first_of("\r\n", pos);
        if (end == std::string_view::npos) end = text.size();
        const std::string line(text.substr(pos, end - pos));
        pos = end + 1;
        std::istringstream words(line);
        std::string first, from, to;
        if (words >> first && first == "replace" && words >> from >> to) {
            out.push_back({from, to});
            continue;
        }
        // "FROM,TO": FROM ends at a comma or a space, blanks may stand around the comma.
        const size_t begin = line.find_first_not_of(" \t");
        if (begin == std::string::npos) continue;
        const size_t fromEnd = line.find_first_of(", \t", begin);
        if (fromEnd == std::string::npos || fromEnd == begin) continue;
        const size_t comma = line.find_first_not_of(" \t", fromEnd);
        if (comma == std::string::npos || line[comma] != ',') continue;
        std::istringstream rest(line.substr(comma + 1));
        if (rest >> to) out.push_back({line.substr(begin, fromEnd - begin), to});
    }
    return out;
}

std::string skinFileName(const std::string& modelPath, const std::string& skin) {
    const bool number = !skin.empty() && std::all_of(skin.begin(), skin.end(), [](char c) { return std::isdigit(uint8_t(c)); });
    return (number ? modelPath : extensionless(modelPath)) + "_" + skin + ".skin";
}

}  // namespace q3::model
