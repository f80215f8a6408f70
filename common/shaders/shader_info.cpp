#include "shader_info.h"

#include <algorithm>

#include "script.h"

namespace q3 {

std::vector<std::string> ShaderInfo::lightImageCandidates() const {
    std::vector<std::string> out;
    if (isNoDraw()) return out;
    for (const std::string* path : {&lightImage, &editorImage, &name}) {
        if (path->empty()) continue;
        // Loading ignores one extension, so "x.tga" and "x" are the same image.
        bool seen = std::any_of(out.begin(), out.end(), [&](const std::string& p) { return shaderKey(p) == shaderKey(*path); });
        if (!seen) out.push_back(*path);
    }
    return out;
}

std::vector<std::string> ShaderInfo::textureImageCandidates() const {
    std::vector<std::string> out;
    for (const std::string* path : {&editorImage, &name, &implicitImage, &lightImage})
        if (!path->empty()) out.push_back(*path);
    return out;
}

ShaderInfo makeImplicitShader(std::string_view textureName) {
    ShaderInfo shader;
    std::string key = shaderKey(textureName);
    // Keep the caller's spelling, minus the extension.
    shader.name = std::string(textureName.substr(0, key.size()));
    std::replace(shader.name.begin(), shader.name.end(), '\\', '/');
    shader.explicitScript = false;
    return shader;
}

std::string shaderKey(std::string_view name) {
    std::string key = toLower(name);
    std::replace(key.begin(), key.end(), '\\', '/');
    size_t dot = key.rfind('.');
    size_t slash = key.rfind('/');
    if (dot != std::string::npos && (slash == std::string::npos || dot > slash)) key.resize(dot);
    return key;
}

ShaderTable::ShaderTable(ShaderTable&& other) noexcept { *this = std::move(other); }

ShaderTable& ShaderTable::operator=(ShaderTable&& other) noexcept {
    if (this == &other) return *this;
    std::scoped_lock lock(implicitMutex_, other.implicitMutex_);
    shaders_ = std::move(other.shaders_);
    byName_ = std::move(other.byName_);
    duplicates_ = other.duplicates_;
    files_ = std::move(other.files_);
    hasShaderList_ = other.hasShaderList_;
    implicit_ = std::move(other.implicit_);
    return *this;
}

bool ShaderTable::add(ShaderInfo shader) {
    std::string key = shaderKey(shader.name);
    return add(std::make_unique<ShaderInfo>(std::move(shader)), std::move(key));
}

bool ShaderTable::add(std::unique_ptr<ShaderInfo> shader, std::string key) {
    const auto [it, added] = byName_.try_emplace(std::move(key), shader.get());
    if (!added) {
        ++duplicates_;
        return false;
    }
    shader->explicitScript = true;
    shaders_.push_back(std::move(shader));
    return true;
}

void ShaderTable::reserve(size_t shaders) {
    shaders_.reserve(shaders);
    byName_.reserve(shaders);
}

const ShaderInfo* ShaderTable::findExplicit(std::string_view name) const {
    auto it = byName_.find(shaderKey(name));
    return it == byName_.end() ? nullptr : it->second;
}

const ShaderInfo& ShaderTable::find(std::string_view name) const {
    constexpr int kMaxDeprecationDepth = 16;
    std::string key = shaderKey(name);
    for (int depth = 0;; ++depth) {
        auto it = byName_.find(key);
        if (it == byName_.end()) break;
        const ShaderInfo& shader = *it->second;
        if (shader.deprecatedBy.empty() || depth == kMaxDeprecationDepth) return shader;
        key = shaderKey(shader.deprecatedBy);
    }
    std::lock_guard lock(implicitMutex_);
    auto it = implicit_.find(key);
    if (it == implicit_.end())
        it = implicit_.emplace(key, std::make_unique<ShaderInfo>(makeImplicitShader(key))).first;
    return *it->second;
}

}  // namespace q3
