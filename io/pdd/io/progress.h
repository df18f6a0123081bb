// progress.h — progress and time-left estimate on stderr for long batches.
//
// Silent for batches that finish within `quiet_seconds`; after that, one line at most every
// `interval_seconds`: "pdd solve: 120/400 pairs (30%), 12 s elapsed, about 28 s left".
// Thread-safe: tick() may be called from worker threads.
#pragma once

#include <atomic>
#include <chrono>
#include <cstddef>
#include <limits>
#include <mutex>
#include <string>

namespace pdd::io {

class Progress {
 public:
  // quiet_seconds for a Progress that never prints (e.g. `--quiet`).
  static constexpr double kNever = std::numeric_limits<double>::infinity();

  Progress(std::string what, std::size_t total, double quiet_seconds = 2.0,
           double interval_seconds = 2.0);
  void tick(std::size_t n = 1);  // n more items done
  void finish();  // final line if anything was printed

 private:
  using Clock = std::chrono::steady_clock;
  void print(std::size_t done, double elapsed);
  std::string what_;
  std::size_t total_;
  double quiet_, interval_;
  Clock::time_point start_;
  std::atomic<std::size_t> done_{0};
  std::mutex mutex_;
  double last_print_ = -1;
};

}  // namespace pdd::io
