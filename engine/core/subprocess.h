// Running a helper program: the plot script of `planet bench --plot` (runProcess: its standard
// input given as a string, its standard output and error captured whole), and ffmpeg encoding a
// video while the frames are rendered (FedProcess: its input written piece by piece).
#pragma once

#include <signal.h>

#include <string>
#include <string_view>
#include <vector>

namespace planet {

struct ProcessResult {
  bool started = false;  // false: the program could not be run (not found, not executable)
  int exitCode = -1;     // the exit status, or 128 + the signal that ended it
  std::string out;
  std::string err;
};

// Runs argv[0] (looked up in PATH unless it contains '/') with `argv`, writes `input` to its
// standard input and closes it, and waits for it. Never throws for what the program does; throws
// planet::Error only when the pipes or the process cannot be created.
ProcessResult runProcess(const std::vector<std::string>& argv, std::string_view input);

// A program fed through its standard input while it runs. Its standard output is discarded; its
// error output goes to an anonymous file, not a pipe, so that a chatty program can never stall
// on a full pipe while this process is blocked writing its input. SIGPIPE is ignored while one
// lives (a program that exits early makes write() return false instead of ending this process).
class FedProcess {
 public:
  // Starts argv[0] (looked up in PATH unless it contains '/'); started() tells whether it ran.
  // Throws planet::Error only when the pipe or the error file cannot be created.
  explicit FedProcess(const std::vector<std::string>& argv);
  // A program still running is killed (SIGKILL) and waited for.
  ~FedProcess();
  FedProcess(const FedProcess&) = delete;
  FedProcess& operator=(const FedProcess&) = delete;

  bool started() const { return started_; }
  // Writes all of `data` to its input, blocking while the pipe is full; false when the program
  // no longer reads it (it exited, or finish() was called).
  bool write(std::string_view data);
  // Closes its input and waits for it: the exit status, or 128 + the signal that ended it.
  int finish();
  // Everything it wrote to its standard error so far.
  std::string errorOutput() const;

 private:
  bool started_ = false;
  int pid_ = -1;                         // until it is waited for
  int input_ = -1;                       // write end of its standard input
  int errorFile_ = -1;                   // its standard error
  struct sigaction previousSigpipe_ {};  // restored by the destructor
};
}  // namespace planet
