// Small helpers shared by the test files.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <system_error>

#include "core/error.h"

namespace planet::test {

// Whether an RGBA8 pixel of a render without clouds shows the sea (or, with the water off, the
// sea's own colours): blue well above red and above green. Land is green, brown or white, the
// sea floor sand or mud.
inline bool looksLikeSea(const uint8_t* rgba) { return rgba[2] > rgba[0] + 40 && rgba[2] > rgba[1]; }

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

// A fresh folder of the test's own in the system's temporary directory ($TMPDIR, else /tmp),
// planet_NAME_PID_XXXXXX, removed with everything in it when the object is destroyed. Cleanup
// lives in the destructor because a failed ASSERT returns from the test body early, past any
// remove_all at its end.
class TempDir {
 public:
  explicit TempDir(const std::string& name) {
    std::string pattern = (std::filesystem::temp_directory_path() /
                           ("planet_" + name + "_" + std::to_string(::getpid()) + "_XXXXXX"))
                              .string();
    if (!::mkdtemp(pattern.data()))
      throw std::filesystem::filesystem_error("cannot make a temporary folder", pattern,
                                              std::error_code(errno, std::generic_category()));
    path_ = pattern;
  }
  ~TempDir() {
    if (::getpid() != owner_) return;  // a forked child must not remove its parent's folder
    std::error_code error;
    std::filesystem::remove_all(path_, error);
    if (error) std::fprintf(stderr, "cannot remove %s: %s\n", path_.c_str(), error.message().c_str());
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::filesystem::path& name) const { return path_ / name; }
  std::string string() const { return path_.string(); }

 private:
  std::filesystem::path path_;
  pid_t owner_ = ::getpid();
};

// This test program's folder NAME for its files (a TempDir), made on first use and removed when
// the program exits, pass or fail. CTest runs every test in a process of its own, so there it
// is one folder per test.
inline const std::filesystem::path& processTempDir(const std::string& name) {
  static std::map<std::string, TempDir> dirs;
  return dirs.try_emplace(name, name).first->second.path();
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
