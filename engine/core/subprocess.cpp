#include "core/subprocess.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
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

}  // namespace

ProcessResult runProcess(const std::vector<std::string>& argv, std::string_view input) {
  ProcessResult result;
  Pipe in, out, err;
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, in.fd[0], STDIN_FILENO);
  posix_spawn_file_actions_adddup2(&actions, out.fd[1], STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, err.fd[1], STDERR_FILENO);
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = -1;
  const int spawnError = ::posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawnError != 0) return result;
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

}  // namespace planet
