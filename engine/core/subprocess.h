// Running a helper program (the plot script of `planet bench --plot`): its standard input
// given as a string, its standard output and error captured whole.
#pragma once

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

}  // namespace planet
