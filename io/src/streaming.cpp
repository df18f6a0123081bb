#include "pdd/io/streaming.h"

#include <atomic>
#include <condition_variable>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <iostream>
#include <thread>

#include <unistd.h>

namespace pdd::io {
namespace {

volatile std::sig_atomic_t g_signal = 0;
int g_guards = 0;  // InterruptGuards alive (main thread only)
struct sigaction g_old_int, g_old_term;

// PartialFile's slots: 0 free, 2 being filled, 1 holding a whole path (a path is copied into
// its slot before the slot is marked 1, so that the handler reads only whole paths). Lock-free
// atomics: safe to read in a signal handler.
constexpr int kSlots = 8;
constexpr std::size_t kPathBytes = 4096;
char g_partial[kSlots][kPathBytes];
std::atomic<int> g_partial_used[kSlots] = {};
static_assert(std::atomic<int>::is_always_lock_free);

void remove_partial_files() {
  for (int k = 0; k < kSlots; ++k)
    if (g_partial_used[k].load() == 1) ::unlink(g_partial[k]);  // async-signal-safe
}

std::mutex g_scope_mutex;
InterruptScope* g_scope = nullptr;  // the innermost alive scope

extern "C" void record_signal(int sig) {
  if (g_signal) {  // the second one: remove the temporary files, then the default action, now
    remove_partial_files();
    std::signal(sig, SIG_DFL);
    std::raise(sig);
    return;
  }
  g_signal = sig;
}

}  // namespace

InterruptGuard::InterruptGuard() {
  if (g_guards++) return;
  struct sigaction sa = {};
  sa.sa_handler = record_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;  // a write in progress completes
  sigaction(SIGINT, &sa, &g_old_int);
  sigaction(SIGTERM, &sa, &g_old_term);
}

InterruptGuard::~InterruptGuard() {
  if (--g_guards) return;
  sigaction(SIGINT, &g_old_int, nullptr);
  sigaction(SIGTERM, &g_old_term, nullptr);
}

int pending_signal() { return g_signal; }

PartialFile::PartialFile(std::string path) : path_(std::move(path)) {
  if (path_.empty() || path_.size() >= kPathBytes) return;
  for (int k = 0; k < kSlots; ++k) {
    int free = 0;
    if (g_partial_used[k].compare_exchange_strong(free, 2)) {
      std::memcpy(g_partial[k], path_.c_str(), path_.size() + 1);
      g_partial_used[k].store(1);
      slot_ = k;
      return;
    }
  }
}

PartialFile::~PartialFile() {
  if (slot_ >= 0) g_partial_used[slot_] = 0;
}

InterruptScope::InterruptScope(std::function<std::string()> kept) : kept_(std::move(kept)) {
  std::lock_guard<std::mutex> lock(g_scope_mutex);
  outer_ = g_scope;
  g_scope = this;
}

InterruptScope::~InterruptScope() {
  std::lock_guard<std::mutex> lock(g_scope_mutex);
  g_scope = outer_;
}

int run_watched(const std::string& command, const std::function<int()>& work) {
  InterruptGuard interrupts;
  std::mutex m;
  std::condition_variable cv;
  bool finished = false;
  int status = 0;
  std::exception_ptr error;
  std::thread worker([&] {
    try {
      status = work();
    } catch (...) {
      error = std::current_exception();
    }
    std::lock_guard<std::mutex> lock(m);
    finished = true;
    cv.notify_all();
  });
  std::unique_lock<std::mutex> lock(m);
  bool polled = false;  // the command answers this signal itself
  while (!finished) {
    cv.wait_for(lock, std::chrono::milliseconds(20));
    const int sig = pending_signal();
    if (!sig || finished || polled) continue;
    std::string kept = "nothing was kept (this command writes its results when it ends)";
    {
      std::lock_guard<std::mutex> scope_lock(g_scope_mutex);  // held to the exit: no scope ends
      if (g_scope && !g_scope->kept_) {
        polled = true;
        continue;
      }
      if (g_scope) kept = g_scope->kept_();
      std::cout.flush();
      std::cerr << "\n" << command << ": interrupted (signal " << sig << "): " << kept << "\n";
      std::cerr.flush();
      remove_partial_files();  // a file being written whole: the old one stays
      std::_Exit(interrupted_exit(sig));
    }
  }
  lock.unlock();
  worker.join();
  if (error) std::rethrow_exception(error);
  return status;
}

void run_interruptible(const std::function<void()>& work, OrderedLines& lines, std::atomic<bool>& stop,
                       const std::string& order) {
  InterruptScope scope([&] {
    stop = true;
    const std::size_t written = lines.flush_and_hold();  // no line is half-written now
    return std::to_string(written) + " records written, each complete, in " + order;
  });
  work();
}

}  // namespace pdd::io
