#include "option_sets.h"

#include <rapidjson/document.h>

#include <fstream>
#include <sstream>
#include <stdexcept>

namespace q3::test {

std::filesystem::path optionSetsFile() { return std::filesystem::path(Q3MAP_SOURCE_DIR) / "bench" / "option-sets.json"; }

std::vector<OptionSet> readOptionSets(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw std::runtime_error(file.string() + ": cannot be read");
    std::stringstream text;
    text << in.rdbuf();
    rapidjson::Document doc;
    doc.Parse(text.str().c_str());
    const auto fail = [&](const std::string& what) { return std::runtime_error(file.string() + ": " + what); };
    if (doc.HasParseError() || !doc.IsObject()) throw fail("not a JSON object");
    if (!doc.HasMember("sets") || !doc["sets"].IsObject()) throw fail("no \"sets\" object");

    std::vector<OptionSet> sets;
    for (const auto& member : doc["sets"].GetObject()) {
        OptionSet set;
        set.name = member.name.GetString();
        const auto& body = member.value;
        if (!body.IsObject() || !body.HasMember("args") || !body["args"].IsArray())
            throw fail("set \"" + set.name + "\" has no \"args\" array");
        for (const auto& arg : body["args"].GetArray()) {
            if (!arg.IsString()) throw fail("set \"" + set.name + "\" has a non-string argument");
            set.args.emplace_back(arg.GetString());
        }
        if (set.args.empty()) throw fail("set \"" + set.name + "\" has no arguments");
        if (body.HasMember("after")) {
            if (!body["after"].IsString()) throw fail("set \"" + set.name + "\": \"after\" is not a string");
            set.after = body["after"].GetString();
        }
        if (body.HasMember("sampledBuilds")) {
            const auto& sampled = body["sampledBuilds"];
            if (!sampled.IsString() || std::string(sampled.GetString()) != "skip")
                throw fail("set \"" + set.name + "\": \"sampledBuilds\" must be \"skip\"");
            set.skipWhenSampled = true;
        }
        sets.push_back(std::move(set));
    }
    for (const OptionSet& set : sets) {
        if (set.after.empty()) continue;
        bool known = false;
        for (const OptionSet& other : sets) known = known || (other.name == set.after && other.after.empty());
        if (!known) throw fail("set \"" + set.name + "\" runs after \"" + set.after + "\", which is not a plain set");
    }
    return sets;
}

}  // namespace q3::test
