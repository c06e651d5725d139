#include "skeleton/sources/akagi/akagi_model.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "util/input_error.h"
#include "util/random_draws.h"

namespace nenrin {

namespace {

// Priors (docs/tree-akagi.md). Weights act on standardised covariates, so one scale fits all.
constexpr double kInterceptPriorSd = 10;
constexpr double kWeightPriorSd = 2;
constexpr double kRatePriorShape = 0.01, kRatePriorRate = 0.01;    // beta (of y / mean)
constexpr double kResidualPrecShape = 1, kResidualPrecRate = 0.1;  // 1 / sigma^2
constexpr double kEffectPrecShape = 1, kEffectPrecRate = 0.005;    // 1 / sigma_ID^2 ...
constexpr double kTargetAcceptance = 0.44;  // optimal for one-dimensional random walks
constexpr int kAdaptBatch = 50;

bool isNormalFamily(int i) { return i == 6 || i == 7 || i == 9 || i == 10 || i == 11; }
bool isRegressed(int i) { return i <= 9; }

// One parameter's sub-model and its sampler state.
class SubModel {
public:
    SubModel(const ObservationTable& table, int param, const std::vector<int>& covariates,
             AkagiParamFit& out)
        : out_(out) {
        family_ = isNormalFamily(param) ? AkagiFamily::Normal : AkagiFamily::Gamma;
        regressed_ = isRegressed(param);
        hasErr_ = regressed_ && family_ == AkagiFamily::Gamma;
        R_ = static_cast<int>(table.rows.size());
        T_ = static_cast<int>(table.treeIds.size());
        // Standardise the covariates; a constant one carries no information and is dropped.
        std::vector<int> used;
        for (int j : covariates) {
            double m = 0, s = 0;
            for (const AkagiParams& row : table.rows) m += row[j];
            m /= R_;
            for (const AkagiParams& row : table.rows) s += (row[j] - m) * (row[j] - m);
            s = std::sqrt(s / std::max(R_ - 1, 1));
            if (s <= 1e-12 * std::max(1.0, std::abs(m))) continue;
            used.push_back(j);
            out.xMean.push_back(m);
            out.xSd.push_back(s);
        }
        out.covariates = used;
        out.family = family_;
        out.individualEffect = regressed_;
        out.observationError = hasErr_;
        K_ = 1 + static_cast<int>(used.size());
        double ym = 0, ys = 0;
        for (const AkagiParams& row : table.rows) ym += row[param];
        ym /= R_;
        for (const AkagiParams& row : table.rows) ys += (row[param] - ym) * (row[param] - ym);
        ys = std::sqrt(ys / std::max(R_ - 1, 1));
        if (family_ == AkagiFamily::Gamma) {
            out.yScale = ym;
            out.yMean = 0;
        } else {
            out.yMean = ym;
            out.yScale = std::max(ys, 1e-6 * std::max(1.0, std::abs(ym)));
        }
        constant_ = ys <= 1e-12 * std::max(1.0, std::abs(ym));
        constantValue_ = ym;
        x_.resize(static_cast<size_t>(R_) * K_);
        y_.resize(R_);
        logY_.resize(R_);
        tree_ = table.rowTree;
        rowsOfTree_.resize(T_);
        for (int r = 0; r < R_; ++r) {
            const AkagiParams& row = table.rows[r];
            y_[r] = (row[param] - out.yMean) / out.yScale;
            logY_[r] = family_ == AkagiFamily::Gamma ? std::log(y_[r]) : 0.0;
            x_[r * K_] = 1;
            for (int k = 1; k < K_; ++k)
                x_[r * K_ + k] = (row[used[k - 1]] - out.xMean[k - 1]) / out.xSd[k - 1];
            rowsOfTree_[tree_[r]].push_back(r);
        }
        // Start at moment estimates.
        w_.assign(K_, 0.0);
        if (family_ == AkagiFamily::Gamma) {
            double var = 0;
            for (double v : y_) var += (v - 1) * (v - 1);
            var /= std::max(R_ - 1, 1);
            double shape = std::clamp(1 / std::max(var, 1e-6), 0.5, 1e4);
            w_[0] = std::log(shape);
            dispersion_ = shape;  // beta of y / mean
        } else {
            dispersion_ = 1;  // residual precision
        }
        id_.assign(T_, 0.0);
        err_.assign(R_, 0.0);
        stepW_.assign(K_, 0.1);
        counterW_.assign(K_, {});
        eta_.resize(R_);
        ll_.resize(R_);
        recomputeAll();
    }

