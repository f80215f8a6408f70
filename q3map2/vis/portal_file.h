// The `.prt` portal file that -bsp writes for -vis, read the way q3map2's LoadPortals reads it:
//
//   PRT1
//   <clusters>
//   <portals>
//   <solid faces>
//   <points> <cluster A> <cluster B> <flags> (x y z ) (x y z ) ...     one line per portal
//   <points> <cluster> (x y z ) ...                                    one line per solid face
//
// Flags: bit 0 = the portal comes from a hint brush, bit 1 = sky. Numbers are read as scanf's %i
// reads them (so "0x10" is 16), coordinates as %f. Malformed input throws PortalFileError.
#pragma once

#include "vec3.h"

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace q3::vis {

// One line: "<file>: <what is wrong>".
struct PortalFileError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

constexpr int kMaxFilePortals = 0x20000;    // q3map2's MAX_PORTALS
constexpr int kMaxPortalPoints = 64;        // q3map2's MAX_POINTS_ON_WINDING
constexpr uint32_t kPortalFlagHint = 1;
constexpr uint32_t kPortalFlagSky = 2;

struct FilePortal {
    int clusters[2] = {0, 0};  // the portal's plane (from its first three points) faces cluster 0
    uint32_t flags = 0;
    std::vector<Vec3> points;
};

struct FileFace {
    int cluster = 0;
    std::vector<Vec3> points;
};

struct PortalFile {
    int clusterCount = 0;
    std::vector<FilePortal> portals;
    std::vector<FileFace> faces;
};

// `name` is used in error messages. Beyond what q3map2 checks (header, counts, points per
// portal, cluster numbers above the count), this also refuses negative counts and cluster
// numbers, windings of fewer than three points, cluster numbers equal to the count (q3map2 reads
// past its leaf array there) and text left after the last face.
PortalFile parsePortalFile(std::string_view text, const std::string& name);
PortalFile readPortalFile(const std::filesystem::path& path);

}  // namespace q3::vis
