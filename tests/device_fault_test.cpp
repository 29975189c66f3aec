// Device faults as a user meets them: no Vulkan driver, a device that runs out of memory, and a
// device that is lost in the middle of the work. Each command must end with one clear line on
// stderr and exit code 1, leave no output file behind (not even a temporary one) and not crash;
// under the asan preset the same runs also prove that nothing leaks on these paths.
//
// Out-of-memory and device loss are injected (PLANET_DEVICE_MEMORY_LIMIT caps the allocator,
// PLANET_FAULT=device-lost@N makes submission N report VK_ERROR_DEVICE_LOST): lavapipe runs in
// the machine's RAM and never loses its device, and the code paths after the driver's answer are
// the same either way.
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/subprocess.h"
#include "test_support.h"

namespace {

namespace fs = std::filesystem;

// A fresh, empty folder for one case's output files.
fs::path emptyDir(const std::string& name) {
  const fs::path dir = planet::test::processTempDir("fault_test") / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// Runs `env VARS... planet ARGS...` (the environment of the test, plus VARS).
planet::ProcessResult planetWith(const std::vector<std::string>& vars, const std::vector<std::string>& args,
                                 const std::string& input = "") {
  std::vector<std::string> argv = {"env"};
  argv.insert(argv.end(), vars.begin(), vars.end());
  argv.push_back(PLANET_EXE);
  argv.insert(argv.end(), args.begin(), args.end());
  return planet::runProcess(argv, input);
}

size_t lines(const std::string& s) { return size_t(std::count(s.begin(), s.end(), '\n')); }

bool haveDevice() {
  static const bool have = planetWith({}, {"height", "--at", "0,0", "--backend", "gpu"}).exitCode == 0;
  return have;
}

std::vector<std::string> filesIn(const fs::path& dir) {
  std::vector<std::string> names;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename());
  return names;
}

// `count` points, one per line: enough that their buffers alone exceed the 1 MiB limit below.
std::string manyPoints(int count) {
  std::string text;
  for (int i = 0; i < count; ++i) text += std::to_string(i % 97) + " " + std::to_string(i % 89) + " 0.5\n";
  return text;
}

struct Command {
  std::string name;
  std::vector<std::string> args;  // "OUT" stands for the case's output folder
  std::string input;
};

// Every command that opens a Vulkan device, each asked to write its output files.
std::vector<Command> gpuCommands() {
  return {
      {"validate", {"validate", "--points", "100000", "--json", "OUT/validate.json"}, ""},
      {"render", {"render", "--size", "64x36", "--out", "OUT/render.png"}, ""},
      {"bench", {"bench", "--size", "64x36", "--frames", "2", "--warmup", "1", "--json", "OUT/bench.json",
                 "--csv", "OUT/bench.csv"}, ""},
      {"bench_noise", {"bench", "noise", "--points", "200000", "--repeats", "5", "--json", "OUT/noise.json"}, ""},
      {"height_gpu", {"height", "--at", "10,20", "--count", "100000", "--step-m", "1", "--backend", "gpu"}, ""},
      {"noise_gpu", {"noise", "--type", "fbm", "--backend", "gpu"}, manyPoints(100000)},
  };
}

std::vector<std::string> withOut(std::vector<std::string> args, const fs::path& dir) {
  for (std::string& arg : args)
    if (arg.rfind("OUT/", 0) == 0) arg = (dir / arg.substr(4)).string();
  return args;
}

// The lines of `text` that mention an error (progress lines do not).
std::vector<std::string> errorLines(const std::string& text) {
  std::vector<std::string> found;
  size_t start = 0;
  while (start < text.size()) {
    const size_t end = std::min(text.find('\n', start), text.size());
    const std::string line = text.substr(start, end - start);
    if (line.find("error") != std::string::npos || line.find("VUID") != std::string::npos) found.push_back(line);
    start = end + 1;
  }
  return found;
}

// What every fault case must show: exit 1, one error line (the last on stderr, after any
// progress lines) containing `reason`, nothing on stdout for the value-printing commands, and an
// empty output folder.
void expectCleanFailure(const Command& c, const planet::ProcessResult& run, const fs::path& dir,
                        const std::string& reason) {
  EXPECT_EQ(run.exitCode, 1) << c.name << "\n" << run.err;
  const std::vector<std::string> errors = errorLines(run.err);
  ASSERT_EQ(errors.size(), 1u) << c.name << "\n" << run.err;
  EXPECT_EQ(errors[0].rfind("planet: error: ", 0), 0u) << c.name << "\n" << run.err;
  EXPECT_EQ(run.err.substr(run.err.size() - errors[0].size() - 1), errors[0] + "\n") << "not the last line: " << run.err;
  EXPECT_NE(errors[0].find(reason), std::string::npos) << c.name << "\n" << run.err;
  EXPECT_EQ(run.err.find("internal error"), std::string::npos) << c.name << "\n" << run.err;
  if (c.name == "height_gpu" || c.name == "noise_gpu") {
    EXPECT_EQ(run.out, "") << c.name;
  }
  EXPECT_TRUE(filesIn(dir).empty()) << c.name << " left " << filesIn(dir).front();
}

TEST(DeviceFaults, NoVulkanDriverIsOneLineAndExitOne) {
  for (const Command& c : gpuCommands()) {
    const fs::path dir = emptyDir("nodriver_" + c.name);
    const planet::ProcessResult run =
        planetWith({"VK_ICD_FILENAMES=/nonexistent/icd.json", "VK_DRIVER_FILES=/nonexistent/icd.json"},
                   withOut(c.args, dir), c.input);
    expectCleanFailure(c, run, dir, "no Vulkan");
    EXPECT_NE(run.err.find("mesa-vulkan-drivers"), std::string::npos) << "names the package to install: " << run.err;
  }
}

TEST(DeviceFaults, AnUnknownDeviceNameListsTheDevicesThereAre) {
  if (!haveDevice()) GTEST_SKIP() << "no Vulkan device on this machine";
  const Command c{"render", {"--device", "nosuch-gpu", "render", "--size", "64x36", "--out", "OUT/r.png"}, ""};
  const fs::path dir = emptyDir("nosuch");
  const planet::ProcessResult run = planetWith({}, withOut(c.args, dir));
  expectCleanFailure(c, run, dir, "no Vulkan device matches 'nosuch-gpu' (available: ");
}

TEST(DeviceFaults, OutOfDeviceMemoryIsOneLineNamingTheRequest) {
  if (!haveDevice()) GTEST_SKIP() << "no Vulkan device on this machine";
  // 1 MiB holds the first small buffers but not a 64 MiB block or the render targets.
  for (const Command& c : gpuCommands()) {
    const fs::path dir = emptyDir("oom_" + c.name);
    const planet::ProcessResult run = planetWith({"PLANET_DEVICE_MEMORY_LIMIT=1M"}, withOut(c.args, dir), c.input);
    expectCleanFailure(c, run, dir, "out of device memory: cannot allocate ");
    EXPECT_NE(run.err.find("of the 1.0 MiB limit"), std::string::npos) << c.name << ": " << run.err;
  }
}

TEST(DeviceFaults, RunningOutAtAnyPointOfTheRenderersSetupFailsCleanly) {
  if (!haveDevice()) GTEST_SKIP() << "no Vulkan device on this machine";
  // Limits that run out at different steps of building the renderer (a 64x36 render holds
  // about 52 MiB on lavapipe): each failure must leave no Vulkan object alive (validation
  // reports any at vkDestroyDevice) and no file; a limit the work fits in renders normally.
  int failed = 0;
  for (const char* limit : {"4M", "12M", "24M", "36M", "42M", "46M", "50M"}) {
    const Command c{std::string("render_") + limit, {"render", "--size", "64x36", "--out", "OUT/r.png"}, ""};
    const fs::path dir = emptyDir("sweep_" + std::string(limit));
    const planet::ProcessResult run =
        planetWith({std::string("PLANET_DEVICE_MEMORY_LIMIT=") + limit}, withOut(c.args, dir));
    if (run.exitCode == 0) {
      EXPECT_TRUE(errorLines(run.err).empty()) << limit << ": " << run.err;
      EXPECT_TRUE(fs::exists(dir / "r.png")) << limit;
      continue;
    }
    ++failed;
    expectCleanFailure(c, run, dir, "out of device memory");
  }
  EXPECT_GE(failed, 4) << "the renderer needs far less memory than it did: move the limits down";
}

TEST(DeviceFaults, AMemoryLimitTheWorkFitsInChangesNothing) {
  if (!haveDevice()) GTEST_SKIP() << "no Vulkan device on this machine";
  const fs::path dir = emptyDir("fits");
  const std::vector<std::string> args = {"render", "--size", "64x36", "--out"};
  std::vector<std::string> limited = args, free = args;
  limited.push_back((dir / "limited.png").string());
  free.push_back((dir / "free.png").string());
  const planet::ProcessResult a = planetWith({"PLANET_DEVICE_MEMORY_LIMIT=1G"}, limited);
  const planet::ProcessResult b = planetWith({}, free);
  ASSERT_EQ(a.exitCode, 0) << a.err;
  ASSERT_EQ(b.exitCode, 0) << b.err;
  EXPECT_EQ(planet::test::readFileBytes(dir / "limited.png"), planet::test::readFileBytes(dir / "free.png")) << "the limit changed the image";
}

TEST(DeviceFaults, BadFaultSettingsNameTheVariableAndTheValue) {
  struct Case {
    std::string var, mustContain;
  } cases[] = {
      {"PLANET_DEVICE_MEMORY_LIMIT=lots", "PLANET_DEVICE_MEMORY_LIMIT expects a size in bytes"},
      {"PLANET_DEVICE_MEMORY_LIMIT=-5M", "got '-5M'"},
      {"PLANET_DEVICE_MEMORY_LIMIT=12T", "got '12T'"},
      {"PLANET_DEVICE_MEMORY_LIMIT=nan", "got 'nan'"},
      {"PLANET_DEVICE_MEMORY_LIMIT=1e300", "got '1e300'"},
      {"PLANET_FAULT=device-lost@0", "PLANET_FAULT must be device-lost@N"},
      {"PLANET_FAULT=meteor", "got 'meteor'"},
      {"PLANET_FAULT=device-lost@99999999999", "got 'device-lost@99999999999'"},
  };
  for (const Case& c : cases) {
    const fs::path dir = emptyDir("badvar");
    const planet::ProcessResult run = planetWith({c.var}, {"render", "--size", "8x8", "--out", (dir / "r.png").string()});
    EXPECT_EQ(run.exitCode, 1) << c.var << "\n" << run.err;
    EXPECT_EQ(lines(run.err), 1u) << c.var << "\n" << run.err;
    EXPECT_NE(run.err.find(c.mustContain), std::string::npos) << c.var << "\n" << run.err;
    EXPECT_TRUE(filesIn(dir).empty()) << c.var;
  }
}

TEST(DeviceFaults, ALostDeviceEndsTheCommandWithAMessageAndNoOutput) {
  if (!haveDevice()) GTEST_SKIP() << "no Vulkan device on this machine";
  // Submission 1 is the first upload; a later one lands in the middle of the frames or runs.
  for (const char* at : {"1", "4"}) {
    for (const Command& c : gpuCommands()) {
      const fs::path dir = emptyDir(std::string("lost_") + at + "_" + c.name);
      const planet::ProcessResult run =
          planetWith({std::string("PLANET_FAULT=device-lost@") + at}, withOut(c.args, dir), c.input);
      if (run.exitCode == 0) {
        // The command needed fewer submissions than that: it ran to the end untouched.
        EXPECT_STRNE(at, "1") << c.name << " submitted nothing?";
        continue;
      }
      expectCleanFailure(c, run, dir, "the Vulkan device was lost");
      EXPECT_NE(run.err.find("VK_ERROR_DEVICE_LOST"), std::string::npos) << c.name << ": " << run.err;
    }
  }
}

}  // namespace