    /// A column without spread (e.g. BranchNum 3 in every row) is not sampled: its draws
    /// return the constant.
    bool constant() const { return constant_; }
    double constantValue() const { return constantValue_; }

    void sweep(SplitMix& rng) {
        if (constant_) return;
        for (int k = 0; k < K_; ++k) moveWeight(k, rng);
        if (family_ == AkagiFamily::Gamma) {
            moveRidge(rng);
            double shape = kRatePriorShape, rate = kRatePriorRate;
            for (int r = 0; r < R_; ++r) shape += std::exp(eta_[r]), rate += y_[r];
            dispersion_ = drawGamma(rng, shape, 1 / rate);
        } else {
            double ss = 0;
            for (int r = 0; r < R_; ++r) ss += (y_[r] - eta_[r]) * (y_[r] - eta_[r]);
            dispersion_ =
                drawGamma(rng, kResidualPrecShape + 0.5 * R_, 1 / (kResidualPrecRate + 0.5 * ss));
        }
        recomputeLogLik();
        if (regressed_) {
            for (int t = 0; t < T_; ++t) moveEffect(t, rng);
            tauId_ = drawPrecision(id_, rng);
        }
        if (hasErr_) {
            for (int r = 0; r < R_; ++r) moveError(r, rng);
            tauErr_ = drawPrecision(err_, rng);
        }
    }

    void adapt() {
        auto tune = [](double& step, Counter& c) {
            if (c.tried == 0) return;
            double rate = double(c.accepted) / c.tried;
            step = std::clamp(step * std::exp(2 * (rate - kTargetAcceptance)), 1e-5, 10.0);
            c = {};
        };
        for (int k = 0; k < K_; ++k) tune(stepW_[k], counterW_[k]);
        tune(stepRidge_, counterRidge_);
        tune(stepId_, counterId_);
        tune(stepErr_, counterErr_);
    }

    void startSampling() {
        counterW_.assign(K_, {});
        counterRidge_ = counterId_ = counterErr_ = {};
    }

    void record() {
        std::vector<double> d = w_;
        d.push_back(family_ == AkagiFamily::Gamma ? dispersion_ : 1 / std::sqrt(dispersion_));
        d.push_back(regressed_ ? 1 / std::sqrt(tauId_) : 0.0);
        d.push_back(hasErr_ ? 1 / std::sqrt(tauErr_) : 0.0);
        out_.draws.push_back(std::move(d));
    }

    void summarise() {
        AkagiParamFit& o = out_;
        size_t n = o.draws.size();
        std::vector<std::vector<double>> raw(n);  // weights (raw), dispersion (raw)
        for (size_t s = 0; s < n; ++s) {
            const std::vector<double>& d = o.draws[s];
            std::vector<double> w(K_);
            double intercept = d[0];
            for (int k = 1; k < K_; ++k) {
                w[k] = d[k] / o.xSd[k - 1];
                intercept -= d[k] * o.xMean[k - 1] / o.xSd[k - 1];
            }
            w[0] = intercept;
            if (family_ == AkagiFamily::Normal)
                for (int k = 0; k < K_; ++k) w[k] = (k == 0 ? o.yMean : 0.0) + o.yScale * w[k];
            double disp = family_ == AkagiFamily::Gamma ? d[K_] / o.yScale : d[K_] * o.yScale;
            w.push_back(disp);
            w.push_back(d[K_ + 1] * (family_ == AkagiFamily::Normal ? o.yScale : 1.0));
            w.push_back(d[K_ + 2]);
            raw[s] = std::move(w);
        }
        auto meanSd = [&](size_t idx) {
            double m = 0, m2 = 0;
            for (const auto& v : raw) m += v[idx], m2 += v[idx] * v[idx];
            m /= n;
            return std::pair<double, double>{m, std::sqrt(std::max(m2 / n - m * m, 0.0))};
        };
        for (int k = 0; k < K_; ++k) {
            auto [m, s] = meanSd(k);
            o.weightMean.push_back(m);
            o.weightSd.push_back(s);
        }
        auto [dm, ds] = meanSd(K_);
        if (family_ == AkagiFamily::Gamma)
            o.rateMean = dm, o.rateSd = ds;
        else
            o.sigmaMean = dm, o.sigmaSd = ds;
        o.sigmaIdMean = meanSd(K_ + 1).first;
        o.sigmaErrMean = meanSd(K_ + 2).first;
        long accepted = 0, tried = 0;
        for (const Counter& c : counterW_) accepted += c.accepted, tried += c.tried;
        for (const Counter* c : {&counterRidge_, &counterId_, &counterErr_})
            accepted += c->accepted, tried += c->tried;
        o.acceptance = tried > 0 ? double(accepted) / tried : 0;
    }

private:
    bool constant_ = false;
    double constantValue_ = 0;
    struct Counter {
        long accepted = 0, tried = 0;
    };

