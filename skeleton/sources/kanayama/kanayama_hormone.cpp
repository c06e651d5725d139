#include "skeleton/sources/kanayama/kanayama_hormone.h"

#include <stdexcept>

namespace nenrin {

std::vector<double> transportHormone(const std::vector<int32_t>& parent,
                                     const std::vector<double>& previous,
                                     const std::vector<double>& production,
                                     const std::vector<uint8_t>& alive, double beta, double gamma) {
    size_t n = parent.size();
    if (previous.size() != n || production.size() != n || alive.size() != n)
        throw std::invalid_argument("transportHormone: arrays of different lengths");
    // Children come after their parent, so one backward sweep sees every child before its
    // parent: a single pass, no iteration to equilibrium (the paper's point against [8]).
    std::vector<double> fromChildren(n, 0.0), hormone(n, 0.0);
    for (size_t s = n; s-- > 0;) {
        if (!alive[s]) continue;
        hormone[s] = beta * previous[s] + production[s] + gamma * fromChildren[s];
        int32_t p = parent[s];
        if (p >= 0) {
            if (static_cast<size_t>(p) >= s)
                throw std::invalid_argument("transportHormone: parent must precede child");
            fromChildren[p] += hormone[s];
        }
    }
    return hormone;
}

}  // namespace nenrin
