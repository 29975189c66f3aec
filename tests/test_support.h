// Small helpers shared by the test files.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "core/error.h"

namespace planet::test {

// The message of the planet::Error that `fn` throws, or "" when it throws nothing; any other
// exception escapes and fails the test.
template <typename Fn>
std::string errorOf(Fn fn) {
  try {
    fn();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// The whole file as bytes ("" when it cannot be read).
inline std::string readFileBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// This test process's folder for its files, /tmp/planet_NAME_PID, made on first use.
inline std::filesystem::path processTempDir(const std::string& name) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("planet_" + name + "_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  return dir;
}

struct ShellRun {
  int exitCode = -1;  // -1: ended by a signal
  std::string out;
  std::string err;
};

// Runs `EXE ARGS` through the shell (so ARGS may quote, e.g. --size ''), with `input` on stdin;
// the streams pass through files in `dir`.
inline ShellRun runShell(const std::string& exe, const std::string& args, const std::string& input,
                         const std::filesystem::path& dir) {
  std::ofstream(dir / "in", std::ios::binary) << input;
  const std::string command = exe + " " + args + " < " + (dir / "in").string() + " > " + (dir / "out").string() +
                              " 2> " + (dir / "err").string();
  const int status = std::system(command.c_str());
  ShellRun run;
  run.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  run.out = readFileBytes(dir / "out");
  run.err = readFileBytes(dir / "err");
  return run;
}

}  // namespace planet::test
