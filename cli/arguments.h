#pragma once
/// Parsing of the CLI's compound arguments ("0.4x0.3m", "512x256", "x0,y0,z0,x1,y1,z1").
/// Errors are InputErrors located at the option, e.g. "command line: --size: ...".

#include <CLI/CLI.hpp>
#include <string>
#include <utility>
#include <vector>

#include "util/limits.h"

namespace nenrin {

/// A CLI11 check for a number option: finite (no nan, inf or overflow to inf) and within
/// [lo, hi], with a short message ("expected a finite number in [-10000, 10000], found 1e+308").
CLI::Validator finiteRange(double lo, double hi);

/// --max-memory SIZE ("8G", "512M"): the most memory the command's grids and frames may take
/// (util/memory_budget.h); by default 80 % of the machine's.
void addMaxMemoryOption(CLI::App* command);

/// "WxH" or "WxHm": two positive sizes in metres.
std::pair<double, double> parseSizeMetres(const std::string& text, const std::string& option);
/// "WxH": two positive integers, each <= cap.
std::pair<int, int> parseResolution(const std::string& text, const std::string& option, int cap);
/// A comma-separated list of exactly `count` finite numbers.
std::vector<double> parseNumberList(const std::string& text, const std::string& option,
                                    size_t count);

}  // namespace nenrin
