// What the fuzz targets share: how a finding ends the run, and the rule every parser's error
// message follows. A finding aborts, so that libFuzzer keeps the input as a crash and the
// corpus replay test (replay_main.cpp) fails on it.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

namespace planet::fuzz {

[[noreturn]] inline void finding(std::string_view what, std::string_view detail = {}) {
  std::fprintf(stderr, "FUZZ FINDING: %.*s\n%.*s\n", int(what.size()), what.data(), int(detail.size()), detail.data());
  std::abort();
}

// The parsers promise one line per error that starts with where it came from; a message that
// breaks that is as much a finding as a crash (a user would see a garbled or anonymous error).
inline void checkErrorMessage(std::string_view message, std::string_view expectedStart) {
  if (!message.starts_with(expectedStart))
    finding("error message does not start with its source", std::string(message));
  if (message.find_first_of("\n\r") != std::string_view::npos)
    finding("error message is not a single line", std::string(message));
}

}  // namespace planet::fuzz
