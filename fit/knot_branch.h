#pragma once
/// The branches behind the knots seen on a sample's faces. Two faces' knots that one straight
/// branch from the pith can pass through are one branch, through both centres; a knot seen on
/// one face alone is a branch whose angle to the face its outline tells (an oblique branch
/// draws an oval), leaning the way that passes nearest the pith. Every branch is born with the
/// trunk (all birth times 0, as the fitted trunk's), so its knot's radius at a distance r from the
/// pith is about gamma x r (eq. 3'): gamma comes from the knot's radius on the face it
/// crosses most squarely.

#include <span>
#include <string>
#include <vector>

#include "fit/knot_find.h"
#include "skeleton/skeleton.h"

namespace nenrin {

struct KnotBranch {
    std::vector<std::string> faces;  ///< the faces whose knots placed it
    Vec3 start;                      ///< on the pith line
    std::vector<Vec3> points;        ///< after the start, the last past the sample
    double gamma = 0.1;
    std::string sizedBy;  ///< the face whose knot radius sets gamma
    double radius = 0;    ///< m: that knot's radius in the photograph
    Vec3 sizedAt;         ///< that knot's centre
    /// Years: when the branch's tip passed `sizedAt` (its birth times grow in proportion to
    /// the path from the pith, which it leaves at year 0).
    double birth = 0;
};

/// The branches of the knots (at most one per face). `reach`: how far past the pith the
/// branches must run to leave the sample (m); `ringWidth`: the trunk's mean ring width (m).
std::vector<KnotBranch> knotBranches(std::span<const FaceKnot> knots, const PithLine& pith,
                                     std::span<const SampleFace> faces, double reach,
                                     double ringWidth);

/// Adds the branches to a skeleton whose trunk is one segment along the pith line.
void addKnotBranches(Skeleton& skeleton, std::span<const KnotBranch> branches);

}  // namespace nenrin
