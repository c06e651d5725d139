#include "fit/pith_fit.h"

#include <ceres/ceres.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>
#include <vector>

#include "fit/least_squares.h"
#include "renderer/stats/image_statistics.h"
#include "util/axis_frame.h"
#include "util/input_error.h"

namespace nenrin {

namespace {

/// The Cauchy loss's scale: a misfit of sin 11.5 degrees counts half as much as a square.
constexpr double kLossScale = 0.2;
/// A face's fine texture whose gradients are this anisotropic (the smaller in-plane eigenvalue
/// over the larger) is side grain.
constexpr double kSideGrainAnisotropy = 0.5;
/// The grid search: radii from the sample's centre, log-spaced, and directions around it.
constexpr double kNearest = 0.002, kFarthest = 2.0;
constexpr int kRadii = 48, kAngles = 72;

/// The frame the line is searched in: d0 along the fibres, u and v across.
struct SearchFrame {
    Vec3 d0, u, v, centre;
};

/// The misfit of one ring direction for a line through c along d: the line's unit radial
/// direction at the pixel along the photo's ring tangent (in the face's plane, across its
/// normal). Where the face is tangential to the rings the radial direction leaves the face
/// and the photo's ring direction says little: the misfit is small there whatever it shows.
template <class T>
T misfitSine(const RingDirection& r, const Vec3& faceNormal, const T c[3], const T d[3]) {
    const T q[3] = {T(r.position.x) - c[0], T(r.position.y) - c[1], T(r.position.z) - c[2]};
    const T along = q[0] * d[0] + q[1] * d[1] + q[2] * d[2];
    T radial[3] = {q[0] - d[0] * along, q[1] - d[1] * along, q[2] - d[2] * along};
    const Vec3 t = cross(faceNormal, r.normal);  // along the photo's rings
    const T across = radial[0] * t.x + radial[1] * t.y + radial[2] * t.z;
    const T norm2 = radial[0] * radial[0] + radial[1] * radial[1] + radial[2] * radial[2];
    using std::sqrt;
    return across / sqrt(norm2 + T(1e-12));
}

/// The line of parameters (place a, b; tilt alpha, beta) in the frame.
template <class T>
void lineOf(const SearchFrame& f, const T* place, const T* tilt, T c[3], T d[3]) {
    T raw[3] = {T(f.d0.x) + tilt[0] * f.u.x + tilt[1] * f.v.x,
                T(f.d0.y) + tilt[0] * f.u.y + tilt[1] * f.v.y,
                T(f.d0.z) + tilt[0] * f.u.z + tilt[1] * f.v.z};
    using std::sqrt;
    const T l = sqrt(raw[0] * raw[0] + raw[1] * raw[1] + raw[2] * raw[2]);
    for (int i = 0; i < 3; ++i) d[i] = raw[i] / l;
    c[0] = T(f.centre.x) + place[0] * f.u.x + place[1] * f.v.x;
    c[1] = T(f.centre.y) + place[0] * f.u.y + place[1] * f.v.y;
    c[2] = T(f.centre.z) + place[0] * f.u.z + place[1] * f.v.z;
}

struct MisfitResidual {
    const SearchFrame* frame;
    RingDirection ring;
    Vec3 faceNormal;
    template <class T>
    bool operator()(const T* place, const T* tilt, T* residual) const {
        T c[3], d[3];
        lineOf(*frame, place, tilt, c, d);
        residual[0] = std::sqrt(ring.weight) * misfitSine(ring, faceNormal, c, d);
        return true;
    }
};

/// Every ring direction with its face's normal.
struct Observation {
    const RingDirection* ring;
    Vec3 faceNormal;
};

std::vector<Observation> observations(std::span<const FacePhoto> faces) {
    std::vector<Observation> out;
    for (const FacePhoto& f : faces) {
        const Vec3 n = f.face->normal();
        for (const RingDirection& r : f.directions)
            if (r.weight > 0.05) out.push_back({&r, n});
    }
    return out;
}

/// The fibre direction: the direction most nearly across every face's fine-texture gradients,
/// the smallest eigenvector of sum g g^T, reweighted a few times (Cauchy weights of the sine
/// between g and the plane across the estimate) so that fibres swirling round a knot do not
/// pull it.
Vec3 fibreDirection(std::span<const FacePhoto> faces) {
    Vec3 d{0, 0, 0};
    for (int round = 0; round < 6; ++round) {
        Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
        for (const FacePhoto& f : faces)
            for (const Vec3& g : f.fineGradients) {
                const double g2 = dot(g, g);
                if (g2 <= 0) continue;
                double w = 1;
                if (round > 0) {
                    const double along2 = dot(g, d) * dot(g, d) / g2;  // sine^2 off the plane
                    w = 1 / (1 + along2 / (kLossScale * kLossScale));
                }
                const Eigen::Vector3d v(g.x, g.y, g.z);
                m += w * v * v.transpose();
            }
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(m);
        const Eigen::Vector3d values = eigen.eigenvalues();  // ascending
        // Faces all in one plane have no gradient across it: the smallest is their normal,
        // the fibres' direction only if the face is end grain. Side grain shows it as the
        // face's own direction of least texture (fibres make it anisotropic).
        const bool onePlane = values(0) < 1e-6 * values(2);
        const int column = onePlane && values(1) < kSideGrainAnisotropy * values(2) ? 1 : 0;
        const Eigen::Vector3d e = eigen.eigenvectors().col(column);
        d = {e.x(), e.y(), e.z()};
    }
    // Point it along its largest coordinate's positive side: the same line either way.
    const double big = std::abs(d.x) > std::abs(d.y) && std::abs(d.x) > std::abs(d.z)
                           ? d.x
                           : (std::abs(d.y) > std::abs(d.z) ? d.y : d.z);
    return big < 0 ? d * -1.0 : d;
}

SearchFrame frameAround(const Vec3& d0, const Vec3& centre) {
    const AxisFrame frame(d0);
    return {d0, frame.s, frame.t, centre};
}

double robustCost(std::span<const Observation> obs, size_t stride, const SearchFrame& f,
                  const double place[2], const double tilt[2]) {
    double c[3], d[3];
    lineOf(f, place, tilt, c, d);
    double cost = 0;
    const double s2 = kLossScale * kLossScale;
    for (size_t i = 0; i < obs.size(); i += stride) {
        const double e = misfitSine(*obs[i].ring, obs[i].faceNormal, c, d);
        cost += obs[i].ring->weight * s2 * std::log1p(e * e / s2);
    }
    return cost;
}

/// Variance of the shell means of L* around the line: how sharp its rings look.
double ringSharpness(const PithLine& pith, std::span<const FacePhoto> faces, double shell) {
    std::vector<double> sum, count;
    std::vector<std::pair<double, double>> samples;  // radius, L*
    double inner = std::numeric_limits<double>::infinity();
    for (const FacePhoto& f : faces)
        for (int y = 2; y < f.lightness.height - 2; y += 2)
            for (int x = 2; x < f.lightness.width - 2; x += 2) {
                const double r = ringRadius(pith, f.position(x, y));
                samples.push_back({r, f.lightness.at(x, y)});
                inner = std::min(inner, r);
            }
    for (const auto& [r, l] : samples) {
        const size_t b = size_t((r - inner) / shell);
        if (b >= sum.size()) sum.resize(b + 1, 0), count.resize(b + 1, 0);
        sum[b] += l, count[b] += 1;
    }
    double total = 0, total2 = 0, n = 0;
    for (size_t b = 0; b < sum.size(); ++b) {
        if (count[b] < 4) continue;
        const double m = sum[b] / count[b];
        total += m * count[b], total2 += m * m * count[b], n += count[b];
    }
    return n > 0 ? total2 / n - (total / n) * (total / n) : 0;
}

}  // namespace

PithLine focusPithLine(const PithLine& pith, std::span<const FacePhoto> faces, double shell) {
    const AxisFrame frame(pith.direction);
    const Vec3 &u = frame.s, &v = frame.t;
    // A compass search over place (across the line) and tilt (of its direction, radians),
    // halving the steps when no move sharpens the rings.
    constexpr int kParameters = 4;  // place (m) and tilt (rad), each across the line
    auto lineAt = [&](const double x[kParameters]) {
        PithLine l = pith;
        l.direction = normalize(pith.direction + u * x[2] + v * x[3]);
        l.point = pith.point + u * x[0] + v * x[1];
        return l;
    };
    double x[kParameters] = {0, 0, 0, 0};
    const double placeStep = std::max(5e-4, 0.01 * pith.distance);
    double best = ringSharpness(pith, faces, shell);
    // First the place alone on two grids (the sharpness varies slowly along the radius, where
    // a local search stops early), ...
    for (double gridStep : {placeStep, placeStep / 5}) {
        const double x0 = x[0], x1 = x[1];
        for (int i = -6; i <= 6; ++i)
            for (int j = -6; j <= 6; ++j) {
                const double trial[kParameters] = {x0 + i * gridStep, x1 + j * gridStep, 0, 0};
                const double s = ringSharpness(lineAt(trial), faces, shell);
                if (s > best) best = s, x[0] = trial[0], x[1] = trial[1];
            }
    }
    // ... then place and tilt together.
    double step[kParameters] = {placeStep / 5, placeStep / 5, 0.02, 0.02};
    const double smallest[kParameters] = {2e-5, 2e-5, 2e-4, 2e-4};
    for (int evaluations = 0; evaluations < 400;) {
        bool moved = false;
        for (int k = 0; k < kParameters; ++k)
            for (double sign : {1.0, -1.0}) {
                double trial[kParameters];
                std::copy(x, x + kParameters, trial);
                trial[k] += sign * step[k];
                const double s = ringSharpness(lineAt(trial), faces, shell);
                ++evaluations;
                if (s > best) {
                    best = s, moved = true;
                    std::copy(trial, trial + kParameters, x);
                }
            }
        if (moved) continue;
        bool done = true;
        for (int k = 0; k < kParameters; ++k) {
            step[k] /= 2;
            done = done && step[k] < smallest[k];
        }
        if (done) break;
    }
    PithLine out = lineAt(x);
    out.point = out.point - out.direction * dot(out.point, out.direction);
    out.distance = length(out.point);
    out.medianMisfitDeg = pithMisfitDeg(out, faces);
    return out;
}

Vec3 radialOffset(const PithLine& pith, const Vec3& p) {
    const Vec3 q = p - pith.point;
    return q - pith.direction * dot(q, pith.direction);
}

double ringRadius(const PithLine& pith, const Vec3& p) { return length(radialOffset(pith, p)); }

Vec3 radialInPlane(const PithLine& pith, const Vec3& p, const Vec3& faceNormal) {
    const Vec3 radial = radialOffset(pith, p);
    return radial - faceNormal * dot(radial, faceNormal);
}

double pithMisfitDeg(const PithLine& pith, std::span<const FacePhoto> faces) {
    std::vector<double> angles, weights;
    for (const FacePhoto& f : faces) {
        const Vec3 n = f.face->normal();
        for (const RingDirection& r : f.directions) {
            const Vec3 radial = radialInPlane(pith, r.position, n);
            const double across = std::abs(dot(radial, cross(n, r.normal)));
            const double along = std::abs(dot(radial, r.normal));
            angles.push_back(std::atan2(across, along) * 180 / std::numbers::pi);
            weights.push_back(r.weight);
        }
    }
    return angles.empty() ? 0 : weightedMedian(angles, weights);
}

PithLine fitPithLine(std::span<const FacePhoto> faces, const std::string& sampleFile) {
    const std::vector<Observation> obs = observations(faces);
    if (obs.size() < 100)
        throw InputError(sampleFile, "faces",
                         "the photographs show no ring structure to fit (blank or flat images?)");
    const SearchFrame frame = frameAround(fibreDirection(faces), Vec3{0, 0, 0});

    // 2. The grid search, on every 8th direction.
    double best[2] = {0, 0}, tilt[2] = {0, 0};
    double bestCost = robustCost(obs, 8, frame, best, tilt);
    for (int i = 0; i < kRadii; ++i) {
        const double r = kNearest * std::pow(kFarthest / kNearest, i / double(kRadii - 1));
        for (int k = 0; k < kAngles; ++k) {
            const double a = 2 * std::numbers::pi * k / kAngles;
            const double place[2] = {r * std::cos(a), r * std::sin(a)};
            const double cost = robustCost(obs, 8, frame, place, tilt);
            if (cost < bestCost) bestCost = cost, best[0] = place[0], best[1] = place[1];
        }
    }

    // 3. Place and tilt together, on every other direction.
    ceres::Problem problem;
    double place[2] = {best[0], best[1]};
    for (size_t i = 0; i < obs.size(); i += 2) {
        auto* cost = new ceres::AutoDiffCostFunction<MisfitResidual, 1, 2, 2>(
            new MisfitResidual{&frame, *obs[i].ring, obs[i].faceNormal});
        problem.AddResidualBlock(cost, new ceres::CauchyLoss(kLossScale), place, tilt);
    }
    // The tilt stays: ring directions on faces near a knot pull it off (the focus below
    // refines it from the ring spacing instead).
    problem.SetParameterBlockConstant(tilt);
    solveLeastSquares(problem, LinearSolver::Dense, 100);

    PithLine pith;
    double c[3], d[3];
    lineOf(frame, place, tilt, c, d);
    pith.direction = normalize(Vec3{d[0], d[1], d[2]});
    const Vec3 through{c[0], c[1], c[2]};
    // The line's point nearest the sample's centre.
    pith.point = through - pith.direction * dot(through, pith.direction);
    pith.distance = length(pith.point);
    pith.medianMisfitDeg = pithMisfitDeg(pith, faces);
    return pith;
}

}  // namespace nenrin
