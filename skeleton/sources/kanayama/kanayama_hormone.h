#pragma once
/// The hormone model of Kanayama et al. (paper 2.2): one imaginary auxin-like hormone, made
/// only by new shoots in proportion to their light, flowing only toward the root, inherited by
/// next year's shoots (terminal more than lateral):
///
///     H_n0 = alpha_t H_o0  (terminal)  |  alpha_l H_o0  (lateral)
///     H_n  = beta H_n0 + L dH
///     H_o  = beta H_o0 + gamma H_n        (and so on down to the trunk)
///
/// Our reading: H_o0 is the parent's hormone at the end of the previous year; a shoot with
/// several children receives gamma times the sum of their hormone; an old shoot keeps beta of
/// its own last-year hormone. See docs/tree-kanayama.md.

#include <cstdint>
#include <vector>

namespace nenrin {

/// Hormone a new shoot inherits from its parent (the parent's hormone at the end of last year).
inline double inheritedHormone(double parentHormone, bool terminal, double alphaTerminal,
                               double alphaLateral) {
    return (terminal ? alphaTerminal : alphaLateral) * parentHormone;
}

/// One year's transport, tips to root. Shoots are indexed so that a parent comes before its
/// children (parent[s] < s, or -1 for the root). `previous` is H_s0 (inherited for new shoots,
/// last year's hormone for old ones), `production` is L dH for new shoots and 0 for old ones.
/// Dead shoots (alive[s] == 0) get 0 and pass nothing on. Returns H_s for every shoot.
std::vector<double> transportHormone(const std::vector<int32_t>& parent,
                                     const std::vector<double>& previous,
                                     const std::vector<double>& production,
                                     const std::vector<uint8_t>& alive, double beta, double gamma);

}  // namespace nenrin
