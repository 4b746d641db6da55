#include "sumo_bridge/sumo_start.hpp"

#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <thread>

namespace lpsim {

namespace {

bool executable(const std::string& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(path.c_str(), X_OK) == 0;
}

// A port no one listens on now, from the kernel (SUMO binds it a moment later: another process taking it in
// between makes SUMO fail to start, reported as such).
int free_port() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  if (fd < 0) throw SumoError("cannot open a socket to find a free port for SUMO");
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  a.sin_port = 0;
  socklen_t len = sizeof a;
  const bool ok = ::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0 &&
                  ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len) == 0;
  ::close(fd);
  if (!ok) throw SumoError("cannot find a free local port for SUMO");
  return ntohs(a.sin_port);
}

}  // namespace

std::string find_sumo_binary(const std::string& name) {
  if (name.find('/') != std::string::npos) {
    if (executable(name)) return name;
    throw SumoError("SUMO binary '" + name + "' not found or not executable");
  }
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "/usr/bin:/bin";
  size_t begin = 0;
  while (begin <= dirs.size()) {
    const size_t end = std::min(dirs.find(':', begin), dirs.size());
    const std::string candidate = dirs.substr(begin, end - begin) + "/" + name;
    if (end > begin && executable(candidate)) return candidate;
    begin = end + 1;
  }
  throw SumoError("SUMO binary '" + name + "' not found on PATH (Debian: apt-get install sumo)");
}

SumoProcess::SumoProcess(const std::string& binary, const std::vector<std::string>& args,
                         double answer_timeout_s)
    : answer_timeout_s_(answer_timeout_s) {
  port_ = free_port();
  std::vector<std::string> argv{binary};
  argv.insert(argv.end(), args.begin(), args.end());
  argv.push_back("--remote-port");
  argv.push_back(std::to_string(port_));
  std::vector<char*> c_argv;
  for (std::string& a : argv) c_argv.push_back(a.data());
  c_argv.push_back(nullptr);
  pid_ = ::fork();
  if (pid_ < 0) throw SumoError("cannot start SUMO: fork failed");
  if (pid_ == 0) {
    ::execv(binary.c_str(), c_argv.data());
    ::_exit(127);
  }
  watchdog_ = std::thread([this] { watch(); });
}

void SumoProcess::watch() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (!stop_) {
    if (deadline_ && std::chrono::steady_clock::now() >= *deadline_) {
      timed_out_ = true;
      deadline_.reset();
      ::kill(pid_, SIGKILL);  // its socket closes: the blocked call fails
    }
    if (deadline_) {
      const auto until = *deadline_;  // a Call ending meanwhile resets deadline_
      wake_.wait_until(lock, until);
    } else {
      wake_.wait(lock);
    }
  }
}

SumoProcess::Call::Call(SumoProcess& p, double seconds) : p_(p) {
  const std::lock_guard<std::mutex> lock(p_.mutex_);
  p_.deadline_ = std::chrono::steady_clock::now() +
                 std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::duration<double>(seconds));
  p_.wake_.notify_one();
}

SumoProcess::Call::~Call() {
  const std::lock_guard<std::mutex> lock(p_.mutex_);
  p_.deadline_.reset();
  p_.wake_.notify_one();
}

bool SumoProcess::ended(int* status) {
  if (!ended_) {
    int s = 0;
    if (::waitpid(pid_, &s, WNOHANG) == pid_) {
      ended_ = true;
      status_ = WIFEXITED(s) ? WEXITSTATUS(s) : 128 + WTERMSIG(s);
    }
  }
  if (ended_ && status) *status = status_;
  return ended_;
}

void SumoProcess::finish(double timeout_s) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (!ended(nullptr) && std::chrono::steady_clock::now() < until)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  if (ended(nullptr)) return;
  ::kill(pid_, SIGKILL);
  int s = 0;
  ::waitpid(pid_, &s, 0);
  ended_ = true;
  status_ = 128 + SIGKILL;
}

SumoProcess::~SumoProcess() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
    wake_.notify_one();
  }
  if (watchdog_.joinable()) watchdog_.join();
  if (pid_ > 0) finish(0);
}

std::unique_ptr<SumoLink> start_sumo(SumoMode mode, const std::string& binary,
                                     const std::vector<std::string>& args, double answer_timeout_s) {
  // SUMO validates the files that name a schema against those under SUMO_HOME and fails without it; Debian's
  // package installs them here but does not set the variable.
  if (std::getenv("SUMO_HOME") == nullptr && ::access("/usr/share/sumo/data/xsd", R_OK) == 0)
    ::setenv("SUMO_HOME", "/usr/share/sumo", 0);
  if (mode == SumoMode::Libsumo) return start_libsumo(args);
  // A socket whose SUMO died must give an error on the next call, not end this process by SIGPIPE.
  ::signal(SIGPIPE, SIG_IGN);
  return start_traci(find_sumo_binary(binary), args, answer_timeout_s);
}

}  // namespace lpsim
