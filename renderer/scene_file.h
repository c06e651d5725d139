#pragma once
/// Loads a scene JSON file (docs/scene-format.md). Every problem is an InputError naming the
/// file and the JSON path; unknown keys are errors. Paths inside are relative to the file.

#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "renderer/scene.h"

namespace nenrin {

/// Values set into the scene JSON before it is read: (JSON pointer, value) pairs such as
/// ("/render/seed", 7) or ("/camera/position", [1, 2, 3]), applied in order. The pointer's
/// parent must exist; `origin` names where the overrides come from in error messages.
struct SceneOverrides {
    std::string origin = "command line";
    std::vector<std::pair<std::string, nlohmann::json>> values;
};

/// "POINTER=VALUE" strings (`--set`, a batch file's "set") as overrides; VALUE is JSON, or
/// else a string (/materials/0/species=sugi).
SceneOverrides parseSceneOverrides(const std::vector<std::string>& sets);

std::unique_ptr<Scene> loadScene(const std::string& path, const SceneOverrides& overrides = {});

}  // namespace nenrin
