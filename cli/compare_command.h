#pragma once
/// `nenrin compare A B [--diff D.exr] [--flip] [--flip-map F.exr]`: how far image B is from A,
/// as numbers (RMSE, PSNR, absolute errors) and as a viewer sees it (FLIP, docs/compare.md).

#include <CLI/CLI.hpp>

namespace nenrin {

void addCompareCommand(CLI::App& app);

}  // namespace nenrin
