#pragma once
/// Importer for quantitative structure models (QSMs): the cylinder lists that TreeQSM's
/// save_model_text writes (tab-separated, no header) and the CSV variants with a header row
/// (qsm2r, rTwig, spreadsheets). Each QSM branch becomes a skeleton chain through its
/// cylinders; a branch starts on its parent cylinder's axis. QSMs have no time, so birth
/// times come from path length over an elongation speed and the ring width from the stem's
/// base radius over the tree's age. Accepted columns: docs/trees.md ("TreeQSM").

#include <string>

#include "skeleton/skeleton.h"

namespace nenrin {

struct QsmOptions {
    double elongationSpeed = 0.5;  ///< m/year along every axis
    double diebackExponent = 1;
};

struct QsmTree {
    Skeleton skeleton;
    size_t cylinders = 0, branches = 0;
    double age = 0;        ///< years: the last tip's birth time, rounded up
    double ringWidth = 0;  ///< m/year: stem base radius / age
    /// For every chain, the QSM branch id it came from (chain 0 = the stem).
    std::vector<long long> branchIdOfChain;
};

QsmTree importQsm(const std::string& path, const QsmOptions& options = {});
/// Same, from the file's text; `name` stands for the file in messages.
QsmTree parseQsm(const std::string& text, const std::string& name, const QsmOptions& options = {});

}  // namespace nenrin
