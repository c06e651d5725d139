#include "renderer/furniture/part_frame.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

namespace nenrin {

namespace {

/// Area-weighted surface moments: total area, centroid and covariance. Over a triangle
/// (a, b, c) of area A, the integral of x x^T is A/12 (a a^T + b b^T + c c^T + s s^T) with
/// s = a + b + c.
struct SurfaceMoments {
    double area = 0;
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
};

SurfaceMoments moments(const TriangleMesh& m) {
    SurfaceMoments s;
    Eigen::Vector3d first = Eigen::Vector3d::Zero();
    Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
    for (const auto& t : m.triangles) {
        Eigen::Vector3d v[3];
        for (int c = 0; c < 3; ++c) {
            const Vec3& p = m.positions[t[c]];
            v[c] = {p.x, p.y, p.z};
        }
        const double a = 0.5 * (v[1] - v[0]).cross(v[2] - v[0]).norm();
        const Eigen::Vector3d sum = v[0] + v[1] + v[2];
        s.area += a;
        first += a / 3 * sum;
        second += a / 12 *
                  (v[0] * v[0].transpose() + v[1] * v[1].transpose() + v[2] * v[2].transpose() +
                   sum * sum.transpose());
    }
    if (s.area > 0) {
        s.centroid = first / s.area;
        s.covariance = second / s.area - s.centroid * s.centroid.transpose();
    }
    return s;
}

Vec3 vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

/// The sign that makes a vector's largest component positive.
Vec3 canonical(Vec3 v) {
    const double ax = std::abs(v.x), ay = std::abs(v.y), az = std::abs(v.z);
    const double big = ax >= ay && ax >= az ? v.x : (ay >= az ? v.y : v.z);
    return big < 0 ? -v : v;
}

/// The oriented box of the mesh along the frame's axes: its centre and extent.
void fitBox(const TriangleMesh& m, PartFrame& f) {
    double lo[3], hi[3];
    for (int k = 0; k < 3; ++k) lo[k] = std::numeric_limits<double>::infinity(), hi[k] = -lo[k];
    for (const Vec3& p : m.positions)
        for (int k = 0; k < 3; ++k) {
            const double d = dot(p, f.axes[k]);
            lo[k] = std::min(lo[k], d);
            hi[k] = std::max(hi[k], d);
        }
    if (m.positions.empty())
        for (int k = 0; k < 3; ++k) lo[k] = hi[k] = 0;
    f.extent = {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]};
    f.centre = f.axes[0] * (0.5 * (lo[0] + hi[0])) + f.axes[1] * (0.5 * (lo[1] + hi[1])) +
               f.axes[2] * (0.5 * (lo[2] + hi[2]));
}

}  // namespace

PartFrame partFrame(const TriangleMesh& mesh) {
    PartFrame f;
    const SurfaceMoments s = moments(mesh);
    f.area = s.area;
    f.axes[0] = {1, 0, 0}, f.axes[1] = {0, 1, 0}, f.axes[2] = {0, 0, 1};
    if (s.area > 0) {
        // Eigenvalues in increasing order: the longest axis is the last.
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(s.covariance);
        f.axes[0] = canonical(normalize(vec(solver.eigenvectors().col(2))));
        f.axes[1] = canonical(normalize(vec(solver.eigenvectors().col(1))));
        f.axes[2] = cross(f.axes[0], f.axes[1]);
    }
    fitBox(mesh, f);
    return f;
}

PartFrame partFrameAlong(const TriangleMesh& mesh, const Vec3& fibre) {
    PartFrame f = partFrame(mesh);
    const Vec3 along = normalize(fibre);
    // The fibre a plan gives back unchanged: the frame as nenrin found it, to the last bit.
    if (std::abs(dot(along, f.axes[0])) > 1 - 1e-12) return f;
    // The width: the longest principal axis other than the one nearest the fibre.
    int nearest = 0;
    for (int k = 1; k < 3; ++k)
        if (std::abs(dot(f.axes[k], along)) > std::abs(dot(f.axes[nearest], along))) nearest = k;
    Vec3 width = f.axes[nearest == 0 ? 1 : 0];
    width = normalize(width - along * dot(width, along));
    f.axes[0] = along;
    f.axes[1] = width;
    f.axes[2] = cross(along, width);
    fitBox(mesh, f);
    return f;
}

}  // namespace nenrin