    double rowLogLik(int r, double eta, double dispersion) const {
        if (family_ == AkagiFamily::Gamma) {
            double a = std::exp(std::min(eta, 30.0));
            return a * std::log(dispersion) - std::lgamma(a) + (a - 1) * logY_[r] -
                   dispersion * y_[r];
        }
        double e = y_[r] - eta;
        return -0.5 * dispersion * e * e;
    }
    void recomputeAll() {
        for (int r = 0; r < R_; ++r) {
            double eta = id_[tree_[r]] + err_[r];
            for (int k = 0; k < K_; ++k) eta += w_[k] * x_[r * K_ + k];
            eta_[r] = eta;
        }
        recomputeLogLik();
    }
    void recomputeLogLik() {
        for (int r = 0; r < R_; ++r) ll_[r] = rowLogLik(r, eta_[r], dispersion_);
    }
    double weightPrior(int k, double w) const {
        double sd = k == 0 ? kInterceptPriorSd : kWeightPriorSd;
        return -0.5 * w * w / (sd * sd);
    }
    bool accept(double logRatio, SplitMix& rng, Counter& c) {
        ++c.tried;
        bool ok = logRatio >= 0 || std::log(1 - rng.uniform()) < logRatio;
        if (ok) ++c.accepted;
        return ok;
    }
    void moveWeight(int k, SplitMix& rng) {
        double delta = stepW_[k] * drawNormal(rng);
        double diff = weightPrior(k, w_[k] + delta) - weightPrior(k, w_[k]);
        newLl_.resize(R_);
        for (int r = 0; r < R_; ++r) {
            newLl_[r] = rowLogLik(r, eta_[r] + delta * x_[r * K_ + k], dispersion_);
            diff += newLl_[r] - ll_[r];
        }
        if (!accept(diff, rng, counterW_[k])) return;
        w_[k] += delta;
        for (int r = 0; r < R_; ++r) eta_[r] += delta * x_[r * K_ + k], ll_[r] = newLl_[r];
    }
    // Shape and rate move together (mean kept): the posterior is a long ridge along them.
    void moveRidge(SplitMix& rng) {
        double delta = stepRidge_ * drawNormal(rng);
        double beta = dispersion_ * std::exp(delta);
        double diff = weightPrior(0, w_[0] + delta) - weightPrior(0, w_[0]) +
                      kRatePriorShape * delta - kRatePriorRate * (beta - dispersion_);
        newLl_.resize(R_);
        for (int r = 0; r < R_; ++r) {
            newLl_[r] = rowLogLik(r, eta_[r] + delta, beta);
            diff += newLl_[r] - ll_[r];
        }
        if (!accept(diff, rng, counterRidge_)) return;
        w_[0] += delta;
        dispersion_ = beta;
        for (int r = 0; r < R_; ++r) eta_[r] += delta, ll_[r] = newLl_[r];
    }
    void moveEffect(int t, SplitMix& rng) {
        double delta = stepId_ * drawNormal(rng);
        double v = id_[t];
        double diff = -0.5 * tauId_ * ((v + delta) * (v + delta) - v * v);
        for (int r : rowsOfTree_[t]) diff += rowLogLik(r, eta_[r] + delta, dispersion_) - ll_[r];
        if (!accept(diff, rng, counterId_)) return;
        id_[t] += delta;
        for (int r : rowsOfTree_[t]) eta_[r] += delta, ll_[r] = rowLogLik(r, eta_[r], dispersion_);
    }
    void moveError(int r, SplitMix& rng) {
        double delta = stepErr_ * drawNormal(rng);
        double v = err_[r];
        double nl = rowLogLik(r, eta_[r] + delta, dispersion_);
        double diff = -0.5 * tauErr_ * ((v + delta) * (v + delta) - v * v) + nl - ll_[r];
        if (!accept(diff, rng, counterErr_)) return;
        err_[r] += delta;
        eta_[r] += delta;
        ll_[r] = nl;
    }
    double drawPrecision(const std::vector<double>& effects, SplitMix& rng) {
        double ss = 0;
        for (double e : effects) ss += e * e;
        return drawGamma(rng, kEffectPrecShape + 0.5 * effects.size(),
                         1 / (kEffectPrecRate + 0.5 * ss));
    }

