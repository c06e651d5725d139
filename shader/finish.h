#pragma once
/// Clear finishes over bare wood: a GGX coat layer (the film of oil or varnish), the strength
/// and width of the fibre highlight seen through it, and the late-wood relief left after
/// sanding. Presets carry the values documented in docs/scene-format.md (materials).

#include <cstdint>
#include <string>

#include "util/json_reader.h"

namespace nenrin {

struct Finish {
    std::string name = "oiled";
    double coatWeight = 1;        ///< 0 = no coat (bare wood), 1 = a full clear film
    double coatRoughness = 0.12;  ///< GGX alpha of the coat
    double coatIor = 1.5;         ///< refractive index of the film (and of the wood fibres)
    double fibreStrength = 0.35;  ///< albedo-tinted fibre highlight (Marschner et al. 2005)
    double fibreWidth = 0.14;     ///< radians: Gaussian width beta of that highlight
    double bumpDepth = 4e-6;      ///< m: height of late wood above early wood
    double woodRoughness = 0.55;  ///< GGX alpha of the bare wood (reported to plugin hosts)
    /// Saw marks (shader/saw_marks.h): relative brightness of the striations on end grain
    /// (side grain shows a fifth), their spacing and groove depth (m); 0 = a smooth surface.
    double sawMarks = 0;
    double sawMarkSpacing = 0.0004;
    double sawMarkDepth = 2e-5;
    uint64_t sawMarkSeed = 5;

    /// The GGX alpha of the surface a host sees: the coat's, or the bare wood's without one.
    double surfaceRoughness() const { return coatWeight > 0 ? coatRoughness : woodRoughness; }
};

/// "matte" (sanded), "oiled", "varnished", "bare" (Lambert only), "brushed" (wire-brushed and
/// oiled: the late wood stands out), "sawn" (straight off the saw: saw marks, no coat). False
/// for an unknown name.
bool finishPreset(const std::string& name, Finish& out);
/// The preset names, comma separated, for error messages.
const char* finishPresetNames();

/// The "finish" key of a material or shader description: a preset name, "oiled" if absent;
/// an unknown name is an InputError at that key listing the presets.
Finish readFinish(JsonReader& reader);

}  // namespace nenrin
