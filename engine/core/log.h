// Minimal logging to stderr. stdout is reserved for a command's results (values, tables,
// JSON), so that `planet noise < points > values` stays clean.
#pragma once

#include <fmt/format.h>
#include <string_view>

namespace planet {

enum class LogLevel { Debug, Info, Warning, Error };

// Messages below this level are dropped (default Info; PLANET_LOG=debug lowers it).
void setLogLevel(LogLevel level);
LogLevel logLevel();

void logMessage(LogLevel level, std::string_view message);

template <typename... Args>
void logInfo(fmt::format_string<Args...> fmt, Args&&... args) {
  logMessage(LogLevel::Info, fmt::format(fmt, std::forward<Args>(args)...));
}
template <typename... Args>
void logWarning(fmt::format_string<Args...> fmt, Args&&... args) {
  logMessage(LogLevel::Warning, fmt::format(fmt, std::forward<Args>(args)...));
}
template <typename... Args>
void logError(fmt::format_string<Args...> fmt, Args&&... args) {
  logMessage(LogLevel::Error, fmt::format(fmt, std::forward<Args>(args)...));
}
template <typename... Args>
void logDebug(fmt::format_string<Args...> fmt, Args&&... args) {
  if (logLevel() <= LogLevel::Debug) logMessage(LogLevel::Debug, fmt::format(fmt, std::forward<Args>(args)...));
}

}  // namespace planet
