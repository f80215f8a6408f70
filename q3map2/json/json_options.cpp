#include "json_stage.h"

namespace q3::json {

const cli::OptionTable<JsonOptions>& jsonOptionTable() {
    using O = JsonOptions;
    using cli::flag;
    using cli::kImplemented;
    static const cli::OptionTable<O> table = {
        flag<O>({"-unpack"}, &O::unpack, "Unpack the BSP to JSON files in maps/NAME/", kImplemented),
        flag<O>({"-pack"}, &O::pack, "Pack maps/NAME/ back into maps/NAME_json.bsp", kImplemented),
        flag<O>({"-useflagnames"}, &O::useFlagNames,
                "While packing, take surface and content flag values from their names in shaders.json",
                kImplemented),
        flag<O>({"-skipflags"}, &O::skipFlags, "With -useflagnames, skip unknown flag names", kImplemented),
        flag<O>({"-lightmapimages"}, &O::lightmapImages,
                "While unpacking, write lightmap pages as PNG files listed in LightmapImages.json instead of "
                "LightBytes.json",
                kImplemented),
    };
    return table;
}

}  // namespace q3::json
