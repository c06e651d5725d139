#pragma once
/// Aono & Kunii's A-system tree form ("Botanical tree image generation", IEEE CG&A 4(5), 1984),
/// as used by Im, Shinagawa & Kunii for the trees of their forest: every axis grows in
/// internodes; at the end of each one the axis forks into a continuation (shortened by the
/// contraction ratio r1, deflected by the branching angle a1) and a lateral (r2, a2, on the
/// other side), and the branching plane turns by the divergence angle from one fork to the
/// next. Widths shrink by the width ratio at every fork.
///
/// The presets are the four sympodial structures that Prusinkiewicz & Lindenmayer reproduce
/// from Aono & Kunii (The Algorithmic Beauty of Plants, 1990, Fig. 2.7 a-d); see
/// docs/stand-kunii.md for why these and not the 1984 tables themselves.

#include <string>
#include <vector>

#include "skeleton/skeleton.h"

namespace nenrin {

struct ASystemParams {
    double divergenceAngle = 180;  ///< degrees: turn of the branching plane per fork
    double contraction1 = 0.9;     ///< r1: continuation / parent internode length
    double contraction2 = 0.7;     ///< r2: lateral / parent internode length
    double branchAngle1 = 10;      ///< a1, degrees: deflection of the continuation
    double branchAngle2 = 60;      ///< a2, degrees: angle of the lateral to its parent
    double widthRatio = 0.707;     ///< child / parent width at a fork
    int generations = 9;           ///< forks along an axis (2^(generations-1) axes in all)
    /// Forks along the trunk when it should carry more limbs than `generations` (a forest
    /// tree's persistent leader); the laterals keep at most generations - 1 forks each.
    /// 0 = generations: the A-system as published.
    int trunkForks = 0;
};

/// "aono-kunii-a" .. "aono-kunii-d" (ABOP Fig. 2.7) and "aono-kunii-spiral" (b with the
/// golden divergence angle, 137.5 degrees). Throws InputError for an unknown name.
ASystemParams aSystemPreset(const std::string& name);
std::vector<std::string> aSystemPresetNames();
/// Throws InputError naming the parameter when one is out of range.
void validateASystemParams(const ASystemParams& params);

/// One axis of the form: a polyline starting on its parent axis.
struct ASystemAxis {
    int parent = -1;         ///< parent axis, -1 for the trunk
    int parentSegment = -1;  ///< the parent's segment whose end point this axis starts at
    int order = 0;           ///< 0 trunk, 1 lateral of the trunk, ...
    std::vector<Vec3> points;
};

/// The form in its own units: trunk base at the origin growing up +Z, first internode of
/// length 1. Axes are listed parents first. `trunkSway` scales the trunk's deflection a1
/// (1 = the A-system as is; forest-grown stems are straighter).
std::vector<ASystemAxis> growASystem(const ASystemParams& params, double trunkSway = 1);

/// A standalone A-system skeleton of the given height: every axis grown at one speed (birth
/// time = path length / elongationSpeed), gamma = widthRatio^order, radii from the widths.
Skeleton makeASystemTree(const ASystemParams& params, double height, double elongationSpeed = 1,
                         double trunkSway = 1);

}  // namespace nenrin
