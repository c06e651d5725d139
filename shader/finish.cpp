#include "shader/finish.h"

#include <fmt/format.h>

namespace nenrin {

bool finishPreset(const std::string& name, Finish& f) {
    f = Finish{};
    f.name = name;
    if (name == "matte") {
        // Sanded, unfinished: a rough sheen, a broad fibre glow, the most relief.
        f.coatWeight = 0.6;
        f.coatRoughness = 0.45;
        f.fibreStrength = 0.18;
        f.fibreWidth = 0.22;
        f.bumpDepth = 6e-6;
        return true;
    }
    if (name == "oiled") return true;  // the defaults
    if (name == "bare") {
        // Lambert only: no coat, no fibre highlight, no relief (for comparisons with renderers
        // that see only the albedo, such as the POV-Ray twins).
        f.coatWeight = 0;
        f.fibreStrength = 0;
        f.bumpDepth = 0;
        return true;
    }
    if (name == "varnished") {
        // A thick film: a sharp coat reflection, relief mostly filled in.
        f.coatRoughness = 0.03;
        f.fibreStrength = 0.3;
        f.fibreWidth = 0.1;
        f.bumpDepth = 1.5e-6;
        return true;
    }
    if (name == "brushed") {
        // Wire-brushed, then oiled (cladding, floors, table tops): the brush scoops the soft
        // early wood out and leaves the late wood standing, a relief of a few tenths of a
        // millimetre that shows in every highlight. 0.15 mm: a light brushing.
        f.coatRoughness = 0.2;
        f.fibreStrength = 0.3;
        f.fibreWidth = 0.18;
        f.bumpDepth = 1.5e-4;
        return true;
    }
    if (name == "sawn") {
        // Straight off the saw, unfinished: no coat, a rough surface, the teeth's striations
        // (strongest on end grain, where they tear the fibre ends), as on a sawn sample block.
        f.coatWeight = 0;
        f.fibreStrength = 0.12;
        f.fibreWidth = 0.25;
        f.bumpDepth = 6e-6;
        f.woodRoughness = 0.7;
        f.sawMarks = 0.22;
        return true;
    }
    return false;
}

const char* finishPresetNames() { return "matte, oiled, varnished, bare, brushed, sawn"; }

Finish readFinish(JsonReader& r) {
    const std::string preset = r.string("finish", "oiled");
    Finish finish;
    if (!finishPreset(preset, finish))
        throw r.error("finish",
                      fmt::format("expected one of {}, found \"{}\"", finishPresetNames(), preset));
    return finish;
}

}  // namespace nenrin
