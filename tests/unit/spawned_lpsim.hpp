// The real `lpsim` binary started in the background, for tests that act on it while it runs (send it a
// signal): its pid, stdout and stderr in files of a directory, and a bounded wait for its end.
#pragma once

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "lpsim_cli.hpp"

namespace lpsim::test {

class SpawnedLpsim {
 public:
  /// Starts LPSIM_BINARY with `args` in `dir`, its stdout and stderr going to dir/stdout.txt and
  /// dir/stderr.txt (so stderr is not a terminal).
  SpawnedLpsim(const std::filesystem::path& dir, const std::vector<std::string>& args) : dir_(dir) {
    const std::string out = (dir / "stdout.txt").string(), err = (dir / "stderr.txt").string();
    std::vector<std::string> words{LPSIM_BINARY};
    words.insert(words.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (std::string& w : words) argv.push_back(w.data());
    argv.push_back(nullptr);
    pid_ = fork();
    if (pid_ == 0) {
      // The child: only async-signal-safe calls until exec.
      const int o = open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      const int e = open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      if (o < 0 || e < 0 || chdir(dir.c_str()) != 0 || dup2(o, 1) < 0 || dup2(e, 2) < 0) _exit(127);
      execv(argv[0], argv.data());
      _exit(127);
    }
  }
  /// Kills a child still running (a failed test must not leave it behind).
  ~SpawnedLpsim() {
    if (running()) {
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
  }
  SpawnedLpsim(const SpawnedLpsim&) = delete;
  SpawnedLpsim& operator=(const SpawnedLpsim&) = delete;

  bool started() const { return pid_ > 0; }
  bool running() const { return pid_ > 0 && status_ < 0; }
  void send(int signal) const { kill(pid_, signal); }

  /// Polls `ready` every 10 ms until it holds (true) or `seconds` pass or the process ended (false).
  bool wait_until(const std::function<bool()>& ready, double seconds) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (std::chrono::steady_clock::now() < until) {
      if (ready()) return true;
      if (!poll_exit()) return ready();
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return false;
  }

  /// Waits up to `seconds` for the process to end; its wait status, or -1 if it is still running.
  int wait_exit(double seconds) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (poll_exit() && std::chrono::steady_clock::now() < until)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    return status_;
  }

  std::string out() const { return read_file(dir_ / "stdout.txt"); }
  std::string err() const { return read_file(dir_ / "stderr.txt"); }

 private:
  // True while the process runs; records its status once it ended.
  bool poll_exit() {
    if (!running()) return false;
    int status = 0;
    if (waitpid(pid_, &status, WNOHANG) == pid_) status_ = status;
    return running();
  }

  std::filesystem::path dir_;
  pid_t pid_ = -1;
  int status_ = -1;
};

}  // namespace lpsim::test
