#include "pdd/io/progress.h"

#include <cstdio>

namespace pdd::io {

Progress::Progress(std::string what, std::size_t total, double quiet_seconds,
                   double interval_seconds)
    : what_(std::move(what)), total_(total), quiet_(quiet_seconds),
      interval_(interval_seconds), start_(Clock::now()) {}

void Progress::tick(std::size_t n) {
  const std::size_t done = done_ += n;
  const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
  if (elapsed < quiet_) return;
  std::lock_guard<std::mutex> lock(mutex_);
  if (last_print_ >= 0 && elapsed - last_print_ < interval_) return;
  last_print_ = elapsed;
  print(done, elapsed);
}

void Progress::finish() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (last_print_ < 0) return;
  const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
  std::fprintf(stderr, "%s: %zu/%zu done in %.1f s\n", what_.c_str(), done_.load(), total_, elapsed);
}

void Progress::print(std::size_t done, double elapsed) {
  const double left = done ? elapsed * double(total_ - done) / double(done) : 0.0;
  std::fprintf(stderr, "%s: %zu/%zu (%.0f%%), %.0f s elapsed, about %.0f s left\n", what_.c_str(),
               done, total_, 100.0 * double(done) / double(total_ ? total_ : 1), elapsed, left);
}

}  // namespace pdd::io
