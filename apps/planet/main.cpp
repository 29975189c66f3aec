// planet: procedural planets with Vulkan compute. Parses the command line and runs one
// subcommand; the work itself lives in the engine library.
#include <cstdio>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli_common.h"
#include "core/error.h"
#include "core/process_memory.h"

namespace planet::cli {
// planet sky (cmd_sky.cpp; declared here as cli_common.h is shared with work in flight).
void addSkyCommand(CLI::App& app, const GlobalOptions& global, int& exitCode);
}  // namespace planet::cli

int main(int argc, char** argv) {
  using namespace planet;
  keepLargeBlocksOutOfTheHeap();  // before any allocation the driver's compiles could fragment
  CLI::App app{"planet: procedural Earth-scale planets rendered with Vulkan compute (CPU via lavapipe or GPU)",
               "planet"};
  app.require_subcommand(0, 1);  // checked after parsing, for a clearer message
  app.fallthrough();
  cli::GlobalOptions global;
  app.add_option("--device", global.device, "Use the first Vulkan device whose name contains this (or PLANET_DEVICE)");
  app.add_flag("--validation", global.validation,
               "Enable Vulkan validation layers; any message fails the run (or PLANET_VALIDATION=1)");
  app.footer("Exit codes: 0 success, 1 failure, 2 bad command line or input.");

  int exitCode = 0;
  cli::addNoiseCommand(app, global, exitCode);
  cli::addValidateCommand(app, global, exitCode);
  cli::addBenchCommand(app, global, exitCode);
  cli::addHeightCommand(app, global, exitCode);
  cli::addExportCommand(app, exitCode);
  cli::addStatsCommand(app, exitCode);
  cli::addRenderCommand(app, global, exitCode);
  cli::addViewCommand(app, global, exitCode);
  cli::addSkyCommand(app, global, exitCode);

  try {
    app.parse(argc, argv);
    // A command group (planet, planet bench) given without its command. planet bench given
    // options of its own ran the frame benchmark instead.
    std::string path = "planet";
    for (CLI::App* group = &app; group;) {
      std::vector<CLI::App*> chosen = group->get_subcommands();
      size_t ownOptions = 0;
      for (const CLI::Option* option : group->get_options()) ownOptions += option->count();
      const bool ranItself = group != &app && ownOptions > 0;
      if (!group->get_subcommands({}).empty() && chosen.empty() && !ranItself) {
        std::string names;
        for (CLI::App* sub : group->get_subcommands({})) names += (names.empty() ? "" : ", ") + sub->get_name();
        if (group != &app && group->get_options().size() > 1) names += ", or options of its own";
        throw cli::UsageError("a command is required after '" + path + "': " + names + " (see " + path + " --help)");
      }
      group = chosen.empty() ? nullptr : chosen.front();
      if (group) path += " " + group->get_name();
    }
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "planet: error: %s (see planet --help)\n", e.what());
    return cli::kExitUsage;
  } catch (const cli::UsageError& e) {
    std::fprintf(stderr, "planet: error: %s\n", e.what());
    return cli::kExitUsage;
  } catch (const VulkanError& e) {
    // A lost device cannot be recovered in-process; say what it means rather than only the code.
    if (e.result() == VK_ERROR_DEVICE_LOST)
      std::fprintf(stderr,
                   "planet: error: the Vulkan device was lost (driver reset or crash); nothing was written: %s\n",
                   e.what());
    else
      std::fprintf(stderr, "planet: error: %s\n", e.what());
    return cli::kExitFailure;
  } catch (const Error& e) {
    std::fprintf(stderr, "planet: error: %s\n", e.what());
    return cli::kExitFailure;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "planet: internal error: %s\n", e.what());
    return cli::kExitFailure;
  }
  return exitCode;
}
