#pragma once
// Where a ring lies: the distance from `centre` along `dir` at which the growth time reaches
// `years` (bisection to far below 1e-6 m; T grows outward on the tests' trees).

#include "grain/growth_field.h"

namespace nenrin::test {

inline double ringRadius(const GrowthField& f, Vec3 centre, Vec3 dir, double years) {
    double lo = 0, hi = 1;
    for (int i = 0; i < 200; ++i) {
        double mid = 0.5 * (lo + hi);
        (f.evaluate(centre + dir * mid).T < years ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

}  // namespace nenrin::test
