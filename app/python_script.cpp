#include "vgroove/app/python_script.h"

#include "vgroove/app/commands.h"
#include "vgroove/support/parallel.h"
#include "vgroove/support/user_error.h"

#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

extern char** environ;

namespace vgroove::app {

namespace {

namespace fs = std::filesystem;

// The script python/vgroove/FILE: beside the binary in the build tree (build/python/vgroove/FILE),
// or in the installed Python package (PREFIX/bin/vgroove -> PREFIX/VGROOVE_PYTHON_INSTALL_DIR/vgroove/FILE).
std::string script_path(const PythonScript& s) {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    for (const fs::path& p : {exe.parent_path() / "python" / "vgroove" / s.file,
                              exe.parent_path().parent_path() / VGROOVE_PYTHON_INSTALL_DIR / "vgroove" / s.file})
      if (fs::is_regular_file(p, ec)) return p.string();
  }
  throw support::UserError(s.command + ": the " + s.command + " script (python/vgroove/" + s.file +
                           ") is neither beside this binary nor in its installed Python package (" +
                           VGROOVE_PYTHON_INSTALL_DIR + ")");
}

// The signals that stop a script: Ctrl-C, kill's default and a closed terminal. While the script runs
// the parent holds them blocked and takes them with sigtimedwait: each is passed on to the
// script's process group, and the parent returns only once the script is gone.
sigset_t stop_signals() {
  sigset_t s;
  sigemptyset(&s);
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&s, sig);
  return s;
}

// Blocks the stop signals for this scope (the script is run from the main thread alone) and, on the way
// out, takes any still pending (sent while the script was being reaped) before unblocking them.
class BlockedSignals {
 public:
  BlockedSignals() : set_(stop_signals()) { pthread_sigmask(SIG_BLOCK, &set_, &old_); }
  ~BlockedSignals() {
    const timespec zero{0, 0};
    while (sigtimedwait(&set_, nullptr, &zero) > 0) {
    }
    pthread_sigmask(SIG_SETMASK, &old_, nullptr);
  }
  BlockedSignals(const BlockedSignals&) = delete;
  BlockedSignals& operator=(const BlockedSignals&) = delete;
  const sigset_t& set() const { return set_; }
  const sigset_t& old() const { return old_; }

 private:
  sigset_t set_, old_;
};

// Starts the script in a process group of its own (a terminal's Ctrl-C reaches the parent alone,
// which passes it on once; the script never reads the terminal, so a background group costs
// nothing), killed with the parent if the parent dies first (PR_SET_PDEATHSIG: even a SIGKILL'd
// vgroove leaves no script behind to write figures later). Returns its pid, or throws naming the
// interpreter when it cannot be run.
pid_t start_script(const PythonScript& s, const std::string& python, std::vector<char*>& argv,
                   const BlockedSignals& blocked) {
  const std::string cannot_start = s.command + ": cannot start the " + s.command + " script: ";
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) throw support::UserError(cannot_start + std::strerror(errno));
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) {
    const int err = errno;
    ::close(fds[0]), ::close(fds[1]);
    throw support::UserError(cannot_start + std::strerror(err));
  }
  if (pid == 0) {  // the child: async-signal-safe calls only
    ::close(fds[0]);
    ::setpgid(0, 0);
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) ::_exit(127);  // the parent died before the line above
    // The parent's handlers would take a signal meant for the script before exec resets them.
    for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
      struct sigaction sa {};
      if (::sigaction(sig, nullptr, &sa) == 0 && sa.sa_handler != SIG_IGN) std::signal(sig, SIG_DFL);
    }
    pthread_sigmask(SIG_SETMASK, &blocked.old(), nullptr);
    ::execve(python.c_str(), argv.data(), environ);
    const int err = errno;
    (void)!::write(fds[1], &err, sizeof err);
    ::_exit(127);
  }
  ::close(fds[1]);
  ::setpgid(pid, pid);  // also here: no signal may reach the group before it exists
  int err = 0;
  ssize_t n;
  while ((n = ::read(fds[0], &err, sizeof err)) < 0 && errno == EINTR) {
  }
  ::close(fds[0]);
  if (n == static_cast<ssize_t>(sizeof err)) {  // exec failed: the child is gone, reap it
    while (::waitpid(pid, nullptr, 0) < 0 && errno == EINTR) {
    }
    throw support::UserError(s.command + ": cannot run " + python + " (" + std::strerror(err) + "): " + s.needs);
  }
  return pid;
}

