#include "core/subprocess.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "core/error.h"

extern char** environ;

namespace planet {
namespace {

// Both ends of a pipe, closed when leaving scope.
struct Pipe {
  int fd[2] = {-1, -1};
  Pipe() {
    if (::pipe2(fd, O_CLOEXEC) != 0) throw Error(std::string("cannot create a pipe: ") + std::strerror(errno));
  }
  ~Pipe() {
    closeEnd(0);
    closeEnd(1);
  }
  void closeEnd(int end) {
    if (fd[end] >= 0) ::close(fd[end]);
    fd[end] = -1;
  }
};

// Ignores SIGPIPE while it lives: a child that exits before reading all its input must not end
// this process; the write then fails with EPIPE instead.
struct IgnoreSigpipe {
  struct sigaction previous {};
  IgnoreSigpipe() {
    struct sigaction ignore {};
    ignore.sa_handler = SIG_IGN;
    ::sigaction(SIGPIPE, &ignore, &previous);
  }
  ~IgnoreSigpipe() { ::sigaction(SIGPIPE, &previous, nullptr); }
};

// Starts argv[0] (looked up in PATH) with argv and the file actions, which it then destroys.
// Returns the child's pid, or -1 when it could not be started.
pid_t spawn(const std::vector<std::string>& argv, posix_spawn_file_actions_t& actions) {
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = -1;
  const int spawnError = ::posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  return spawnError == 0 ? pid : -1;
}

}  // namespace

ProcessResult runProcess(const std::vector<std::string>& argv, std::string_view input) {
  ProcessResult result;
  Pipe in, out, err;
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, in.fd[0], STDIN_FILENO);
  posix_spawn_file_actions_adddup2(&actions, out.fd[1], STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, err.fd[1], STDERR_FILENO);
  const pid_t pid = spawn(argv, actions);
  if (pid < 0) return result;
  result.started = true;
  IgnoreSigpipe ignoreSigpipe;
  in.closeEnd(0);
  out.closeEnd(1);
  err.closeEnd(1);

  // Feed stdin and drain both outputs together, so that no pipe fills up and stalls the child.
  ::fcntl(in.fd[1], F_SETFL, O_NONBLOCK);
  size_t written = 0;
  if (input.empty()) in.closeEnd(1);
  char buffer[65536];
  while (out.fd[0] >= 0 || err.fd[0] >= 0) {
    pollfd fds[3] = {{in.fd[1], POLLOUT, 0}, {out.fd[0], POLLIN, 0}, {err.fd[0], POLLIN, 0}};
    if (::poll(fds, 3, -1) < 0) {
      if (errno == EINTR) continue;
      break;
    }
    if (in.fd[1] >= 0 && (fds[0].revents & (POLLOUT | POLLERR | POLLHUP))) {
      const ssize_t n = ::write(in.fd[1], input.data() + written, input.size() - written);
      if (n > 0) written += size_t(n);
      // Done, or the child closed its end (EPIPE, or the error events).
      if (written == input.size() || (n < 0 && errno != EAGAIN && errno != EINTR) ||
          (fds[0].revents & (POLLERR | POLLHUP)))
        in.closeEnd(1);
    }
    for (int k = 1; k <= 2; ++k) {
      Pipe& pipe = k == 1 ? out : err;
      if (pipe.fd[0] < 0 || !(fds[k].revents & (POLLIN | POLLHUP | POLLERR))) continue;
      const ssize_t n = ::read(pipe.fd[0], buffer, sizeof buffer);
      if (n > 0)
        (k == 1 ? result.out : result.err).append(buffer, size_t(n));
      else if (n == 0 || (errno != EAGAIN && errno != EINTR))
        pipe.closeEnd(0);
    }
  }
  in.closeEnd(1);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return result;
}

FedProcess::FedProcess(const std::vector<std::string>& argv) {
  Pipe in;
  errorFile_ = ::memfd_create("planet-child-stderr", MFD_CLOEXEC);
  if (errorFile_ < 0) throw Error(std::string("cannot create a file for a program's errors: ") + std::strerror(errno));
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, in.fd[0], STDIN_FILENO);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, errorFile_, STDERR_FILENO);
  const pid_t pid = spawn(argv, actions);
  if (pid < 0) return;
  started_ = true;
  pid_ = pid;
  input_ = in.fd[1];
  in.fd[1] = -1;  // kept open here; the read end closes with `in`
  struct sigaction ignore {};
  ignore.sa_handler = SIG_IGN;
  ::sigaction(SIGPIPE, &ignore, &previousSigpipe_);
}

FedProcess::~FedProcess() {
  if (input_ >= 0) ::close(input_);
  if (pid_ > 0) {
    ::kill(pid_, SIGKILL);
    int status = 0;
    while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
  }
  if (started()) ::sigaction(SIGPIPE, &previousSigpipe_, nullptr);
  if (errorFile_ >= 0) ::close(errorFile_);
}

bool FedProcess::write(std::string_view data) {
  while (!data.empty()) {
    if (input_ < 0) return false;
    const ssize_t n = ::write(input_, data.data(), data.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;  // EPIPE: it closed its input
    data.remove_prefix(size_t(n));
  }
  return true;
}

int FedProcess::finish() {
  if (input_ >= 0) ::close(input_);
  input_ = -1;
  if (pid_ <= 0) return -1;
  int status = 0;
  while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
  }
  pid_ = -1;  // reaped: nothing left for the destructor to kill
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

std::string FedProcess::errorOutput() const {
  std::string text;
  if (errorFile_ < 0) return text;
  char buffer[4096];
  for (off_t offset = 0;;) {
    const ssize_t n = ::pread(errorFile_, buffer, sizeof buffer, offset);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    text.append(buffer, size_t(n));
    offset += n;
  }
  return text;
}

}  // namespace planet
