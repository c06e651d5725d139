#include "fit/fit_report.h"

#include <algorithm>
#include <cmath>

#include "grain/cielab.h"

namespace nenrin {

namespace {

constexpr int kGap = 4;  ///< px of white between the tiles

uint8_t srgbByte(double linear) {
    return uint8_t(std::lround(255 * std::clamp(srgbFromLinear(std::max(0.0, linear)), 0.0, 1.0)));
}

}  // namespace

ReportImage reportImage(const WoodFit& fit) {
    ReportImage r;
    const int side = fit.faces.empty() ? 0 : fit.faces.front().photo[0].width;
    const int faces = int(fit.faces.size());
    r.width = faces * side + (faces + 1) * kGap;
    r.height = 2 * side + 3 * kGap;
    r.rgb.assign(size_t(r.width) * r.height * 3, 255);
    auto put = [&](int x, int y, double red, double green, double blue) {
        uint8_t* p = &r.rgb[(size_t(y) * r.width + x) * 3];
        p[0] = srgbByte(red), p[1] = srgbByte(green), p[2] = srgbByte(blue);
    };
    for (int i = 0; i < faces; ++i) {
        const FaceFigures& f = fit.faces[size_t(i)];
        const int x0 = kGap + i * (side + kGap);
        for (int y = 0; y < side; ++y)
            for (int x = 0; x < side; ++x) {
                put(x0 + x, kGap + y, f.photo[0].at(x, y), f.photo[1].at(x, y),
                    f.photo[2].at(x, y));
                const float* v = f.bake.at(x, y);
                put(x0 + x, 2 * kGap + side + y, v[0], v[1], v[2]);
            }
    }
    return r;
}

}  // namespace nenrin
