#pragma once
/// Bounds the growth field's culls share: the dieback of eq. 10 from below and backwards.
/// Internal to grain/.

#include <algorithm>
#include <cmath>
#include <limits>

#include "grain/point_box.h"

namespace nenrin {

inline constexpr double kInf = std::numeric_limits<double>::infinity();

/// The whole power n <= eps that the bounds below use in place of the dieback exponent.
inline int diebackPower(double eps) { return static_cast<int>(std::min(eps, 8.0)); }

/// A lower bound of dieback(t, deathTime, eps) without pow(): (t / Tlim)^eps >= (t / Tlim)^n
/// for n = diebackPower(eps) since t / Tlim >= 1 there.
inline double diebackLowerBound(double t, double deathTime, double eps) {
    if (!(t > deathTime)) return t;
    double x = t / deathTime, factor = 1;
    for (int n = diebackPower(eps); n > 0; --n) factor *= x;
    return t * factor;
}

/// The largest time t whose diebackLowerBound(t, deathTime, eps) can stay under `limit`
/// (rounded up): a path must come in under it before dieback to come in under `limit` after.
inline double diebackBudget(double limit, double deathTime, double eps) {
    if (!(limit > deathTime)) return limit;
    const int n = diebackPower(eps);
    if (n <= 0) return limit;
    // t (t / Tlim)^n = limit  <=>  t = Tlim (limit / Tlim)^(1 / (n + 1)); the usual exponents
    // without pow().
    const double x = limit / deathTime;
    const double root = n == 1 ? std::sqrt(x) : n == 2 ? std::cbrt(x) : std::pow(x, 1.0 / (n + 1));
    return deathTime * root * (1 + 1e-9) + 1e-12;
}

}  // namespace nenrin
