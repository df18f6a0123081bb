// streaming.h — output that survives an interrupt: records written in input order as soon as
// each one and every one before it are computed, never a partial line, and SIGINT / SIGTERM
// turned into "finish the line being written, flush, exit 128 + signal".
//
// Written by hand (no library offers it): a TBB loop completes pairs out of order, the file
// must hold an input-order prefix at every moment, and a signal may arrive while a line is half
// in the stream's buffer. Hence:
//   - InterruptGuard: while alive, SIGINT and SIGTERM only record the signal (a second one
//     takes the default action at once: the user insists); the command polls
//     pending_signal() and stops at a line boundary. main() exits 128 + signal whenever one
//     was recorded, whatever the command returned.
//   - OrderedLines: done(k, line) from any thread; the lines 0..m-1 already done are written
//     in order, each whole, under one mutex; the stream is flushed at least every
//     `flush_seconds` (and by finish()), so that a killed run loses at most that much.
//   - run_interruptible(work, lines): runs `work` (a parallel loop) on a thread of its own while
//     the calling thread watches for a signal; on one it takes the lines' mutex (so no line is
//     half-written), flushes, says on standard error how many records were written and exits
//     128 + signal without waiting for pairs still being computed (an exact pair can take
//     seconds).
#pragma once

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstddef>
#include <functional>
#include <iostream>
#include <mutex>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace pdd::io {

class InterruptGuard {
 public:
  InterruptGuard();
  ~InterruptGuard();
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;
};

// 0, or the signal received while an InterruptGuard was alive.
int pending_signal();
// The exit status of a run stopped by signal `sig`: 130 for SIGINT, 143 for SIGTERM.
inline int interrupted_exit(int sig) { return 128 + sig; }

class OrderedLines {
 public:
  // `out`: the destination; `count`: how many lines this batch holds (indices 0..count-1).
  OrderedLines(std::ostream& out, double flush_seconds = 0.05) : out_(out), flush_seconds_(flush_seconds) {}

  // Starts a batch of `count` lines; the previous batch must be complete.
  void start(std::size_t count) {
    std::lock_guard<std::mutex> lock(mutex_);
    pending_.assign(count, std::nullopt);
    next_ = 0;
  }
  // Line k of the batch is computed (without its newline); writes the ready prefix. `note`, if
  // not empty, goes to standard error when the line is written (messages in input order too).
  void done(std::size_t k, std::string line, std::string note = {}) {
    std::lock_guard<std::mutex> lock(mutex_);
    pending_[k] = Line{std::move(line), std::move(note)};
    while (next_ < pending_.size() && pending_[next_]) {
      out_ << pending_[next_]->text << '\n';
      if (!pending_[next_]->note.empty()) std::cerr << pending_[next_]->note;
      pending_[next_].reset();
      ++next_, ++written_;
    }
    const auto now = std::chrono::steady_clock::now();
    if (std::chrono::duration<double>(now - last_flush_).count() >= flush_seconds_) {
      out_.flush();
      last_flush_ = now;
    }
  }
  // Flushes under the lock (no line is half-written then); returns the lines written so far.
  std::size_t flush() {
    std::lock_guard<std::mutex> lock(mutex_);
    out_.flush();
    return written_;
  }
  // Holds the lock for good: for the exit path of run_interruptible.
  std::size_t flush_and_hold() {
    mutex_.lock();
    out_.flush();
    return written_;
  }
  std::size_t written() {
    std::lock_guard<std::mutex> lock(mutex_);
    return written_;
  }

 private:
  struct Line {
    std::string text, note;
  };
  std::ostream& out_;
  double flush_seconds_;
  std::mutex mutex_;
  std::vector<std::optional<Line>> pending_;
  std::size_t next_ = 0, written_ = 0;
  std::chrono::steady_clock::time_point last_flush_ = std::chrono::steady_clock::now();
};

// Runs `work` while watching for a signal (see above). `stop` is set on a signal so that work
// starts no new pair. On a signal this function does not return: it says on standard error,
// as `command`, how many records were written and exits with interrupted_exit(sig). An
// exception thrown by `work` is rethrown here.
void run_interruptible(const std::function<void()>& work, OrderedLines& lines, std::atomic<bool>& stop,
                       const std::string& command);

}  // namespace pdd::io
