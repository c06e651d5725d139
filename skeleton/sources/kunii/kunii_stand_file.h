#pragma once
/// The stand file (format "nenrin-stand", docs/stand-kunii.md): the options a stand was
/// simulated with, I0 of every year, and every tree that ever lived with its yearly record.
/// Written so that it loads back to the same Stand bit for bit (doubles are written with
/// round-trip precision); read strictly: unknown keys, wrong types, out-of-range values and
/// inconsistent histories are InputErrors naming the file and the JSON path.

#include <nlohmann/json.hpp>
#include <string>

#include "skeleton/sources/kunii/kunii_stand.h"

namespace nenrin {

nlohmann::json standToJson(const Stand& stand);
/// `file` names the source in error messages.
Stand standFromJson(const nlohmann::json& json, const std::string& file);

/// Writes atomically (no partial file on failure); InputError if `path` cannot be written.
void saveStandFile(const Stand& stand, const std::string& path);
Stand loadStandFile(const std::string& path);

}  // namespace nenrin
