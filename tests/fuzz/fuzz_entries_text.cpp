// Text inputs: .map sources, shader scripts and the JSON reader (tree and streaming forms).
#include "fuzz_entries.h"

#include "json_error.h"
#include "json_value.h"
#include "log.h"
#include "map_file.h"
#include "num_file.h"
#include "script.h"
#include "shader_parser.h"
#include "texture_projection.h"

#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <string_view>

namespace q3::fuzz {

namespace {

std::string_view asText(std::span<const uint8_t> input) {
    return {reinterpret_cast<const char*>(input.data()), input.size()};
}

// Every conversion a JSON value offers; each either succeeds or throws JsonError.
void convertEverything(const json::Value& value, int depth) {
    const char* context = "fuzz";
    auto attempt = [](auto&& convert) {
        try {
            convert();
        } catch (const json::JsonError&) {
        }
    };
    attempt([&] { value.asInt(context); });
    attempt([&] { value.asByte(context); });
    attempt([&] { value.asFloat(context); });
    attempt([&] { value.asString(context); });
    attempt([&] { value.asObject(context); });
    attempt([&] { value.asArray(3, context); });
    attempt([&] { value.member("Num", context); });
    attempt([&] { value.element(0, context); });
    if (value.source) value.source->where(value.offset);
    // Deep documents are legal JSON; converting the first levels covers every code path.
    if (depth >= 8) return;
    for (const json::Value& item : value.items) convertEverything(item, depth + 1);
}

}  // namespace

void fuzzMap(std::span<const uint8_t> input, const FuzzContext&) {
    map::MapFile parsed;
    try {
        parsed = map::parseMap(asText(input), "fuzz.map");
    } catch (const ScriptError&) {
        return;
    }
    const map::TextureImage image{64, 32, false};
    for (const map::MapEntity& entity : parsed.entities) {
        Vec3 origin;
        entity.origin(origin);
        entity.classname();
        for (const map::MapBrush& brush : entity.brushes)
            for (const map::BrushFace& face : brush.faces)
                if (face.planeValid) map::textureVectors(face, face.plane, image);
        for (const map::MapPatch& patch : entity.patches) {
            if (patch.width < 3 || patch.height < 3 || patch.width > map::kMaxPatchSize ||
                patch.height > map::kMaxPatchSize || patch.control.size() != size_t(patch.width) * size_t(patch.height))
                throw PropertyViolation("parseMap returned a patch with an inconsistent control grid");
            patch.at(patch.width - 1, patch.height - 1);
        }
    }
    map::lightEntities(parsed);
}

void fuzzShader(std::span<const uint8_t> input, const FuzzContext&) {
    Log log(false);
    try {
        parseShaderScript(asText(input), "fuzz.shader", log);
    } catch (const ScriptError&) {
    }
}

void fuzzJson(std::span<const uint8_t> input, const FuzzContext&) {
    const std::string text(asText(input));
    try {
        json::Document document = json::parseDocument("fuzz.json", text);
        convertEverything(document.root, 0);
    } catch (const json::JsonError&) {
    }
    try {
        json::readNumFile("fuzz.json", text, std::numeric_limits<int32_t>::min(), std::numeric_limits<int32_t>::max());
    } catch (const json::JsonError&) {
    }
    try {
        json::readNumFile("fuzz.json", text, 0, 255);
    } catch (const json::JsonError&) {
    }
}

}  // namespace q3::fuzz
