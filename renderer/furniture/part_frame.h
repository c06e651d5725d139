#pragma once
/// A part's own frame: the principal axes of its surface (area-weighted second moments, so a
/// finely tessellated end does not outweigh a long plain side), longest first. The fibre of
/// a board runs along the longest axis; the wide face is normal to the shortest.

#include "renderer/geometry/obj_mesh.h"
#include "renderer/geometry/rigid_transform.h"

namespace nenrin {

struct PartFrame {
    Vec3 centre;      ///< centre of the part's oriented box
    Vec3 axes[3];     ///< unit, right-handed: [0] longest (fibre), [1] width, [2] thickness
    Vec3 extent;      ///< the oriented box's sizes along the axes (m)
    double area = 0;  ///< m²
    /// The part's frame as a transform: x along the fibre, y across the wide face, z through
    /// the thickness, origin at the box's centre.
    RigidTransform modelFromPart() const {
        return RigidTransform::fromAxes(axes[0], axes[1], axes[2], centre);
    }
};

/// The principal frame of a triangle mesh's surface. Each axis points the way its largest
/// component is positive (a deterministic sign). A mesh without area gets the model axes.
PartFrame partFrame(const TriangleMesh& mesh);

/// The same with the fibre given (a user's --plan): the width axis is the longest principal
/// axis other than the one nearest the fibre, made exactly perpendicular to it.
PartFrame partFrameAlong(const TriangleMesh& mesh, const Vec3& fibre);

}  // namespace nenrin
