#include "frame_plot.h"

#include <cstdlib>
#include <vector>

#include <fmt/format.h>

#include "core/error.h"
#include "core/file.h"
#include "core/subprocess.h"
#include "scripts/embedded_scripts.h"

namespace planet::cli {
namespace {

constexpr const char* kInstallHint = "install python3-matplotlib (tools/setup.sh does) or set PLANET_PYTHON";

// The last non-empty line of a program's error output (a Python traceback ends with the error).
std::string lastLine(const std::string& text) {
  size_t end = text.find_last_not_of(" \n\r\t");
  if (end == std::string::npos) return "";
  size_t start = text.rfind('\n', end);
  return text.substr(start == std::string::npos ? 0 : start + 1,
                     end - (start == std::string::npos ? 0 : start + 1) + 1);
}

}  // namespace

std::string findPlotPython() {
  std::vector<std::string> candidates;
  const char* chosen = std::getenv("PLANET_PYTHON");
  if (chosen && *chosen)
    candidates.push_back(chosen);
  else
    candidates = {"python3", "/usr/bin/python3"};
  std::string tried;
  for (const std::string& python : candidates) {
    ProcessResult probe = runProcess({python, "-c", "import matplotlib"}, "");
    if (probe.started && probe.exitCode == 0) return python;
    tried += fmt::format("{}{} ({})", tried.empty() ? "" : ", ", python, probe.started ? "no matplotlib" : "not found");
  }
  throw Error(fmt::format("--plot needs Python 3 with matplotlib; tried {}: {}", tried, kInstallHint));
}

void writeFramePlot(const std::string& python, const std::string& csv, const std::string& pngPath,
                    const std::string& title) {
  ProcessResult run = runProcess({python, "-c", scripts::kEmbedded[0].text, "-", title}, csv);
  if (!run.started) throw Error(fmt::format("--plot: cannot run '{}'", python));
  if (run.exitCode == 3) throw Error(fmt::format("--plot: {} has no matplotlib: {}", python, kInstallHint));
  if (run.exitCode != 0 || run.out.compare(0, 4, "\x89PNG") != 0)
    throw Error(fmt::format("--plot: the plot script failed (exit {}): {}", run.exitCode, lastLine(run.err)));
  writeFileAtomic(pngPath, run.out);
}

}  // namespace planet::cli
