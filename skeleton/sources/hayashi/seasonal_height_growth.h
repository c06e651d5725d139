#pragma once
/// The trunk's height through the years with seasonal growth (Hayashi & Takahashi 3.3, Fig. 9):
/// the leader grows from the start of each year over a growing season (a fraction of the year),
/// fast in spring and slowing to zero at the season's end; in autumn and winter the height
/// stands still. So branches laid on the spiral cluster in height by year.
///
/// Within year y the height is H_y + g_y (1 - (1 - u)^p), u = (t - y) / season in [0, 1].

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace nenrin {

class SeasonalHeightGrowth {
public:
    /// `yearStartHeights`: H_0 = 0 < H_1 <= ... (one more entry than years); `season` in (0, 1];
    /// `shape` = p >= 1.
    SeasonalHeightGrowth(std::vector<double> yearStartHeights, double season, double shape)
        : h_(std::move(yearStartHeights)), season_(season), shape_(shape) {}

    int years() const { return static_cast<int>(h_.size()) - 1; }
    double finalHeight() const { return h_.back(); }
    const std::vector<double>& yearStartHeights() const { return h_; }

    /// Share of a year's growth done at season fraction u in [0, 1].
    double grownFraction(double u) const {
        return 1 - std::pow(1 - std::clamp(u, 0.0, 1.0), shape_);
    }
    /// Season fraction at which a share f of the year's growth is done (inverse of the above).
    double seasonFractionFor(double f) const {
        return 1 - std::pow(1 - std::clamp(f, 0.0, 1.0), 1 / shape_);
    }

    double heightAt(double t) const {
        if (t <= 0) return 0;
        int y = static_cast<int>(std::floor(t));
        if (y >= years()) return finalHeight();
        return h_[y] + (h_[y + 1] - h_[y]) * grownFraction((t - y) / season_);
    }

    /// When the leader first reached height h (infinity above the final height).
    double timeAt(double h) const {
        if (h <= 0) return 0;
        if (h > finalHeight()) return std::numeric_limits<double>::infinity();
        // The year whose growth covers h: H_y < h <= H_{y+1}.
        auto it = std::lower_bound(h_.begin() + 1, h_.end(), h);
        int y = static_cast<int>(it - h_.begin()) - 1;
        double g = h_[y + 1] - h_[y];
        double f = g > 0 ? (h - h_[y]) / g : 1;
        return y + season_ * seasonFractionFor(f);
    }

private:
    std::vector<double> h_;
    double season_, shape_;
};

}  // namespace nenrin
