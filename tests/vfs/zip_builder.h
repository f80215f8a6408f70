// Writes .pk3 archives for tests with minizip's zip API.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace q3::test {

// (name inside the archive, contents)
using ZipFiles = std::vector<std::pair<std::string, std::string>>;

// Creates `path` (and its folder) holding `files`, deflated.
void writeZip(const std::filesystem::path& path, const ZipFiles& files);
// Creates a loose file (and its folders).
void writeLoose(const std::filesystem::path& path, const std::string& contents);

}  // namespace q3::test
