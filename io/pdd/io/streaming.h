// streaming.h — output that survives an interrupt: records written in input order as soon as
// each one and every one before it are computed, never a partial line, and SIGINT / SIGTERM
// turned into "finish the line being written, flush, say what was kept, exit 128 + signal".
//
// Written by hand (no library offers it): a TBB loop completes pairs out of order, the file
// must hold an input-order prefix at every moment, and a signal may arrive while a line is half
// in the stream's buffer. One mechanism for every command:
//   - InterruptGuard: while alive, SIGINT and SIGTERM only record the signal (a second one
//     removes the registered partial files (PartialFile) and takes the default action at once:
//     the user insists).
//   - run_watched(command, work): `pdd`'s main() runs the whole command as `work` on a thread of
//     its own while the calling thread watches for a signal. On one, it asks the innermost
//     alive InterruptScope what was kept: a scope with a `kept` function gets it called (which
//     finishes and flushes its output under its lock and describes what it holds); a scope
//     made with InterruptScope::Polled() means the command polls pending_signal() itself and
//     ends in its own time; with no scope, the command writes its results only at its end, so
//     nothing was kept. The watcher then says on standard error
//     "<command>: interrupted (signal N): <kept>", flushes and exits 128 + signal without
//     waiting for work still being computed (an exact pair can take seconds).
//   - OrderedLines: done(k, line) from any thread; the lines 0..m-1 already done are written
//     in order, each whole, under one mutex; the stream is flushed at least every
//     `flush_seconds` (and by finish()), so that a killed run loses at most that much.
//   - run_interruptible(work, lines): runs `work` (a parallel loop) with a scope whose `kept`
//     holds `lines` (no line is half-written), flushes it and counts the records written.
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

// While alive, `path` (a temporary file renamed over its final name when complete) is removed
// before the process ends on a signal: by the second signal (the one that stops at once) and
// by run_watched's exit. So an interrupted run leaves the old file, or the whole new one, and
// no temporary. An empty path registers nothing; at most 8 alive at a time (more are not
// registered). Thread-safe.
class PartialFile {
 public:
  explicit PartialFile(std::string path);
  ~PartialFile();
  PartialFile(const PartialFile&) = delete;
  PartialFile& operator=(const PartialFile&) = delete;

 private:
  int slot_ = -1;
  std::string path_;
};

// Who answers a signal under run_watched (see above); scopes nest, the innermost answers.
class InterruptScope {
 public:
  // `kept` is called on the watching thread once the signal is seen; it must leave the output
  // whole (finish the line, flush, hold the lock for good) and return what was kept, e.g.
  // "12 records written, each complete, in input order".
  explicit InterruptScope(std::function<std::string()> kept);
  // The command polls pending_signal() itself and ends in its own time.
  static InterruptScope Polled() { return InterruptScope(std::function<std::string()>()); }
  ~InterruptScope();
  InterruptScope(InterruptScope&&) = delete;

 private:
  InterruptScope* outer_;
  std::function<std::string()> kept_;
  friend int run_watched(const std::string&, const std::function<int()>&);
};

// Runs `work` (a whole command) as described above and returns its status; on a signal
// answered by the watcher it does not return. An exception thrown by `work` is rethrown here.
int run_watched(const std::string& command, const std::function<int()>& work);
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

// Runs `work` under an InterruptScope whose answer is "N records written, each complete, in
// `order`" (N: the lines written when the signal came; no line is half-written). `stop` is set
// on a signal so that work starts no new pair.
void run_interruptible(const std::function<void()>& work, OrderedLines& lines, std::atomic<bool>& stop,
                       const std::string& order = "input order");

}  // namespace pdd::io
