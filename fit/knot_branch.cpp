#include "fit/knot_branch.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace nenrin {

namespace {

/// Branches leave the stem at least this far from its axis (degrees): two knots on a line
/// nearer the fibre are two branches.
constexpr double kMinBranchAngleDeg = 30;
/// Two knots are one branch only if their line passes this near the pith line (m, or this
/// share of the knots' distance from it, whichever is larger).
constexpr double kMaxPithMiss = 0.010, kMaxPithMissShare = 0.5;
/// Knots up to half the stem's radius (the skeleton format's least gamma below).
constexpr double kMinGamma = 0.001, kMaxGamma = 0.5;

const SampleFace& faceNamed(std::span<const SampleFace> faces, const std::string& name) {
    return *std::find_if(faces.begin(), faces.end(),
                         [&](const SampleFace& f) { return f.name == name; });
}

/// Where a line through `point` along `u` (unit, outwards) comes nearest the pith line: the
/// two nearest points; none when that lies outwards of `point` (the line cannot have come
/// from the pith) or the line runs along the pith.
struct Foot {
    Vec3 onPith, onLine;
};
std::optional<Foot> footOnPith(const PithLine& pith, const Vec3& point, const Vec3& u) {
    const Vec3 d = pith.direction, w0 = pith.point - point;
    const double along = dot(d, u), denom = 1 - along * along;
    if (denom < 1e-9) return std::nullopt;
    const double s = (along * dot(u, w0) - dot(d, w0)) / denom;
    const double t = (dot(u, w0) - along * dot(d, w0)) / denom;
    if (t > 0) return std::nullopt;
    return Foot{pith.point + d * s, point + u * t};
}

/// The branch through `point` along `u`: from the pith, where the line comes nearest it,
/// straight to `point`, then along the line past the sample. (Its first segment must run
/// out along the branch: the junction blend (eq. 5) weighs the branch by the angle from the
/// plane square to that segment, so a short sideways step from the pith to the line would
/// all but hide the knot.) False when the line has no foot on the pith.
bool placeBranch(KnotBranch& b, const PithLine& pith, const Vec3& point, const Vec3& u,
                 double reach) {
    const std::optional<Foot> foot = footOnPith(pith, point, u);
    if (!foot) return false;
    b.start = foot->onPith;
    b.points = {point, point + u * reach};
    return true;
}

/// The direction of a branch seen on one face: its section's roundness is the cosine of its
/// angle to the face's normal and its long axis the way it leans; of the lines that fit
/// (one of four), the one that passes nearest the pith, where branches start. Straight out
/// from the pith when none has a foot on it.
Vec3 singleFaceDirection(const FaceKnot& k, const PithLine& pith, const SampleFace& face) {
    const double c = std::clamp(k.roundness, 0.0, 1.0), s = std::sqrt(1 - c * c);
    const Vec3 outwards = radialOffset(pith, k.centre);
    Vec3 best = normalize(outwards);
    double bestMiss = std::numeric_limits<double>::infinity();
    for (double alongNormal : {-1.0, 1.0})
        for (double alongAxis : {-1.0, 1.0}) {
            Vec3 u = face.normal() * (alongNormal * c) + k.longAxis * (alongAxis * s);
            if (dot(u, outwards) <= 0) continue;  // its mirror image is one of the four
            u = normalize(u);
            const std::optional<Foot> foot = footOnPith(pith, k.centre, u);
            if (!foot) continue;
            const double miss = length(foot->onLine - foot->onPith);
            if (miss < bestMiss) bestMiss = miss, best = u;
        }
    return best;
}

/// gamma and the birth from the knot on the face the branch crosses most squarely: an
/// oblique crossing draws an oval 1/cos longer one way; the dark radius is about the two
/// axes' geometric mean.
void sizeBranch(KnotBranch& b, std::span<const FaceKnot> knots, const PithLine& pith,
                std::span<const SampleFace> faces, const Vec3& u, double ringWidth) {
    double best = -1;
    for (const FaceKnot& k : knots) {
        if (std::find(b.faces.begin(), b.faces.end(), k.face) == b.faces.end()) continue;
        const double square = std::abs(dot(u, faceNamed(faces, k.face).normal()));
        if (square <= best) continue;
        best = square;
        b.sizedBy = k.face;
        b.radius = k.radius;
        b.sizedAt = k.centre;
        const double across = k.radius * std::sqrt(std::max(square, 0.1));
        const double r = std::max(ringRadius(pith, k.centre), 1e-4);
        b.birth = 0;
        if (k.ringSpacing > 0 && ringWidth > 0) {
            b.gamma = std::clamp(k.ringSpacing / ringWidth, kMinGamma, kMaxGamma);
            b.birth = std::max(0.0, (r - across / b.gamma) / ringWidth);
        } else {
            b.gamma = std::clamp(across / r, kMinGamma, kMaxGamma);
        }
    }
}

}  // namespace

std::vector<KnotBranch> knotBranches(std::span<const FaceKnot> knots, const PithLine& pith,
                                     std::span<const SampleFace> faces, double reach,
                                     double ringWidth) {
    std::vector<size_t> order(knots.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(),
                     [&](size_t a, size_t b) { return knots[a].evidence > knots[b].evidence; });
    std::vector<bool> used(knots.size(), false);
    std::vector<KnotBranch> branches;
    for (size_t i : order) {
        if (used[i]) continue;
        used[i] = true;
        const FaceKnot& k = knots[i];
        KnotBranch b;
        Vec3 u = singleFaceDirection(k, pith, faceNamed(faces, k.face));
        bool placed = false;
        for (size_t j : order) {
            if (used[j] || knots[j].face == k.face) continue;
            const FaceKnot& other = knots[j];
            Vec3 line = normalize(other.centre - k.centre);
            if (dot(line, radialOffset(pith, (k.centre + other.centre) * 0.5)) < 0)
                line = line * -1.0;
            const double angle = std::acos(std::min(1.0, std::abs(dot(line, pith.direction))));
            if (angle < kMinBranchAngleDeg * M_PI / 180) continue;
            const Vec3 inner = ringRadius(pith, k.centre) < ringRadius(pith, other.centre)
                                   ? k.centre
                                   : other.centre;
            KnotBranch pair;
            pair.faces = {k.face, other.face};
            if (!placeBranch(pair, pith, inner, line, reach)) continue;
            const double miss = length(footOnPith(pith, inner, line)->onLine - pair.start);
            if (miss > std::max(kMaxPithMiss, kMaxPithMissShare * ringRadius(pith, inner)))
                continue;
            b = pair, u = line, used[j] = true, placed = true;
            break;
        }
        if (!placed) {
            b.faces = {k.face};
            if (!placeBranch(b, pith, k.centre, u, reach)) continue;
        }
        sizeBranch(b, knots, pith, faces, u, ringWidth);
        branches.push_back(b);
    }
    return branches;
}

void addKnotBranches(Skeleton& skeleton, std::span<const KnotBranch> branches) {
    for (const KnotBranch& b : branches) {
        std::vector<Vec3> points = {b.start};
        points.insert(points.end(), b.points.begin(), b.points.end());
        // Birth in proportion to the path from the start, `birth` at the sized knot.
        const double pace = b.birth / std::max(length(b.sizedAt - b.start), 1e-6);
        std::vector<double> births = {0};
        for (size_t i = 1; i < points.size(); ++i)
            births.push_back(births.back() + pace * length(points[i] - points[i - 1]));
        ChainProperties props;
        props.gamma = b.gamma;
        skeleton.addBranch(0, points, births, props);
    }
}

}  // namespace nenrin
