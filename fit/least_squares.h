#pragma once
/// Ceres, as the fit runs it: quiet, and on one thread, so that a fit's answer does not depend
/// on the machine's cores (Ceres sums a problem's Jacobians per thread).

#include <ceres/ceres.h>

namespace nenrin {

enum class LinearSolver { Dense, Sparse };

inline void solveLeastSquares(ceres::Problem& problem, LinearSolver solver, int iterations) {
    ceres::Solver::Options options;
    options.linear_solver_type =
        solver == LinearSolver::Dense ? ceres::DENSE_QR : ceres::SPARSE_NORMAL_CHOLESKY;
    options.max_num_iterations = iterations;
    options.num_threads = 1;
    options.logging_type = ceres::SILENT;
    ceres::Solver::Summary summary;
    ceres::Solve(options, &problem, &summary);
}

}  // namespace nenrin
