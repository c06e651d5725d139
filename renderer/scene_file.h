#pragma once
/// Loads a scene JSON file (docs/scene-format.md). Every problem is an InputError naming the
/// file and the JSON path; unknown keys are errors. Paths inside are relative to the file.

#include <memory>
#include <string>

#include "renderer/scene.h"

namespace nenrin {

std::unique_ptr<Scene> loadScene(const std::string& path);

}  // namespace nenrin
