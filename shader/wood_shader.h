#pragma once
/// The wood as a material evaluator: tree-space points in, albedo + growth time + knot out.
/// For now this is what the bakers need; the renderer's material (roughness, fibre direction,
/// bump, ring prefiltering) and the plugin C ABI grow here.

#include <span>

#include "grain/growth_field.h"
#include "grain/rgb.h"

namespace nenrin {

struct WoodSample {
    Rgb albedo;           ///< scene-linear
    double coverage = 1;  ///< 0 outside the felled log (T past the felling time), else 1
    double T = 0;         ///< growth time, years
    double knot = 0;
};

class WoodShader {
public:
    /// The field must outlive the shader.
    explicit WoodShader(const GrowthField& field) : field_(&field) {}

    const GrowthField& field() const { return *field_; }

    /// Evaluates a spatially coherent batch of tree-space points.
    void evaluate(std::span<const Vec3> treePoints, std::span<WoodSample> out,
                  GrowthScratch& scratch, std::vector<GrowthSample>& samples) const;

private:
    const GrowthField* field_;
};

}  // namespace nenrin
