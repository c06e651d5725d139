#pragma once
/// How directional a texture is: the ratio of the structure tensor's eigenvalues over an n x n
/// grid of values (row i, column j at v[i * n + j]), from forward differences. About 1 for
/// round features, large for streaks. `gi`, `gj` (if given) receive the mean squared
/// differences along i and along j.

#include <algorithm>
#include <cmath>
#include <vector>

namespace nenrin::test {

inline double structureTensorRatio(const std::vector<double>& v, int n, double* gi = nullptr,
                                   double* gj = nullptr) {
    double ii = 0, jj = 0, ij = 0;
    for (int i = 0; i + 1 < n; ++i)
        for (int j = 0; j + 1 < n; ++j) {
            const double di = v[(i + 1) * n + j] - v[i * n + j],
                         dj = v[i * n + j + 1] - v[i * n + j];
            ii += di * di, jj += dj * dj, ij += di * dj;
        }
    if (gi) *gi = ii / ((n - 1.0) * (n - 1.0));
    if (gj) *gj = jj / ((n - 1.0) * (n - 1.0));
    const double tr = ii + jj, d = std::sqrt((ii - jj) * (ii - jj) + 4 * ij * ij);
    return (tr + d) / std::max(tr - d, 1e-30);
}

}  // namespace nenrin::test
