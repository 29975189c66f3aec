// Small helpers shared by the test files.
#pragma once

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

}  // namespace planet::test
