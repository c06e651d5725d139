#pragma once
/// Laminated timber products as one box each, with the lamella (board) at a point worked out
/// from the point's coordinates in the box (the fast layout of docs/design/embree.md: one box per
/// glued block, 2x faster than a box per lamella).
///
/// Product space: the block spans [-size/2, size/2]; x is the product's length, y its
/// thickness (layers are stacked along y), z its width. Each layer is cut into strips side by
/// side (a CLT layer's boards, a table top's boards) and each strip into pieces end to end
/// (finger-jointed lengths). Every piece is one board: a lamella with its own rigid transform
/// into the tree (treeFromLamella), drawn by the seeded cut plan (cut_plan.h).

#include <cstdint>
#include <vector>

#include "grain/rgb.h"
#include "renderer/geometry/rigid_transform.h"

namespace nenrin {

/// A board of a product: its box in product space and where it was cut from the log.
struct Lamella {
    int32_t id = 0;      ///< unique within the scene (the AOV)
    Vec3 lower, upper;   ///< box in product space (the board before finger profiles)
    int lengthAxis = 0;  ///< product axis the board's fibres run along (0 = x, 2 = z)
    RigidTransform lamellaFromProduct;  ///< board centre at 0, length along x, width along y
    RigidTransform treeFromLamella;
    RigidTransform treeFromProduct;  ///< treeFromLamella * lamellaFromProduct
    Rgb tint{1, 1, 1};               ///< the board's tree (cut plan): filter on the albedo
};

/// The glue line between boards: a thin film of adhesive seen on every face that cuts it.
struct GlueLine {
    double width = 0.0003;                  ///< m: 0 = invisible (e.g. clear PUR)
    double colour[3] = {0.16, 0.10, 0.05};  ///< scene-linear (dark MUF/PRF adhesives)
};

struct FingerJointProfile {
    double length = 0.015;  ///< m: finger length (0 = butt joints)
    double pitch = 0.006;   ///< m: finger spacing across the board
};

class LaminatedLayout {
public:
    struct Strip {
        double lower, upper;             ///< along the layer's strip axis
        std::vector<double> pieceEnds;   ///< upper ends of the pieces along the length axis
        std::vector<uint32_t> lamellae;  ///< one per piece
    };
    struct Layer {
        double lower, upper;  ///< along y
        int lengthAxis;       ///< 0 (x) or 2 (z)
        std::vector<Strip> strips;
    };

    Vec3 size;  ///< of the block
    std::vector<Layer> layers;
    std::vector<Lamella> lamellae;
    FingerJointProfile fingers;
    GlueLine glue;

    /// Distance (m) from a point of the block to the nearest glued boundary between two of
    /// its boards (finger joints approximately: along the board's length axis).
    double glueDistance(const Vec3& productPoint) const;

    /// The lamella holding a point of the block (clamped into the block). Finger joints are
    /// zig-zag: the boundary between two pieces moves by up to fingers.length along the board,
    /// in a triangle wave across it.
    uint32_t lamellaAt(const Vec3& productPoint) const;
};

/// Glulam beam: `count` lamellae of `thickness` stacked to height count x thickness, all
/// `width` wide and `length` long, split into finger-jointed pieces of random length in
/// [minPiece, maxPiece] (no joints if maxPiece <= 0).
LaminatedLayout glulamLayout(int count, double thickness, double width, double length,
                             double minPiece, double maxPiece, uint64_t seed);
/// CLT panel: `layers` (odd) crossed layers of `thickness`, boards `boardWidth` wide; the
/// outer layers run along x (the panel's length), the ones between along z.
LaminatedLayout cltLayout(int layers, double thickness, double boardWidth, double length,
                          double width);
/// Edge-glued panel (table top): `boards` boards side by side along z, all along x.
LaminatedLayout edgeGluedLayout(int boards, double thickness, double width, double length);

}  // namespace nenrin
