#include "statmc/render/progress.h"

#include <cstdio>

#include <unistd.h>

namespace statmc::render {

Progress::Progress(std::uint64_t total_samples, bool enabled)
    : total_(total_samples), enabled_(enabled), start_(std::chrono::steady_clock::now()),
      last_draw_(start_)
{
}

bool Progress::stderr_is_terminal() { return ::isatty(STDERR_FILENO) == 1; }

void Progress::advance(std::uint64_t samples)
{
    done_ += samples;
    if (!enabled_)
        return;
    std::unique_lock<std::mutex> lock(mutex_, std::try_to_lock);
    if (!lock.owns_lock())
        return;
    const auto now = std::chrono::steady_clock::now();
    if (now - last_draw_ < std::chrono::milliseconds(200))
        return;
    last_draw_ = now;
    draw(false);
}

void Progress::draw(bool final)
{
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const std::uint64_t done = done_.load();
    const double frac = total_ ? double(done) / double(total_) : 1.0;
    const double rate = elapsed > 0 ? double(done) / elapsed : 0.0;
    const double eta = rate > 0 ? double(total_ - std::min(done, total_)) / rate : 0.0;
    constexpr int kWidth = 30;
    char bar[kWidth + 1];
    const int filled = int(frac * kWidth);
    for (int i = 0; i < kWidth; ++i)
        bar[i] = i < filled ? '#' : '.';
    bar[kWidth] = 0;
    std::fprintf(stderr, "\r[%s] %5.1f%%  %.2f Msamples/s  ETA %.0fs   %s", bar, 100 * frac,
                 rate * 1e-6, eta, final ? "\n" : "");
    std::fflush(stderr);
}

void Progress::finish()
{
    if (!enabled_)
        return;
    std::lock_guard<std::mutex> lock(mutex_);
    draw(false);
    std::fprintf(stderr, "\r%80s\r", "");
    std::fflush(stderr);
}

}  // namespace statmc::render
