#include "util/progress.h"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdio>

namespace nenrin {

ProgressReporter::ProgressReporter(long long totalWork, std::string title, bool quiet)
    : total_(totalWork > 0 ? totalWork : 1),
      title_(std::move(title)),
      enabled_(!quiet && isatty(STDERR_FILENO)),
      start_(std::chrono::steady_clock::now()) {}

ProgressReporter::~ProgressReporter() { done(); }

double ProgressReporter::elapsedSeconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void ProgressReporter::advance(long long work) {
    long long d = done_.fetch_add(work) + work;
    if (!enabled_) return;
    int percent = static_cast<int>(100 * d / total_);
    int last = lastPercent_.load();
    if (percent > last && lastPercent_.compare_exchange_strong(last, percent)) draw(d);
}

void ProgressReporter::draw(long long d) {
    std::lock_guard lock(drawMutex_);
    if (finished_) return;
    int percent = static_cast<int>(100 * d / total_);
    int bar = percent / 4;
    std::fprintf(stderr, "\r%s [%s%s] %3d%% %.1fs", title_.c_str(), std::string(bar, '=').c_str(),
                 std::string(25 - bar, ' ').c_str(), percent, elapsedSeconds());
    std::fflush(stderr);
}

void ProgressReporter::done() {
    std::lock_guard lock(drawMutex_);
    if (finished_) return;
    finished_ = true;
    if (enabled_) {
        std::fprintf(stderr, "\r%s [=========================] 100%% %.1fs\n", title_.c_str(),
                     elapsedSeconds());
        std::fflush(stderr);
    }
}

}  // namespace nenrin
