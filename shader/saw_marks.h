#pragma once
/// Saw marks: the striations a saw or a planer knife leaves on a cut face (finish "sawn").
/// A solid texture of thin parallel sheets in tree space, so every face of a block shows them
/// as parallel lines, each face at its own angle, as on a sawn cube. End grain shows them
/// most (the saw tears the cut fibre ends); side grain, where the teeth cut cleanly, a fifth.

#include "grain/growth_field.h"

namespace nenrin {

struct Finish;

struct SawMarkSample {
    double brightness = 0;  ///< relative change of the albedo
    Vec3 reliefGradient;    ///< slope of the grooves (tree space)
};

/// `dpdx`, `dpdy`: the footprint on the surface (tree space, m; zero = a point sample);
/// `endGrain` 0 (side grain) … 1 (end grain). Zero when the finish has no saw marks.
SawMarkSample sawMarks(const Finish& finish, const Vec3& treePoint, const Vec3& dpdx,
                       const Vec3& dpdy, double endGrain);

}  // namespace nenrin
