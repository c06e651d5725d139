#pragma once
/// A photographed wood sample (docs/fit.md): the box it was cut to and, per photographed face
/// or planar cut, the image and where it lies: `origin` is the 3-D position of the image's
/// bottom-left corner, `right` and `up` run from it to the bottom-right and top-left corners
/// (metres). The format of ../shared/data/mokume/*/sample.json.

#include <optional>
#include <string>
#include <vector>

#include "util/vec3.h"

namespace nenrin {

struct SampleFace {
    std::string name;
    std::string image;                 ///< path, resolved against the sample file's folder
    std::optional<std::string> rings;  ///< optional ring map (bright = ring boundary)
    Vec3 origin, right, up;
    /// The 3-D position of image point (x, y) in [0, 1]^2, x along a row from the left, y down
    /// the columns from the top (the convention of an image's rows).
    Vec3 at(double x, double y) const { return origin + right * x + up * (1 - y); }
    Vec3 normal() const { return normalize(cross(right, up)); }  ///< out of the sample
};

struct Sample {
    std::string file;  ///< the sample file, for messages
    std::string description;
    Vec3 size;  ///< m: the box's edges (the box is centred at the origin)
    std::vector<SampleFace> faces;
};

/// Reads a sample file strictly (util/json_reader.h): every problem is an InputError naming
/// the file and the JSON path. Faces must have edges 1 mm to 10 m long and not parallel, and
/// name distinct images that exist; at least one face.
Sample loadSampleFile(const std::string& path);

}  // namespace nenrin
