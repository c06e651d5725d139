#pragma once
/// A batch: many frames rendered as one job, each frame its own task (docs/farm.md). The file
/// is JSON:
///   {
///     "scene": "glulam.json",                  // default scene, relative to the batch file
///     "output": "frames/{name}.exr",           // where frames go, relative to the batch file
///     "png": true,                             // also frames/{name}.png
///     "set": {"/render/spp": 64},              // overrides for every frame (JSON pointers)
///     "frames": [{"name": "a", "scene": "...", "set": {...}}, ...],
///     "sweep": {"/render/seed": [1, 2, 3], "/camera/position": [[1,0,1], [0,1,1]]}
///   }
/// Frames are the "frames" list (default: one frame) times every combination of the "sweep"
/// values (the last key varies fastest). A frame's overrides are the batch's "set", then the
/// frame's "set", then its sweep values. Names default to frame-0001, ...; a sweep adds -0001,
/// ... to them. Names must be unique and safe as file names.

#include <string>
#include <vector>

namespace nenrin {

struct BatchFrame {
    std::string name;
    std::string scene;              ///< path, resolved against the batch file
    std::string output, png;        ///< paths ("" png: none)
    std::vector<std::string> sets;  ///< "POINTER=JSON", as `nenrin render --set` takes them
};

/// Reads a batch file; throws InputError naming the file and JSON path on any problem.
std::vector<BatchFrame> loadBatchFile(const std::string& path);

}  // namespace nenrin
