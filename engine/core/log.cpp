#include "core/log.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>

namespace planet {
namespace {

LogLevel initialLevel() {
  const char* env = std::getenv("PLANET_LOG");
  if (env && std::strcmp(env, "debug") == 0) return LogLevel::Debug;
  if (env && std::strcmp(env, "warning") == 0) return LogLevel::Warning;
  if (env && std::strcmp(env, "error") == 0) return LogLevel::Error;
  return LogLevel::Info;
}

LogLevel gLevel = initialLevel();
std::mutex gLogMutex;

}  // namespace

void setLogLevel(LogLevel level) { gLevel = level; }
LogLevel logLevel() { return gLevel; }

void logMessage(LogLevel level, std::string_view message) {
  if (level < gLevel) return;
  static const char* const kPrefix[] = {"debug: ", "", "warning: ", "error: "};
  std::lock_guard lock(gLogMutex);
  std::fprintf(stderr, "%s%.*s\n", kPrefix[static_cast<int>(level)], static_cast<int>(message.size()), message.data());
}

}  // namespace planet
