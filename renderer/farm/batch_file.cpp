#include "renderer/farm/batch_file.h"

#include <fmt/format.h>

#include <set>

#include "util/json_reader.h"

namespace nenrin {

namespace {

constexpr size_t kMaxFrames = 100000;

/// {"/pointer": value, ...} as "POINTER=JSON" strings.
void addSets(JsonReader& r, std::vector<std::string>& sets) {
    const nlohmann::json* set = r.raw("set");
    if (!set) return;
    if (!set->is_object())
        throw r.error("set", fmt::format("expected an object of JSON pointers and values, found {}",
                                         jsonTypeName(*set)));
    for (auto it = set->begin(); it != set->end(); ++it) {
        if (it.key().empty() || it.key()[0] != '/')
            throw r.error("set", fmt::format("\"{}\": expected a JSON pointer such as /render/seed",
                                             it.key()));
        sets.push_back(it.key() + "=" + it.value().dump());
    }
}

bool safeName(const std::string& name) {
    if (name.empty() || name.size() > 128 || name[0] == '.' || name[0] == '-') return false;
    for (char c : name)
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.'))
            return false;
    return true;
}

std::string substitute(std::string pattern, const std::string& name) {
    for (size_t at; (at = pattern.find("{name}")) != std::string::npos;)
        pattern.replace(at, 6, name);
    return pattern;
}

}  // namespace

std::vector<BatchFrame> loadBatchFile(const std::string& path) {
    nlohmann::json json = parseJsonFile(path);
    JsonReader root(json, path);
    root.string("description", "");
    const std::string defaultScene = root.string("scene", "");
    const std::string output = root.string("output", "frames/{name}.exr");
    if (output.find("{name}") == std::string::npos || output.size() < 4 ||
        output.substr(output.size() - 4) != ".exr")
        throw root.error("output",
                         "expected a pattern with {name} ending in .exr, e.g. "
                         "frames/{name}.exr");
    const bool png = root.boolean("png", false);
    std::vector<std::string> common;
    addSets(root, common);

    // The frames list (one unnamed frame if absent).
    std::vector<BatchFrame> frames;
    std::vector<JsonReader> listed = root.objectList("frames");
    if (root.has("frames") && listed.empty()) throw root.error("frames", "an empty list");
    if (listed.empty()) frames.push_back({"", defaultScene, "", "", common});
    for (size_t i = 0; i < listed.size(); ++i) {
        JsonReader& f = listed[i];
        BatchFrame frame{f.string("name", ""), f.string("scene", defaultScene), "", "", common};
        if (frame.scene.empty()) throw f.error("scene", "missing, and the batch has no \"scene\"");
        addSets(f, frame.sets);
        f.finish();
        frames.push_back(std::move(frame));
    }
    if (frames[0].scene.empty()) throw root.error("scene", "missing: the scene to render");

    // The sweep: every combination of its values, the last key fastest.
    std::vector<std::pair<std::string, std::vector<nlohmann::json>>> sweep;
    if (const nlohmann::json* s = root.raw("sweep")) {
        if (!s->is_object())
            throw root.error("sweep", fmt::format("expected an object of JSON pointers and value "
                                                  "lists, found {}",
                                                  jsonTypeName(*s)));
        for (auto it = s->begin(); it != s->end(); ++it) {
            if (it.key().empty() || it.key()[0] != '/')
                throw root.error("sweep", fmt::format("\"{}\": expected a JSON pointer", it.key()));
            if (!it.value().is_array() || it.value().empty())
                throw root.error(
                    "sweep", fmt::format("\"{}\": expected a non-empty list of values", it.key()));
            sweep.emplace_back(it.key(),
                               std::vector<nlohmann::json>(it.value().begin(), it.value().end()));
        }
    }
    size_t combinations = 1;
    for (const auto& [key, values] : sweep) {
        combinations *= values.size();
        if (combinations * frames.size() > kMaxFrames)
            throw root.error("sweep", fmt::format("more than {} frames", kMaxFrames));
    }
    root.finish();

    std::vector<BatchFrame> out;
    std::set<std::string> names;
    for (size_t f = 0; f < frames.size(); ++f) {
        for (size_t c = 0; c < combinations; ++c) {
            BatchFrame frame = frames[f];
            if (frame.name.empty()) frame.name = fmt::format("frame-{:04}", f + 1);
            if (!sweep.empty()) {
                size_t rest = c;
                std::vector<std::string> swept;
                for (size_t k = sweep.size(); k-- > 0;) {
                    const auto& values = sweep[k].second;
                    swept.insert(swept.begin(),
                                 sweep[k].first + "=" + values[rest % values.size()].dump());
                    rest /= values.size();
                }
                frame.sets.insert(frame.sets.end(), swept.begin(), swept.end());
                frame.name += fmt::format("-{:04}", c + 1);
            }
            if (!safeName(frame.name))
                throw InputError(path, "frames",
                                 fmt::format("frame name \"{}\": expected letters, digits, '-', "
                                             "'_' and '.' (not first), at most 128",
                                             frame.name));
            if (!names.insert(frame.name).second)
                throw InputError(path, "frames",
                                 fmt::format("two frames named \"{}\"", frame.name));
            frame.scene = pathRelativeTo(path, frame.scene);
            frame.output = pathRelativeTo(path, substitute(output, frame.name));
            if (png) {
                frame.png = frame.output;
                frame.png.replace(frame.png.size() - 4, 4, ".png");
            }
            out.push_back(std::move(frame));
        }
    }
    return out;
}

}  // namespace nenrin
