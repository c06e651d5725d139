#include "util/input_error.h"

#include <algorithm>

namespace nenrin {

static std::string compose(const std::string& file, const std::string& where,
                           const std::string& message) {
    std::string s = file.empty() ? std::string("<input>") : file;
    if (!where.empty()) s += ": " + where;
    return s + ": " + message;
}

InputError::InputError(std::string file, std::string where, std::string message)
    : std::runtime_error(compose(file, where, message)),
      file_(std::move(file)),
      where_(std::move(where)),
      message_(std::move(message)) {}

std::string oneLine(std::string s) {
    std::replace(s.begin(), s.end(), '\n', ' ');
    s.erase(std::unique(s.begin(), s.end(), [](char a, char b) { return a == ' ' && b == ' '; }),
            s.end());
    while (!s.empty() && s.back() == ' ') s.pop_back();
    return s;
}

}  // namespace nenrin
