#pragma once
/// Parsing of the CLI's compound arguments ("0.4x0.3m", "512x256", "x0,y0,z0,x1,y1,z1").
/// Errors are InputErrors located at the option, e.g. "command line: --size: ...".

#include <string>
#include <utility>
#include <vector>

namespace nenrin {

/// "WxH" or "WxHm": two positive sizes in metres.
std::pair<double, double> parseSizeMetres(const std::string& text, const std::string& option);
/// "WxH": two positive integers, each <= cap.
std::pair<int, int> parseResolution(const std::string& text, const std::string& option, int cap);
/// A comma-separated list of exactly `count` finite numbers.
std::vector<double> parseNumberList(const std::string& text, const std::string& option,
                                    size_t count);

}  // namespace nenrin
