#include "fit/ring_warp.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "fit/least_squares.h"
#include "util/axis_frame.h"

namespace nenrin {

namespace {

constexpr double kLossScale = 0.2;  ///< as the pith fit's
/// m: how far rings typically depart from the fitted cylinders (real wood: 1-3 mm).
constexpr double kTypicalDeparture = 0.002;

/// The lattice cell holding (t, s): its 4 nodes, their bilinear weights and the weights'
/// derivatives along t and s (1/m).
struct Cell {
    std::array<int, 4> node;
    std::array<double, 4> weight, dt, ds;
};

Cell cellAt(const RingWarp& w, double t, double s) {
    auto axis = [&](double x, double origin, int n, int& i0, double& f) {
        const double c = std::clamp((x - origin) / w.step, 0.0, double(n - 1) - 1e-9);
        i0 = int(std::floor(c));
        f = c - i0;
    };
    int i, j;
    double ft, fs;
    axis(t, w.t0, w.nt, i, ft);
    axis(s, w.s0, w.ns, j, fs);
    Cell c;
    for (int corner = 0; corner < 4; ++corner) {
        const int di = corner & 1, dj = corner >> 1;
        const double wt = di ? ft : 1 - ft, ws = dj ? fs : 1 - fs;
        c.node[size_t(corner)] = (j + dj) * w.nt + (i + di);
        c.weight[size_t(corner)] = wt * ws;
        c.dt[size_t(corner)] = (di ? 1 : -1) / w.step * ws;
        c.ds[size_t(corner)] = wt * (dj ? 1 : -1) / w.step;
    }
    return c;
}

/// One photographed ring normal against grad F = radial + d delta/dt grad t + d delta/ds grad s.
struct DirectionResidual {
    Vec3 radial;   ///< grad ringRadius: the outward radial unit vector
    Vec3 alongT;   ///< grad t: meanRadius / R times the tangential unit vector
    Vec3 alongS;   ///< grad s: the line's direction
    Vec3 tangent;  ///< the photo's ring tangent in the face (3-D unit)
    Vec3 normal;   ///< the face's
    std::array<double, 4> dt, ds;
    double weight;
    template <class T>
    bool operator()(T const* const* delta, T* residual) const {
        T gt(0), gs(0);
        for (size_t c = 0; c < 4; ++c) gt += delta[c][0] * dt[c], gs += delta[c][0] * ds[c];
        T g[3] = {radial.x + gt * alongT.x + gs * alongS.x,
                  radial.y + gt * alongT.y + gs * alongS.y,
                  radial.z + gt * alongT.z + gs * alongS.z};
        // The sine of the angle in the face's plane (what photo-stats --rings measures): over
        // the in-plane part of grad F, so that grad F cannot escape the loss by leaving the
        // plane.
        const T out = g[0] * normal.x + g[1] * normal.y + g[2] * normal.z;
        g[0] -= out * normal.x, g[1] -= out * normal.y, g[2] -= out * normal.z;
        using std::sqrt;
        const T across = g[0] * tangent.x + g[1] * tangent.y + g[2] * tangent.z;
        residual[0] = weight * across / sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2] + T(1e-12));
        return true;
    }
};

/// lambda (a - 2 b + c): the warp's curvature along one axis.
struct CurvatureResidual {
    double lambda;
    template <class T>
    bool operator()(const T* a, const T* b, const T* c, T* residual) const {
        residual[0] = T(lambda) * (a[0] - T(2) * b[0] + c[0]);
        return true;
    }
};

/// A pull to 0: rings depart from cylinders by millimetres (and a constant delta changes no
/// direction).
struct AnchorResidual {
    double lambda;
    template <class T>
    bool operator()(const T* a, T* residual) const {
        residual[0] = T(lambda) * a[0];
        return true;
    }
};

/// The warp's frame: azimuth 0 towards `centre` (the sample), so the azimuth's seam at half
/// a turn lies opposite the sample, not across it (unless the pith runs through it).
RingWarp frameOf(const PithLine& pith, const Vec3& centre) {
    RingWarp w;
    w.pith = pith;
    const Vec3 towards = radialOffset(pith, centre);
    w.u = length(towards) > 0 ? normalize(towards) : AxisFrame(pith.direction).s;
    w.v = cross(pith.direction, w.u);
    return w;
}

}  // namespace

void RingWarp::coordinates(const Vec3& p, double& t, double& s) const {
    const Vec3 q = p - pith.point;
    s = dot(q, pith.direction);
    t = meanRadius * std::atan2(dot(q, v), dot(q, u));
}

double RingWarp::at(const Vec3& p) const {
    if (delta.empty()) return 0;
    double t, s;
    coordinates(p, t, s);
    const Cell c = cellAt(*this, t, s);
    double sum = 0;
    for (size_t k = 0; k < 4; ++k) sum += c.weight[k] * delta[size_t(c.node[k])];
    return sum;
}

double warpedRingRadius(const PithLine& pith, const RingWarp& warp, const Vec3& p) {
    return ringRadius(pith, p) + warp.at(p);
}