// Waits for the script. A stop signal is passed on to its process group; a second one, or a
// script still running kKillAfter after the first, gets SIGKILL. Returns the wait status and the
// first signal taken (0: none).
std::pair<int, int> wait_script(const PythonScript& s, pid_t pid, const BlockedSignals& blocked) {
  constexpr double kKillAfter = 3.0;
  int first = 0, status = 0;
  timespec since{};
  for (;;) {
    const pid_t r = ::waitpid(pid, &status, WNOHANG);
    if (r == pid) return {status, first};
    if (r < 0 && errno != EINTR)
      throw support::UserError(s.command + ": waiting for the " + s.command + " script: " + std::strerror(errno));
    const timespec tick{0, 20'000'000};
    const int sig = sigtimedwait(&blocked.set(), nullptr, &tick);
    if (sig > 0) {
      if (first == 0) {
        first = sig;
        ::clock_gettime(CLOCK_MONOTONIC, &since);
        ::kill(-pid, sig);
      } else {
        ::kill(-pid, SIGKILL);
      }
    } else if (first != 0) {
      timespec now{};
      ::clock_gettime(CLOCK_MONOTONIC, &now);
      if (static_cast<double>(now.tv_sec - since.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec - since.tv_nsec) >
          kKillAfter)
        ::kill(-pid, SIGKILL);
    }
  }
}

// The script writes each output to DIR/.NAME.tmp.PID beside its target (plot.py's render_all,
// html_report.py's write) and removes them when interrupted; a script killed outright cannot, so the
// parent does.
void remove_temporaries(const PythonScript& s, pid_t pid) {
  const fs::path dir = s.output_dir.empty() ? fs::path(".") : fs::path(s.output_dir);
  const std::string tail = ".tmp." + std::to_string(pid);
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.size() > tail.size() + 1 && name[0] == '.' &&
        name.compare(name.size() - tail.size(), tail.size(), tail) == 0) {
      std::error_code rm;
      fs::remove(it->path(), rm);
    }
  }
}

// A script stopped by a signal (0: by Ctrl-C before it started): the same line as the script's,
// and the status a shell gives a process killed by it.
int interrupted(const PythonScript& s, int sig) {
  std::cerr << "\nvgroove: interrupted; " << s.nothing_written << "\n";
  return sig == 0 ? kExitInterrupted : 128 + sig;
}

}  // namespace

int run_python_script(const PythonScript& s) {
  // The interpreter: Debian's (the build's), or the one VGROOVE_PYTHON names.
  const char* env = std::getenv("VGROOVE_PYTHON");
  const std::string python = env && *env ? env : VGROOVE_PYTHON_EXECUTABLE;
  const std::string script = script_path(s);
  if (s.dry_run) return 0;  // the inputs are the script's to check; a dry run starts nothing
  std::vector<std::string> args = {python, script};
  args.insert(args.end(), s.args.begin(), s.args.end());
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const BlockedSignals blocked;
  if (support::cancelled(s.cancel)) return interrupted(s, 0);  // Ctrl-C before the block
  const pid_t pid = start_script(s, python, argv, blocked);
  const auto [status, sig] = wait_script(s, pid, blocked);
  if (sig != 0) {
    remove_temporaries(s, pid);
    // Interrupted by SIGINT, the script says so itself (KeyboardInterrupt: exit 130).
    if (WIFEXITED(status) && WEXITSTATUS(status) == kExitInterrupted) return kExitInterrupted;
    return interrupted(s, sig);
  }
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  return WIFSIGNALED(status) ? 128 + WTERMSIG(status) : 3;
}

}  // namespace vgroove::app
