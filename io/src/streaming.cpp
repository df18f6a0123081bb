#include "pdd/io/streaming.h"

#include <condition_variable>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <thread>

namespace pdd::io {
namespace {

volatile std::sig_atomic_t g_signal = 0;
int g_guards = 0;  // InterruptGuards alive (main thread only)
struct sigaction g_old_int, g_old_term;

extern "C" void record_signal(int sig) {
  if (g_signal) {  // the second one: the default action, now
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

void run_interruptible(const std::function<void()>& work, OrderedLines& lines, std::atomic<bool>& stop,
                       const std::string& command) {
  std::mutex m;
  std::condition_variable cv;
  bool finished = false;
  std::exception_ptr error;
  std::thread worker([&] {
    try {
      work();
    } catch (...) {
      error = std::current_exception();
    }
    std::lock_guard<std::mutex> lock(m);
    finished = true;
    cv.notify_all();
  });
  std::unique_lock<std::mutex> lock(m);
  while (!finished) {
    cv.wait_for(lock, std::chrono::milliseconds(20));
    if (const int sig = pending_signal(); sig && !finished) {
      stop = true;
      const std::size_t written = lines.flush_and_hold();  // no line is half-written now
      std::cerr << "\n" << command << ": interrupted (signal " << sig << "): " << written
                << " records written, each complete, in input order\n";
      std::cerr.flush();
      std::cout.flush();
      std::_Exit(interrupted_exit(sig));
    }
  }
  lock.unlock();
  worker.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace pdd::io
