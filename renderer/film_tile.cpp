#include "renderer/film_tile.h"

#include <algorithm>

namespace nenrin {

void TileAovs::writeInto(Film& film, int x0, int y0, int tw, int th,
                         const std::vector<uint32_t>& samples) const {
    for (int j = 0; j < th; ++j) {
        for (int i = 0; i < tw; ++i) {
            size_t p = size_t(j) * tw + i;
            size_t f = size_t(y0 + j - film.firstRow) * film.width + (x0 + i);
            const double inv = 1.0 / samples[p];
            Rgb c = rgb[p] * inv;
            film.rgb[3 * f] = float(c.r);
            film.rgb[3 * f + 1] = float(c.g);
            film.rgb[3 * f + 2] = float(c.b);
            const Rgb d = diffuse[p] * inv;
            film.diffuse[3 * f] = float(d.r);
            film.diffuse[3 * f + 1] = float(d.g);
            film.diffuse[3 * f + 2] = float(d.b);
            film.alpha[f] = float(hits[p] * inv);
            // The samples' variance (unbiased) over their count: the variance of the mean.
            const double n = samples[p], y = luminance(c);
            film.variance[f] =
                n > 1 ? float(std::max(0.0, (luminanceSquares[p] - n * y * y) / (n - 1)) / n) : 0;
            if (!film.samples.empty()) film.samples[f] = float(samples[p]);
            if (hits[p] > 0) {
                double h = 1 / hits[p];
                Rgb a = albedo[p] * h;
                Vec3 n = normal[p] * h;
                film.albedo[3 * f] = float(a.r);
                film.albedo[3 * f + 1] = float(a.g);
                film.albedo[3 * f + 2] = float(a.b);
                film.normal[3 * f] = float(n.x);
                film.normal[3 * f + 1] = float(n.y);
                film.normal[3 * f + 2] = float(n.z);
                film.depth[f] = float(depth[p] * h);
            }
            if (woodHits[p] > 0) {
                film.growthTime[f] = float(growthTime[p] / woodHits[p]);
                film.knot[f] = float(knot[p] / woodHits[p]);
            }
            film.lamella[f] = float(lamella[p]);
            film.occlusion[f] = bounces[p] > 0 ? float(occlusion[p] / bounces[p]) : 0;
            film.visibility[f] = directAll[p] > 0 ? float(directUnblocked[p] / directAll[p]) : 1;
        }
    }
}

}  // namespace nenrin
