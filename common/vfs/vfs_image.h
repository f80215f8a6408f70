// Loading shader images through the VFS with q3map2's extension fallback: a shader may name
// "x.tga" while the game ships "x.jpg". No cache lives here: callers that load the same image many
// times keep their own map from the requested name to the LoadedImage.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "image.h"
#include "vfs.h"

namespace q3 {

struct LoadedImage {
    std::string path;  // the VFS path actually read ("textures/base/floor.jpg")
    Image image;
};

// The VFS paths tried for `name`, in q3map2's order (ImageLoad): the extension, if any, is dropped
// and ".tga", ".png", ".jpg" are tried, then ".jpeg". So "x.jpg" still prefers an existing "x.tga".
std::vector<std::string> imageCandidates(std::string_view name);

// The first candidate that exists, decoded. A JPEG gets its alpha from the blue channel of a
// same-sized "<name>_alpha.jpg" when one exists, as q3map2 does. nullopt when no candidate exists;
// ImageError when the file found is malformed (the message names the VFS path and its source).
std::optional<LoadedImage> loadImage(const Vfs& vfs, std::string_view name);

// The size of the image loadImage would find (its alpha companion does not change it), read from
// the header where the format allows; nullopt when no candidate exists; ImageError when malformed.
std::optional<ImageDimensions> loadImageDimensions(const Vfs& vfs, std::string_view name);

}  // namespace q3
