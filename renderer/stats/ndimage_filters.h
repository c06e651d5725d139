#pragma once
/// The two filters of scipy.ndimage the wood-photo statistics are defined with (the team's
/// photo-stats script), with scipy's exact conventions, on a plane of doubles.

#include <cstddef>
#include <vector>

namespace nenrin {

/// One channel of an image: row-major, row 0 at the top (numpy's axis 0 = rows = y).
struct Plane {
    int width = 0, height = 0;
    std::vector<double> values;

    Plane() = default;
    Plane(int w, int h, double fill = 0) : width(w), height(h), values(size_t(w) * h, fill) {}
    double& at(int x, int y) { return values[size_t(y) * width + x]; }
    double at(int x, int y) const { return values[size_t(y) * width + x]; }
};

/// scipy.ndimage.gaussian_filter(plane, sigma): a normalised Gaussian kernel of radius
/// int(4 sigma + 0.5) (truncate = 4), along rows then columns, mode 'reflect' (the edge sample
/// repeated: d c b a | a b c d).
Plane gaussianFilter(const Plane& plane, double sigma);

/// scipy.ndimage.sobel(plane, axis), mode 'reflect': axis 1 is the x derivative (correlation
/// with [-1 0 1] along a row, smoothed by [1 2 1] along the column), axis 0 the y derivative.
Plane sobel(const Plane& plane, int axis);

/// The index scipy's 'reflect' mode reads for position i of a line of n samples.
int reflectIndex(int i, int n);

/// np.median: the middle value, or the mean of the two middle values of an even count.
double median(std::vector<double> values);

}  // namespace nenrin