WarpParams grainWarp(const RingWarp& warp, const Vec3& lower, const Vec3& upper, int nodes) {
    WarpParams g;
    if (warp.empty()) return g;
    g.origin = lower;
    g.step = (upper - lower) * (1.0 / (nodes - 1));
    g.nx = g.ny = g.nz = nodes;
    for (int k = 0; k < nodes; ++k)
        for (int j = 0; j < nodes; ++j)
            for (int i = 0; i < nodes; ++i) {
                const Vec3 p = g.origin + Vec3{i * g.step.x, j * g.step.y, k * g.step.z};
                const Vec3 radial = radialOffset(warp.pith, p);
                const double r = length(radial);
                g.displacement.push_back(r > 0 ? radial * (warp.at(p) / r) : Vec3{});
            }
    return g;
}

RingWarp fitRingWarp(std::span<const FacePhoto> faces, const PithLine& pith, double step,
                     double smoothness, double anchor) {
    // The faces' pixels: their centre, their mean distance from the line, and (below) the
    // lattice's extent over them.
    Vec3 centre;
    double radiusSum = 0, count = 0;
    for (const FacePhoto& f : faces)
        for (const RingDirection& r : f.directions)
            centre = centre + r.position, radiusSum += ringRadius(pith, r.position), ++count;
    if (count == 0) return RingWarp{};
    RingWarp warp = frameOf(pith, centre * (1 / count));
    warp.meanRadius = radiusSum / count;
    double tMin = std::numeric_limits<double>::infinity(), tMax = -tMin, sMin = tMin, sMax = -tMin;
    for (const FacePhoto& f : faces)
        for (const RingDirection& r : f.directions) {
            double t, s;
            warp.coordinates(r.position, t, s);
            tMin = std::min(tMin, t), tMax = std::max(tMax, t);
            sMin = std::min(sMin, s), sMax = std::max(sMax, s);
        }
    if (!(warp.meanRadius > 0) || !(tMax > tMin)) return RingWarp{};
    warp.step = step;
    warp.t0 = tMin - step, warp.s0 = sMin - step;
    warp.nt = int(std::ceil((tMax - tMin) / step)) + 3;
    warp.ns = int(std::ceil((sMax - sMin) / step)) + 3;
    warp.delta.assign(size_t(warp.nt) * warp.ns, 0.0);

    ceres::Problem problem;
    for (const FacePhoto& f : faces) {
        const Vec3 n = f.face->normal();
        for (const RingDirection& r : f.directions) {
            if (r.weight <= 0.05) continue;
            const Vec3 radialPart = radialOffset(pith, r.position);
            const double radius = length(radialPart);
            if (!(radius > 0)) continue;
            const Vec3 radial = radialPart * (1 / radius);
            const Vec3 tangential = cross(pith.direction, radial);
            double t, s;
            warp.coordinates(r.position, t, s);
            const Cell cell = cellAt(warp, t, s);
            auto* cost =
                new ceres::DynamicAutoDiffCostFunction<DirectionResidual, 4>(new DirectionResidual{
                    radial, tangential * (warp.meanRadius / radius), pith.direction,
                    cross(n, r.normal), n, cell.dt, cell.ds, std::sqrt(r.weight)});
            std::vector<double*> blocks;
            for (int node : cell.node) {
                cost->AddParameterBlock(1);
                blocks.push_back(&warp.delta[size_t(node)]);
            }
            cost->SetNumResiduals(1);
            problem.AddResidualBlock(cost, new ceres::CauchyLoss(kLossScale), blocks);
        }
    }
    auto index = [&](int i, int j) { return size_t(j * warp.nt + i); };
    // Curvature is penalised in units of the lattice step: delta / step.
    const double lambda = smoothness / step;
    for (int j = 0; j < warp.ns; ++j)
        for (int i = 0; i < warp.nt; ++i) {
            double* centre = &warp.delta[index(i, j)];
            problem.AddResidualBlock(new ceres::AutoDiffCostFunction<AnchorResidual, 1, 1>(
                                         new AnchorResidual{anchor / kTypicalDeparture}),
                                     nullptr, centre);
            if (i > 0 && i + 1 < warp.nt)
                problem.AddResidualBlock(
                    new ceres::AutoDiffCostFunction<CurvatureResidual, 1, 1, 1, 1>(
                        new CurvatureResidual{lambda}),
                    nullptr, &warp.delta[index(i - 1, j)], centre, &warp.delta[index(i + 1, j)]);
            if (j > 0 && j + 1 < warp.ns)
                problem.AddResidualBlock(
                    new ceres::AutoDiffCostFunction<CurvatureResidual, 1, 1, 1, 1>(
                        new CurvatureResidual{lambda}),
                    nullptr, &warp.delta[index(i, j - 1)], centre, &warp.delta[index(i, j + 1)]);
        }
    solveLeastSquares(problem, LinearSolver::Sparse, 50);
    return warp;
}

}  // namespace nenrin
