// replay_main.cpp — a main() for the fuzz targets without libFuzzer: runs
// LLVMFuzzerTestOneInput on every file named on the command line (directories: every regular
// file in them, sorted), so the corpus replays under any compiler's ASan/UBSan build
// (scripts/sanitize.sh) and in CTest.
//
// Each file runs in a child process (fork), so one crash does not hide the next: every file
// is reported as "ok" or "FAILED (signal/exit status)", and the exit status is 1 when any
// failed. --no-fork runs them in this process (for a debugger).
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);
extern "C" __attribute__((weak)) int LLVMFuzzerInitialize(int* argc, char*** argv);

namespace fs = std::filesystem;

static int run_one(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    std::fprintf(stderr, "replay: cannot read %s\n", path.c_str());
    return 1;
  }
  const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::vector<uint8_t> data(bytes.begin(), bytes.end());  // own buffer: ASan sees its exact size
  LLVMFuzzerTestOneInput(data.data(), data.size());
  return 0;
}

int main(int argc, char** argv) {
  if (LLVMFuzzerInitialize) LLVMFuzzerInitialize(&argc, &argv);
  bool fork_each = true;
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--no-fork") { fork_each = false; continue; }
    if (fs::is_directory(arg)) {
      std::vector<std::string> in_dir;
      for (const auto& e : fs::directory_iterator(arg))
        if (e.is_regular_file()) in_dir.push_back(e.path().string());
      std::sort(in_dir.begin(), in_dir.end());
      files.insert(files.end(), in_dir.begin(), in_dir.end());
    } else {
      files.push_back(arg);
    }
  }
  if (files.empty()) {
    std::fprintf(stderr, "usage: %s [--no-fork] FILE_OR_DIR...\n", argv[0]);
    return 2;
  }
  std::vector<std::string> failed;
  for (const auto& f : files) {
    std::fflush(stdout);
    if (!fork_each) {
      run_one(f);
      std::printf("ok      %s\n", f.c_str());
      continue;
    }
    const pid_t pid = fork();
    if (pid < 0) { std::perror("fork"); return 2; }
    if (pid == 0) _exit(run_one(f));
    int status = 0;
    waitpid(pid, &status, 0);
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0) {
      std::printf("ok      %s\n", f.c_str());
    } else {
      failed.push_back(f);
      if (WIFSIGNALED(status))
        std::printf("FAILED  %s (signal %d: %s)\n", f.c_str(), WTERMSIG(status), strsignal(WTERMSIG(status)));
      else
        std::printf("FAILED  %s (exit status %d)\n", f.c_str(), WEXITSTATUS(status));
    }
  }
  std::printf("replay: %zu files, %zu failed\n", files.size(), failed.size());
  for (const auto& f : failed) std::printf("  failed: %s\n", f.c_str());
  return failed.empty() ? 0 : 1;
}
