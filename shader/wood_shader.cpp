#include "shader/wood_shader.h"

#include "grain/wood_colour.h"

namespace nenrin {

void WoodShader::evaluate(std::span<const Vec3> treePoints, std::span<WoodSample> out,
                          GrowthScratch& scratch, std::vector<GrowthSample>& samples) const {
    samples.resize(treePoints.size());
    field_->evaluateBatch(treePoints, samples, scratch);
    const ColourParams& colour = field_->params().colour;
    const double felled = field_->params().fellingTime;
    for (size_t i = 0; i < treePoints.size(); ++i) {
        bool outside = felled > 0 && samples[i].T > felled;
        out[i].coverage = outside ? 0 : 1;
        out[i].albedo = outside ? Rgb{} : woodColour(samples[i], treePoints[i], colour);
        out[i].T = samples[i].T;
        out[i].knot = samples[i].knot;
    }
}

}  // namespace nenrin
