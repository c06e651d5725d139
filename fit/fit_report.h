#pragma once
/// report.png of `nenrin fit`: each face's photograph above nenrin's bake of the same face,
/// faces side by side, 8-bit sRGB.

#include <cstdint>
#include <vector>

#include "fit/wood_fit.h"

namespace nenrin {

struct ReportImage {
    int width = 0, height = 0;
    std::vector<uint8_t> rgb;  ///< 3 per pixel, row 0 at the top
};

ReportImage reportImage(const WoodFit& fit);

}  // namespace nenrin
