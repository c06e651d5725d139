#pragma once
/// Akagi & Kitajima's hierarchical-Bayes model of the 13 tree parameters (paper section 3,
/// docs/design/models.md §5), fitted by our own MCMC (Metropolis-within-Gibbs with adaptive
/// random-walk steps) instead of OpenBUGS, and the posterior-predictive drawing of new parameter
/// sets (section 3.3) that feeds the generator (akagi_generator.h), with the plausibility check the
/// paper suggests.
///
/// Per parameter i (all fitted independently: the observed parameters are data):
///   angles P7, P8, P10:  P_i ~ Normal(W_i0 + sum_j W_ij P_j + ID_i[tree], sigma_i)
///   P1-P6, P9:           P_i ~ Gamma(alpha, beta_i), log alpha = W_i0 + sum_j W_ij P_j
///                                                               + ID_i[tree] + Err_i[row]
///   P11, P12:            P_i ~ Normal(theta_i, sigma_i);  P13 ~ Gamma(alpha_13, beta_13)
/// ID_i ~ N(0, sigma_ID,i), Err_i ~ N(0, sigma_err,i). Which P_j enter which parameter is
/// akagiCovariates(); the priors are listed in docs/tree-akagi.md.

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "skeleton/skeleton_writer.h"
#include "skeleton/sources/akagi/akagi_generator.h"
#include "skeleton/sources/akagi/akagi_observations.h"
#include "skeleton/sources/akagi/akagi_params.h"
#include "util/hash.h"

namespace nenrin {

enum class AkagiFamily { Normal, Gamma };

struct McmcOptions {
    int burnIn = 10000;  ///< sweeps discarded (paper: 10000); step sizes adapt during them
    int samples = 1000;  ///< sweeps kept (paper: 1000)
    int thin = 1;        ///< sweeps per kept sample
    uint64_t seed = 1;
    /// false: the sparse botanical covariate sets of akagiCovariates(); true: the paper's
    /// eq. 11 / 15 literally, every P_j (j <= 10, j != i) in every regression.
    bool paperCovariates = false;
};

/// Posterior of one parameter's sub-model. Weights are in raw units: the linear predictor is
/// weightMean[0] + sum_k weightMean[k+1] * P_{covariates[k]} (log-shape for Gamma, mean for
/// Normal).
struct AkagiParamFit {
    AkagiFamily family = AkagiFamily::Gamma;
    std::vector<int> covariates;  ///< parameter indices 0..12
    bool individualEffect = false, observationError = false;
    std::vector<double> weightMean, weightSd;
    double rateMean = 0, rateSd = 0;           ///< Gamma: beta (1 / unit of the parameter)
    double sigmaMean = 0, sigmaSd = 0;         ///< Normal: residual sd (unit of the parameter)
    double sigmaIdMean = 0, sigmaErrMean = 0;  ///< sd of ID / Err (log-shape or parameter unit)
    bool constant = false;  ///< the column has no spread: not sampled, drawn as constantValue
    double constantValue = 0;
    double acceptance = 0;  ///< Metropolis acceptance rate after burn-in (all moves)

    // Internal: standardisation and the kept draws, used by drawAkagiParams.
    double yScale = 1, yMean = 0;  ///< Gamma fits y / yScale; Normal fits (y - yMean) / yScale
    std::vector<double> xMean, xSd;
    /// Per kept sample: the standardised weights, then beta (of y / yScale) or sigma (of the
    /// standardised y), sigma_ID, sigma_err.
    std::vector<std::vector<double>> draws;
};

struct AkagiFit {
    std::string source;
    std::array<AkagiParamFit, kAkagiParamCount> params;
    AkagiParams initialGuess;  ///< the table's mean row: where predictive draws start (3.3)
};

/// The covariates j of parameter i (0-based indices).
std::vector<int> akagiCovariates(int i, bool paperCovariates);

/// Fits the model. Throws InputError if the table cannot identify it (too few rows or trees,
/// a constant column) or the options are out of range.
AkagiFit fitAkagiModel(const ObservationTable& table, const McmcOptions& options = {});

/// One parameter set from the posterior predictive: a posterior sample is picked, a new
/// individual effect drawn, and the conditionals iterated from the initial guess (paper 3.3)
/// until every parameter lies in its range.
AkagiParams drawAkagiParams(const AkagiFit& fit, SplitMix& rng);

struct AkagiGrowOptions {
    McmcOptions mcmc;
    AkagiGenerateOptions generate;
    int maxAttempts = 200;  ///< draws before giving up on a plausible tree
};

/// The CLI's entry point: a built-in species name (akagiSpeciesNames()) or the path of an
/// observation table; fits, draws and generates until isPlausible() accepts the tree.
/// The fit uses options.mcmc.seed (the species model does not change with the tree seed).
AkagiTree growAkagiSpecies(const std::string& speciesOrTablePath, uint64_t seed, double years,
                           const AkagiGrowOptions& options = {});

/// Description and provenance for saveSkeletonFile: model "akagi", the species or table, seed,
/// years, the 13 drawn parameters and the number of draws the plausibility check needed.
SkeletonFileInfo akagiSkeletonInfo(const AkagiTree& tree, const std::string& speciesOrTablePath,
                                   uint64_t seed);

/// The built-in ILLUSTRATIVE tables (skeleton/sources/akagi/species/<species>.csv, compiled in).
std::vector<std::string> akagiSpeciesNames();
/// The table of a built-in species; throws InputError for an unknown name.
ObservationTable akagiSpeciesTable(const std::string& species);
/// Name and CSV text of every built-in table (generated from skeleton/sources/akagi/species by
/// CMake).
const std::vector<std::pair<std::string, std::string>>& akagiBuiltinTables();

}  // namespace nenrin
