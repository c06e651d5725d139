#include "fit/sample_file.h"

#include <cmath>
#include <filesystem>
#include <set>

#include "util/json_parse.h"
#include "util/json_reader.h"

namespace nenrin {

namespace {

/// Faces larger or smaller than this are not photographs of a sample (a typo in the units).
constexpr double kShortestEdge = 0.001, kLongestEdge = 10;

SampleFace readFace(JsonReader& face, const std::string& file, std::set<std::string>& names) {
    SampleFace f;
    f.name = face.string("name", "");
    const std::string image = face.string("image", "");
    if (image.empty()) throw face.error("image", "expected the face's photograph (a path)");
    f.image = pathRelativeTo(file, image);
    std::error_code ec;  // a name the system refuses is a missing file, not a throw
    if (!std::filesystem::is_regular_file(f.image, ec))
        throw face.error("image", "no such image file: " + f.image);
    if (face.has("rings")) {
        f.rings = pathRelativeTo(file, face.string("rings", ""));
        if (!std::filesystem::is_regular_file(*f.rings, ec))
            throw face.error("rings", "no such image file: " + *f.rings);
    }
    f.origin = face.requireVec3("origin");
    f.right = face.requireVec3("right");
    f.up = face.requireVec3("up");
    for (const char* key : {"right", "up"}) {
        const double l = length(std::string(key) == "right" ? f.right : f.up);
        if (!(l >= kShortestEdge && l <= kLongestEdge))
            throw face.error(key, "expected an edge 1 mm to 10 m long (metres), found " +
                                      std::to_string(l) + " m");
    }
    const double sine = length(cross(f.right, f.up)) / (length(f.right) * length(f.up));
    if (!(sine > 0.5))
        throw face.error("up", "expected an edge across `right` (within 30 degrees of square)");
    if (f.name.empty()) f.name = std::to_string(names.size());
    if (!names.insert(f.name).second) throw face.error("name", "a second face named " + f.name);
    face.finish();
    return f;
}

}  // namespace

Sample loadSampleFile(const std::string& path) {
    const nlohmann::json json = parseJsonFile(path);
    JsonReader root(json, path);
    if (!json.is_object()) throw root.error("", "expected a sample file (a JSON object)");
    Sample s;
    s.file = path;
    s.description = root.string("description", "");
    const std::vector<double> size = root.numberList("size");
    if (size.size() != 3 || !(size[0] > 0 && size[1] > 0 && size[2] > 0))
        throw root.error("size", "expected the box's three edges [x, y, z] in metres, all > 0");
    for (double e : size)
        if (!(e >= kShortestEdge && e <= kLongestEdge))
            throw root.error("size", "expected edges 1 mm to 10 m long (metres)");
    s.size = {size[0], size[1], size[2]};
    std::set<std::string> names;
    for (JsonReader& face : root.objectList("faces"))
        s.faces.push_back(readFace(face, path, names));
    if (s.faces.empty()) throw root.error("faces", "expected at least one photographed face");
    root.finish();
    return s;
}

}  // namespace nenrin
