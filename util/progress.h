#pragma once
/// Progress of long work on stderr: a percentage line redrawn in place on a terminal, nothing
/// while running when stderr is not a terminal (logs stay clean). Thread-safe: workers call
/// advance() as they finish units of work.

#include <atomic>
#include <chrono>
#include <mutex>
#include <string>

namespace nenrin {

class ProgressReporter {
public:
    ProgressReporter(long long totalWork, std::string title, bool quiet = false);
    ~ProgressReporter();
    void advance(long long work = 1);
    /// Ends the line; called by the destructor if not called before.
    void done();
    double elapsedSeconds() const;

private:
    void draw(long long done);

    long long total_;
    std::string title_;
    bool enabled_;
    std::atomic<long long> done_{0};
    std::atomic<int> lastPercent_{-1};
    std::mutex drawMutex_;
    bool finished_ = false;
    std::chrono::steady_clock::time_point start_;
};

}  // namespace nenrin