    AkagiParamFit& out_;
    AkagiFamily family_;
    bool regressed_ = false, hasErr_ = false;
    int R_ = 0, T_ = 0, K_ = 1;
    std::vector<double> x_, y_, logY_, eta_, ll_, newLl_;
    std::vector<int> tree_;
    std::vector<std::vector<int>> rowsOfTree_;
    std::vector<double> w_, id_, err_;
    double dispersion_ = 1, tauId_ = 20, tauErr_ = 20;
    std::vector<double> stepW_;
    double stepRidge_ = 0.1, stepId_ = 0.1, stepErr_ = 0.1;
    std::vector<Counter> counterW_;
    Counter counterRidge_, counterId_, counterErr_;
};

double predictorOf(const AkagiParamFit& f, const std::vector<double>& draw,
                   const AkagiParams& current) {
    double eta = draw[0];
    for (size_t k = 0; k < f.covariates.size(); ++k)
        eta += draw[k + 1] * (current[f.covariates[k]] - f.xMean[k]) / f.xSd[k];
    return eta;
}

bool allInRange(const AkagiParams& p) {
    for (int i = 0; i < kAkagiParamCount; ++i)
        if (!akagiParamProblem(i, p[i]).empty()) return false;
    return true;
}

}  // namespace

std::vector<int> akagiCovariates(int i, bool paperCovariates) {
    if (!isRegressed(i)) return {};
    if (paperCovariates) {
        std::vector<int> all;
        for (int j = 0; j <= 9; ++j)
            if (j != i) all.push_back(j);
        return all;
    }
    // Botanical pairs: allometry (height - radius), leaf number - size trade-off, the branching
    // budget (number of children - shares), each angle with the share of its own axis, the
    // rotation with the number of children around the axis.
    static const std::vector<int> sparse[10] = {{1},    {0}, {3}, {2},    {5, 8},
                                                {8, 4}, {5}, {4}, {5, 4}, {8}};
    return sparse[i];
}

AkagiFit fitAkagiModel(const ObservationTable& table, const McmcOptions& options) {
    if (options.burnIn < 0 || options.burnIn > 10000000)
        throw InputError("MCMC options", "burnIn", "expected 0 .. 1e7 sweeps");
    if (options.samples < 1 || options.samples > 1000000)
        throw InputError("MCMC options", "samples", "expected 1 .. 1e6 samples");
    if (options.thin < 1 || options.thin > 1000)
        throw InputError("MCMC options", "thin", "expected 1 .. 1000");
    if (table.rows.size() < 4 || table.treeIds.size() < 2)
        throw InputError(table.source, "", "the model needs >= 4 rows from >= 2 trees");
    AkagiFit fit;
    fit.source = table.source;
    for (int i = 0; i < kAkagiParamCount; ++i) {
        double m = 0;
        for (const AkagiParams& row : table.rows) m += row[i];
        fit.initialGuess[i] = m / table.rows.size();
    }
    // The sub-models are independent (the observed parameters are data), so they run in
    // parallel; each has its own random stream, so the result does not depend on threads.
    tbb::parallel_for(0, kAkagiParamCount, [&](int i) {
        AkagiParamFit& out = fit.params[i];
        SubModel model(table, i, akagiCovariates(i, options.paperCovariates), out);
        out.constant = model.constant();
        out.constantValue = model.constantValue();
        // Each parameter has its own stream: the fit of one does not depend on the others.
        SplitMix rng(hashCombine(options.seed, 0x5eed0000ull + i));
        for (int s = 0; s < options.burnIn; ++s) {
            model.sweep(rng);
            if ((s + 1) % kAdaptBatch == 0) model.adapt();
        }
        model.startSampling();
        for (int s = 0; s < options.samples; ++s) {
            for (int t = 0; t < options.thin; ++t) model.sweep(rng);
            model.record();
        }
        model.summarise();
    });
    return fit;
}

AkagiParams drawAkagiParams(const AkagiFit& fit, SplitMix& rng) {
    const size_t n = fit.params[0].draws.size();
    for (int attempt = 0; attempt < 50; ++attempt) {
        size_t s = std::min(static_cast<size_t>(rng.uniform() * n), n - 1);
        AkagiParams current = fit.initialGuess;
        std::array<double, kAkagiParamCount> individual{};
        for (int i = 0; i < kAkagiParamCount; ++i) {
            const AkagiParamFit& f = fit.params[i];
            const std::vector<double>& d = f.draws[s];
            size_t K = f.covariates.size() + 1;
            individual[i] = f.individualEffect ? d[K + 1] * drawNormal(rng) : 0.0;
        }
        // Paper 3.3: iterate the conditionals from the initial guess.
        for (int sweep = 0; sweep < 60; ++sweep) {
            for (int i = 0; i < kAkagiParamCount; ++i) {
                const AkagiParamFit& f = fit.params[i];
                if (f.constant) {
                    current[i] = f.constantValue;
                    continue;
                }
                const std::vector<double>& d = f.draws[s];
                size_t K = f.covariates.size() + 1;
                double eta = predictorOf(f, d, current) + individual[i];
                if (f.family == AkagiFamily::Gamma) {
                    if (f.observationError) eta += d[K + 2] * drawNormal(rng);
                    double shape = std::exp(std::clamp(eta, -20.0, 30.0));
                    current[i] = drawGamma(rng, shape, 1 / d[K]) * f.yScale;
                } else {
                    current[i] = f.yMean + f.yScale * (eta + d[K] * drawNormal(rng));
                }
            }
            if (sweep >= 19 && allInRange(current)) return current;
        }
    }
    throw InputError(fit.source, "", "no parameter set within the allowed ranges in 50 draws");
}

std::vector<std::string> akagiSpeciesNames() {
    std::vector<std::string> names;
    for (const auto& [name, text] : akagiBuiltinTables()) names.push_back(name);
    return names;
}

ObservationTable akagiSpeciesTable(const std::string& species) {
    for (const auto& [name, text] : akagiBuiltinTables())
        if (name == species)
            return parseAkagiObservations(text, "skeleton/sources/akagi/species/" + name + ".csv");
    std::string list;
    for (const std::string& n : akagiSpeciesNames()) list += (list.empty() ? "" : ", ") + n;
    throw InputError("akagi", "preset",
                     "unknown species '" + species + "' (expected one of " + list +
                         ", or the path of an observation table)");
}

SkeletonFileInfo akagiSkeletonInfo(const AkagiTree& tree, const std::string& speciesOrTablePath,
                                   uint64_t seed) {
    SkeletonFileInfo info;
    info.description = "Akagi & Kitajima 13-parameter tree (" + speciesOrTablePath + ")";
    info.source = {{"model", "akagi"},
                   {"species", speciesOrTablePath},
                   {"seed", seed},
                   {"years", tree.years},
                   {"attempts", tree.attempts},
                   {"parameters", akagiParamsToJson(tree.params)}};
    return info;
}

AkagiTree growAkagiSpecies(const std::string& speciesOrTablePath, uint64_t seed, double years,
                           const AkagiGrowOptions& options) {
    if (!(std::isfinite(years) && years > 0))
        throw InputError("Akagi tree", "years", "expected a number > 0");
    if (options.maxAttempts < 1)
        throw InputError("Akagi tree", "maxAttempts", "expected at least 1");
    bool builtin = false;
    for (const std::string& n : akagiSpeciesNames()) builtin |= n == speciesOrTablePath;
    std::error_code ec;  // a name the system refuses is not a file
    bool looksLikePath = speciesOrTablePath.find('/') != std::string::npos ||
                         speciesOrTablePath.find('.') != std::string::npos ||
                         std::filesystem::exists(speciesOrTablePath, ec);
    ObservationTable table = builtin || !looksLikePath ? akagiSpeciesTable(speciesOrTablePath)
                                                       : loadAkagiObservations(speciesOrTablePath);
    AkagiFit fit = fitAkagiModel(table, options.mcmc);
    SplitMix rng(hashCombine(seed, 0xd4a3ull));
    std::string why;
    for (int attempt = 0; attempt < options.maxAttempts; ++attempt) {
        AkagiParams p = drawAkagiParams(fit, rng);
        AkagiTree tree = generateAkagiTree(p, hashCombine(seed, attempt), years, options.generate);
        if (isPlausible(tree, &why)) {
            tree.attempts = attempt + 1;
            return tree;
        }
    }
    throw InputError(table.source, "",
                     "no plausible tree in " + std::to_string(options.maxAttempts) +
                         " draws (last rejection: " + why + ")");
}

}  // namespace nenrin
