// A one-line progress bar on stderr (samples/s and ETA), shown only on a terminal; off
// when stderr is redirected or --quiet is given, so logs stay clean.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>

namespace statmc::render {

class Progress {
public:
    Progress(std::uint64_t total_samples, bool enabled);
    /// Thread-safe; redraws at most a few times per second.
    void advance(std::uint64_t samples);
    /// Clears the line (when shown).
    void finish();
    /// Whether stderr is a terminal.
    static bool stderr_is_terminal();

private:
    void draw(bool final);
    std::uint64_t total_;
    bool enabled_;
    std::atomic<std::uint64_t> done_{0};
    std::mutex mutex_;
    std::chrono::steady_clock::time_point start_, last_draw_;
};

}  // namespace statmc::render
