#pragma once
/// The pith line of a photographed sample: rings are (near) cylinders around it, so at every
/// pixel the ring normal seen in the photo is the face-plane part of the direction from the
/// pith line to the pixel. Found from the ring directions of all faces:
/// 1. the fibre direction: the one most perpendicular to every ring normal (end grain and
///    side grain agree: rings and fibres are both across the radius);
/// 2. the pith's place across it: a search over a polar grid around the sample (2 mm to
///    2 m out) for the smallest robust misfit, then
/// 3. Ceres (Levenberg-Marquardt, Cauchy loss) refining the place (the tilt is left to
///    focusPithLine: ring directions near a knot pull it off).

#include <span>
#include <string>

#include "fit/face_photo.h"

namespace nenrin {

struct PithLine {
    Vec3 point;      ///< the pith's point nearest the sample's centre
    Vec3 direction;  ///< unit, along the fibres
    /// Coherence-weighted median angle (degrees) between the photos' ring normals and the
    /// line's radial directions, over the directions the fit used.
    double medianMisfitDeg = 0;
    double distance = 0;  ///< from the sample's centre to the line, m
};

/// p less its nearest point on the line: across the line, outwards.
Vec3 radialOffset(const PithLine& pith, const Vec3& p);

/// The distance of p from the line: rings lie near its iso-surfaces (ring_warp.h: on them
/// once warped).
double ringRadius(const PithLine& pith, const Vec3& p);

/// The radial direction of the pith line at p, in the plane with normal `faceNormal`
/// (unnormalised; zero on the pith).
Vec3 radialInPlane(const PithLine& pith, const Vec3& p, const Vec3& faceNormal);

/// Fits the line to the faces' ring directions. Throws InputError naming `sampleFile` when
/// the photos show no ring structure to fit (blank or flat images).
PithLine fitPithLine(std::span<const FacePhoto> faces, const std::string& sampleFile);

/// Moves the line across itself to where the faces' lightness, averaged over shells of equal
/// ringRadius, shows the sharpest rings (the largest variance of the shell means, shells
/// `shell` m thick): ring directions place a far pith poorly along its distance, ring
/// spacing does not. First the place alone on two grids, then place and tilt together by a
/// compass search.
PithLine focusPithLine(const PithLine& pith, std::span<const FacePhoto> faces, double shell = 1e-4);

/// The coherence-weighted median angle (degrees) between the directions' normals and the
/// line's radial directions in their faces.
double pithMisfitDeg(const PithLine& pith, std::span<const FacePhoto> faces);

}  // namespace nenrin
