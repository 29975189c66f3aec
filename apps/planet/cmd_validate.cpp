// planet validate: GPU compute against the CPU reference for every noise type and hash, the value
// and the value with gradient.
#include <unistd.h>

#include <cstdio>

#include <fmt/format.h>

#include "cli_common.h"
#include "core/file.h"
#include "core/log.h"
#include "bench/noise_validate.h"

namespace planet::cli {
namespace {

constexpr size_t kMaxValidatePoints = 10'000'000;

struct ValidateCommand {
  size_t points = 65536;
  std::string json;
};

int runValidate(const GlobalOptions& global, const ValidateCommand& cmd, const CLI::App& sub) {
  if (cmd.points < 1 || cmd.points > kMaxValidatePoints)
    throw UsageError(fmt::format("--points must be in 1..{}, got {}", kMaxValidatePoints, cmd.points));
  if (sub.count("--json")) checkOutputFile("--json", cmd.json);
  auto context = openContext(global);
  const bool interactive = ::isatty(STDERR_FILENO);
  noise::ValidationReport report = noise::runValidation(*context, cmd.points, [&](size_t done, size_t total) {
    if (interactive) std::fprintf(stderr, "\rvalidating: case %zu of %zu", done, total);
    if (interactive && done == total) std::fprintf(stderr, "\n");
  });
  std::fputs(report.table().c_str(), stdout);
  std::fflush(stdout);
  if (!cmd.json.empty()) writeFileAtomic(cmd.json, report.toJson().dump(2) + "\n");
  return finishWithValidation(*context, report.pass() ? 0 : kExitFailure);
}

}  // namespace

void addValidateCommand(CLI::App& app, const GlobalOptions& global, int& exitCode) {
  auto cmd = std::make_shared<ValidateCommand>();
  CLI::App* sub = app.add_subcommand(
      "validate",
      "Compare the GPU compute noise with the CPU reference (every type, both hashes, several parameter sets; the "
      "value and the value with its gradient); exit 0 only within the device's tolerance (lavapipe: bit-identical)");
  sub->add_option("--points", cmd->points, "Points per case")->capture_default_str();
  sub->add_option("--json", cmd->json, "Also write the results as JSON to FILE");
  checkNumbersAsText(*sub);
  sub->callback([&global, &exitCode, cmd, sub] { exitCode = runValidate(global, *cmd, *sub); });
}

}  // namespace planet::cli
