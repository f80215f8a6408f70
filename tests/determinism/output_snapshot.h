// Every file below a folder, by relative path, and a readable account of how two such snapshots
// differ (which file, which BSP lump, which byte).
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace q3::test {

using FolderSnapshot = std::map<std::string, std::vector<uint8_t>>;

FolderSnapshot snapshotFolder(const std::filesystem::path& root);

// Empty when both snapshots hold the same files with the same bytes; otherwise one line per
// difference (at most a few), naming the file, and for IBSP files the lump, of the first
// differing byte.
std::string describeDifferences(const FolderSnapshot& expected, const FolderSnapshot& actual);

// "lump N" for a byte offset inside lump N of an IBSP image, "header" inside the header, "" when
// the bytes are not an IBSP file or the offset lies in no lump.
std::string bspRegionOf(const std::vector<uint8_t>& file, size_t offset);

}  // namespace q3::test
