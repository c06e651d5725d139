#pragma once
/// Rings that are not cylinders around one line: the chestnut cube's rings wave, the hinoki's
/// bend. A smooth radial displacement delta(t, s) of the ring surfaces, bilinear on a lattice
/// over the sample's tangential arc length t (at its mean distance from the line) and its
/// place s along the line, makes the rings the iso-surfaces of F(p) = ringRadius(p) + delta.
/// It is fitted (Ceres) so that grad F lies along every photographed ring normal (the loss
/// of the Mokume paper, on a lattice instead of a network), with second differences keeping
/// it smooth. delta does not vary along the radius, so F stays a distance: rings keep their
/// spacing, and the faces' colours averaged over shells of equal F show them sharply.

#include <span>
#include <vector>

#include "fit/face_photo.h"
#include "fit/pith_fit.h"
#include "grain/point_warp.h"

namespace nenrin {

struct RingWarp {
    PithLine pith;
    Vec3 u, v;              ///< across the line: azimuth 0 along u, a quarter turn along v
    double meanRadius = 0;  ///< m: the sample's; t = meanRadius x azimuth
    double t0 = 0, s0 = 0;  ///< m: node (0, 0)
    double step = 0;        ///< m: between nodes, along t and s
    int nt = 0, ns = 0;
    std::vector<double> delta;  ///< m, t fastest; empty = no warp

    /// The lattice coordinates (t, s) of p, in metres.
    void coordinates(const Vec3& p, double& t, double& s) const;
    double at(const Vec3& p) const;  ///< bilinear; clamped to the lattice's edge
    bool empty() const { return delta.empty(); }
};

/// F(p): the ring radius of p with the warp.
double warpedRingRadius(const PithLine& pith, const RingWarp& warp, const Vec3& p);

/// The warp as the grain file's displacement lattice (grain/point_warp.h) over the box
/// [lower, upper], `nodes` per axis: at each node delta along the outward radial direction,
/// which moves a point's ring radius by delta.
WarpParams grainWarp(const RingWarp& warp, const Vec3& lower, const Vec3& upper, int nodes = 12);

/// Fits the warp to the faces' ring directions; the lattice covers them with steps of
/// `step` m.
RingWarp fitRingWarp(std::span<const FacePhoto> faces, const PithLine& pith, double step = 0.005,
                     double smoothness = 3, double anchor = 1);

}  // namespace nenrin
