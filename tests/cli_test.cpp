// `planet` as a user runs it: values on stdout, one-line errors naming the bad value,
// non-zero exit codes, JSON outputs that parse, and no partial output files.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace {

struct CommandResult {
  int exitCode = -1;
  std::string out;
  std::string err;
};

std::string readFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::filesystem::path tempDir() {
  static std::filesystem::path dir = [] {
    std::filesystem::path d = std::filesystem::temp_directory_path() / ("planet_cli_test_" + std::to_string(getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  return dir;
}

// Runs `planet ARGS` with `input` on stdin.
CommandResult planet(const std::string& args, const std::string& input = "") {
  std::filesystem::path dir = tempDir();
  std::ofstream(dir / "in") << input;
  std::string command = std::string(PLANET_EXE) + " " + args + " < " + (dir / "in").string() + " > " +
                        (dir / "out").string() + " 2> " + (dir / "err").string();
  int status = std::system(command.c_str());
  CommandResult run;
  run.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  run.out = readFile(dir / "out");
  run.err = readFile(dir / "err");
  return run;
}

size_t lineCount(const std::string& s) { return size_t(std::count(s.begin(), s.end(), '\n')); }

bool noDevice(const CommandResult& run) { return run.err.find("no Vulkan") != std::string::npos; }

TEST(Cli, HelpListsTheSubcommands) {
  CommandResult run = planet("--help");
  EXPECT_EQ(run.exitCode, 0);
  for (const char* cmd : {"noise", "validate", "bench", "height", "render", "view"})
    EXPECT_NE(run.out.find(cmd), std::string::npos) << cmd;
  CommandResult sub = planet("noise --help");
  EXPECT_EQ(sub.exitCode, 0);
  EXPECT_NE(sub.out.find("--lacunarity"), std::string::npos);
  // The viewer's help names its scripting flags and the keys.
  CommandResult view = planet("view --help");
  EXPECT_EQ(view.exitCode, 0);
  for (const char* text : {"--frames", "--screenshot", "--path", "--quality", "--vsync", "F1", "F12", "Tab"})
    EXPECT_NE(view.out.find(text), std::string::npos) << text << "\n" << view.out;
}

TEST(Cli, NoisePrintsOneValuePerPointWithNineDigits) {
  // Golden values from tools/golden/simplex_reference.py (see noise_golden_test.cpp).
  CommandResult run = planet("noise --type simplex --hash reference", "0.1 0.2 0.3\n1.5,-2.25,3.75\n# comment\n\n");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(run.err, "");
  std::istringstream values(run.out);
  double a, b;
  values >> a >> b;
  EXPECT_NEAR(a, 0.63589036106093655, 2e-6);
  EXPECT_NEAR(b, -0.56940520833333241, 2e-6);
  EXPECT_EQ(lineCount(run.out), 2u);
  // %.9g: nine significant digits, enough to round-trip a float.
  std::string first = run.out.substr(0, run.out.find('\n'));
  EXPECT_EQ(first.substr(0, 2), "0.");
  EXPECT_EQ(first.size(), 2u + 9u) << first;
}

TEST(Cli, BadFlagsAndLinesGiveOneLineErrorsNamingTheValue) {
  struct Case {
    std::string args, input, mustContain;
  } cases[] = {
      {"noise --type fbm --octaves 0", "1 2 3\n", "octaves must be in 1..32, got 0"},
      {"noise --type fbm --octaves 1000", "1 2 3\n", "got 1000"},
      {"noise --type fbm --octaves many", "1 2 3\n", "many"},
      {"noise --type perlin", "1 2 3\n", "'perlin'"},
      {"noise --type fbm --lacunarity 1", "1 2 3\n", "lacunarity must be in (1, 8], got 1"},
      {"noise --type fbm --H nan", "1 2 3\n", "H must be a finite number"},
      {"noise --type fbm --hash slow", "1 2 3\n", "'slow'"},
      {"noise --type fbm --backend tpu", "1 2 3\n", "'tpu'"},
      {"noise --type fbm --seed -1", "1 2 3\n", "--seed"},
      {"noise --type fbm", "1 2 3\n4 5\n", "line 2: expected 3 numbers"},
      {"noise --type fbm", "1 2 zz\n", "line 1: 'zz' is not a number"},
      {"noise --type fbm", std::string("\x7f\x45\x4c\x46\x02\x01\n", 7), "line 1:"},
      {"noise", "1 2 3\n", "--type"},
      {"noise --type fbm --frobnicate", "1 2 3\n", "--frobnicate"},
      {"validate --points 0", "", "--points must be in 1..10000000, got 0"},
      {"validate --points 1e12", "", "--points"},
      {"bench noise --octaves 33", "", "--octaves must be in 1..32, got 33"},
      {"bench noise --repeats 2", "", "--repeats must be in 5..1000, got 2"},
      {"height --at 95,0", "", "latitude must be in [-90, 90] degrees, got 95"},
      {"height --at 45", "", "--at expects LAT,LON in degrees, got '45'"},
      {"height --at 1,2 --count 0", "", "--count must be in 1..1000000, got 0"},
      {"height --at 1,2 --preset nosuch", "", "unknown planet preset 'nosuch'"},
      {"height --at 1,2 --step-m -1", "", "--step-m must be in [0, 1e8], got -1"},
      {"height --at 1,2 --backend tpu", "", "unknown backend 'tpu'"},
      {"render --size 0x0", "", "--size 0x0 is outside 1x1 .. 8192x8192"},
      {"render --size 100000x100000", "", "--size 100000x100000 is outside"},
      {"render --size big", "", "--size expects WIDTHxHEIGHT in pixels, got 'big'"},
      {"render --camera 95,0,100", "", "camera latitude 95 is outside [-90, 90] degrees"},
      {"render --camera 1,2", "", "expected 3 or 5 numbers"},
      {"render --camera 1,2,x", "", "'x' is not a finite number"},
      {"render --sun 10,100", "", "sun elevation 100 is outside [-90, 90] degrees"},
      {"render --fov 0", "", "--fov must be in (0, 179] degrees, got 0"},
      {"render --preset nosuch", "", "unknown planet preset 'nosuch'"},
      {"render --seed 99999999999", "", "--seed must be in 0..4294967295"},
      {"view --size 0x0", "", "--size 0x0 is outside 1x1 .. 8192x8192"},
      {"view --size 100000x100000", "", "--size 100000x100000 is outside"},
      {"view --vsync maybe", "", "--vsync must be 'on' or 'off', got 'maybe'"},
      {"view --quality best", "", "unknown quality 'best'"},
      {"view --frames -1", "", "--frames"},
      {"view --frames 1e12", "", "--frames"},
      {"view --fov nan", "", "--fov"},
      {"view --camera 1,2,nan", "", "'nan' is not a finite number"},
      {"view --preset nosuch", "", "unknown planet preset 'nosuch'"},
      {"view --path /nonexistent/path.txt", "", "cannot read '/nonexistent/path.txt'"},
      {"view --screenshot /tmp/", "", "--screenshot must name a file, got '/tmp/'"},
      {"frobnicate", "", "frobnicate"},
      {"", "", "a command is required"},
      {"bench", "", "a command is required"},
      {"bench frobnicate", "", "frobnicate"},
      {"bench --frames 0", "", "--frames must be in 1..100000, got 0"},
      {"bench --frames -5", "", "--frames must be in 1..100000, got -5"},
      {"bench --warmup -1", "", "--warmup must be in 0..10000, got -1"},
      {"bench --size 0x0", "", "--size 0x0 is outside 1x1 .. 8192x8192"},
      {"bench --size wide", "", "--size expects WIDTHxHEIGHT in pixels, got 'wide'"},
      {"bench --fov 180", "", "--fov must be in (0, 179] degrees, got 180"},
      {"bench --preset nosuch", "", "unknown planet preset 'nosuch'"},
      {"bench --path /nonexistent/path.txt", "", "cannot read '/nonexistent/path.txt'"},
      {"bench --json ''", "", "--json must name a file"},
      {"bench --sun 0,95", "", "sun elevation 95 is outside [-90, 90] degrees"},
      {"bench noise --frames 3", "", "--frames belongs to the frame benchmark"},
  };
  for (const Case& c : cases) {
    CommandResult run = planet(c.args, c.input);
    EXPECT_EQ(run.exitCode, 2) << c.args << "\n" << run.err;
    EXPECT_EQ(lineCount(run.err), 1u) << c.args << "\n" << run.err;
    EXPECT_NE(run.err.find(c.mustContain), std::string::npos) << c.args << "\n" << run.err;
    EXPECT_EQ(run.out, "") << c.args << ": nothing may be printed on an error";
  }
}

TEST(Cli, HeightPrintsOneHeightPerSampleInMetres) {
  CommandResult run = planet("height --preset earth --at 30,40 --bearing 90 --step-m 1000 --count 4");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  std::istringstream lines(run.out);
  std::vector<double> heights{std::istream_iterator<double>(lines), std::istream_iterator<double>()};
  ASSERT_EQ(heights.size(), 4u);
  for (double h : heights) EXPECT_TRUE(h > -15000 && h < 12000) << h;
  // The first sample is the start point itself.
  CommandResult single = planet("height --at 30,40");
  EXPECT_EQ(single.out, run.out.substr(0, run.out.find('\n') + 1));
}

TEST(Cli, GpuHeightsFollowTheCpuReferenceWithinOneCentimetre) {
  const std::string line = "height --at -40.5,170.25 --bearing 123 --step-m 0.05 --count 100";
  CommandResult cpu = planet(line);
  ASSERT_EQ(cpu.exitCode, 0) << cpu.err;
  CommandResult gpu = planet(line + " --backend gpu");
  if (noDevice(gpu)) GTEST_SKIP() << "no Vulkan device on this machine";
  ASSERT_EQ(gpu.exitCode, 0) << gpu.err;
  std::istringstream a(cpu.out), b(gpu.out);
  std::vector<double> hc{std::istream_iterator<double>(a), std::istream_iterator<double>()};
  std::vector<double> hg{std::istream_iterator<double>(b), std::istream_iterator<double>()};
  ASSERT_EQ(hc.size(), 100u);
  ASSERT_EQ(hg.size(), 100u);
  for (size_t i = 0; i < hc.size(); ++i) EXPECT_NEAR(hg[i], hc[i], 0.01) << "sample " << i;
}

TEST(Cli, GpuBackendPrintsTheSameValuesAsTheCpuReference) {
  std::string input;
  for (int i = 0; i < 500; ++i) input += std::to_string(i * 0.37 - 90) + " " + std::to_string(i * 0.11) + ", 4.5\n";
  CommandResult cpu = planet("noise --type ridged --octaves 12 --seed 5", input);
  ASSERT_EQ(cpu.exitCode, 0) << cpu.err;
  CommandResult gpu = planet("noise --type ridged --octaves 12 --seed 5 --backend gpu", input);
  if (noDevice(gpu)) GTEST_SKIP() << "no Vulkan device on this machine";
  ASSERT_EQ(gpu.exitCode, 0) << gpu.err;
  EXPECT_EQ(lineCount(gpu.out), 500u);
  EXPECT_EQ(gpu.out, cpu.out) << "lavapipe must agree bit for bit";
}

TEST(Cli, RenderWritesAPngAndReportsTheFrame) {
  const std::filesystem::path png = tempDir() / "moon.png";
  CommandResult run = planet("render --preset moon --size 64x36 --camera -20,40,-5000,0,-15 --out " + png.string());
  if (noDevice(run)) GTEST_SKIP() << run.err;
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const std::string bytes = readFile(png);
  ASSERT_GT(bytes.size(), 8u);
  EXPECT_EQ(bytes.substr(1, 3), "PNG");
  EXPECT_NE(run.out.find("wrote " + png.string() + " (64x36"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("metres per vertex at the nadir: "), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("triangles drawn: "), std::string::npos) << run.out;
  for (const char* pass : {"GPU time per pass: sky tables ", " heights ", " terrain ", " sky ", " tonemap "})
    EXPECT_NE(run.out.find(pass), std::string::npos) << pass << "\n" << run.out;
  // 5 km below the reference sphere is below any ground: raised to eye height, with a warning.
  EXPECT_NE(run.err.find("warning: camera altitude -5000.00 m is below the ground"), std::string::npos) << run.err;
}

TEST(Cli, RenderToAMissingDirectoryFailsWithoutLeavingFiles) {
  const std::filesystem::path dir = tempDir() / "no_such_dir";
  CommandResult run = planet("render --size 32x18 --out " + (dir / "x.png").string());
  if (noDevice(run)) GTEST_SKIP() << run.err;
  EXPECT_EQ(run.exitCode, 1);
  EXPECT_EQ(lineCount(run.err), 1u) << run.err;
  EXPECT_NE(run.err.find((dir / "x.png").string()), std::string::npos) << run.err;
  EXPECT_FALSE(std::filesystem::exists(dir));
}

TEST(Cli, ValidatePassesAndWritesJson) {
  std::filesystem::path json = tempDir() / "validate.json";
  CommandResult run = planet("validate --points 2000 --json " + json.string());
  if (noDevice(run)) GTEST_SKIP() << "no Vulkan device on this machine";
  ASSERT_EQ(run.exitCode, 0) << run.out << run.err;
  EXPECT_NE(run.out.find("device: "), std::string::npos);
  EXPECT_NE(run.out.find("PASS"), std::string::npos);
  nlohmann::json j = nlohmann::json::parse(readFile(json));
  EXPECT_TRUE(j["pass"].get<bool>());
  EXPECT_FALSE(j["device"].get<std::string>().empty());
  ASSERT_EQ(j["cases"].size(), 34u);  // 2 hashes x (5 fractals x 3 parameter sets + simplex x 2)
  for (const auto& c : j["cases"]) {
    EXPECT_EQ(c["points"].get<int>(), 2000);
    EXPECT_EQ(c["fraction_identical"].get<double>(), 1.0) << c.dump();
  }
}

TEST(Cli, BenchNoiseReportsEveryMethodInJson) {
  std::filesystem::path json = tempDir() / "bench.json";
  CommandResult run = planet("bench noise --points 20000 --octaves 4 --repeats 5 --json " + json.string());
  if (noDevice(run)) GTEST_SKIP() << "no Vulkan device on this machine";
  ASSERT_EQ(run.exitCode, 0) << run.err;
  nlohmann::json j = nlohmann::json::parse(readFile(json));
  EXPECT_FALSE(j["device"].get<std::string>().empty());
  std::set<std::string> methods;
  for (const auto& r : j["results"]) {
    methods.insert(r["method"].get<std::string>());
    EXPECT_EQ(r["octaves"].get<int>(), 4);
    EXPECT_GT(r["min"].get<double>(), 0.0);
    EXPECT_LE(r["min"].get<double>(), r["mevals_per_s"].get<double>());
    EXPECT_LE(r["mevals_per_s"].get<double>(), r["max"].get<double>());
  }
  EXPECT_EQ(methods, (std::set<std::string>{"gpu_fast", "gpu_reference", "cpu_1", "cpu_all", "libnoise_perlin",
                                            "libnoise_ridged"}));
}

// A short path high above the earth preset: few octaves per vertex, so that even the
// vertex-shader variant of --compare takes well under a second per frame on lavapipe.
std::filesystem::path shortPath() {
  std::filesystem::path path = tempDir() / "orbit_path.txt";
  std::ofstream(path) << "# time_s lat lon height_m heading pitch\n0 20 -30 2e7 0 -90\n1 21 -29 1e7 10 -80\n";
  return path;
}

TEST(Cli, BenchPathErrorsNameTheFileTheLineAndTheValue) {
  const std::filesystem::path path = tempDir() / "bad_path.txt";
  std::ofstream(path) << "0 20 -30 2e7 0 -90\n# fine so far\n1 21 -29 1e7 10 -95\n";
  CommandResult run = planet("bench --path " + path.string());
  EXPECT_EQ(run.exitCode, 2);
  EXPECT_EQ(lineCount(run.err), 1u) << run.err;
  EXPECT_NE(run.err.find(path.string() + ":3: pitch_deg -95 is outside [-90, 90]"), std::string::npos) << run.err;
  EXPECT_EQ(run.out, "");
}

TEST(Cli, BenchPrintsTheDefaultPathInTheFileFormat) {
  CommandResult run = planet("bench --print-path");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(run.out.substr(0, 2), "# ");
  EXPECT_NE(run.out.find("\n0 33.8 -90 40000000 0 -90\n"), std::string::npos) << run.out;
  const std::filesystem::path copy = tempDir() / "default_path.txt";
  std::ofstream(copy) << run.out;
  EXPECT_EQ(planet("bench --print-path --path " + copy.string()).out, run.out);
}

TEST(Cli, BenchReportsEveryFieldWithConsistentTimesAndCompareRatios) {
  const std::filesystem::path json = tempDir() / "frames.json";
  const std::filesystem::path csv = tempDir() / "frames.csv";
  CommandResult run = planet("bench --size 96x64 --frames 3 --warmup 1 --no-patches --compare --path " +
                             shortPath().string() + " --json " + json.string() + " --csv " + csv.string());
  if (noDevice(run)) GTEST_SKIP() << "no Vulkan device on this machine";
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_NE(run.out.find("device: "), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("frames per second"), std::string::npos) << run.out;
  EXPECT_NE(run.err.find("bench: vertex_shader, timed frame 1 of 3"), std::string::npos) << run.err;

  nlohmann::json j = nlohmann::json::parse(readFile(json));
  EXPECT_FALSE(j["device"].get<std::string>().empty());
  EXPECT_FALSE(j["driver"].get<std::string>().empty());
  EXPECT_EQ(j["width"].get<int>(), 96);
  EXPECT_EQ(j["height"].get<int>(), 64);
  EXPECT_EQ(j["frames"].get<int>(), 3);
  EXPECT_EQ(j["preset_hash"].get<std::string>().size(), 16u);
  auto checkSummary = [](const nlohmann::json& s, const std::string& what) {
    for (const char* key : {"median", "p95", "p99", "max"}) EXPECT_GT(s.at(key).get<double>(), 0.0) << what << key;
    EXPECT_LE(s["median"].get<double>(), s["p95"].get<double>()) << what;
    EXPECT_LE(s["p95"].get<double>(), s["p99"].get<double>()) << what;
    EXPECT_LE(s["p99"].get<double>(), s["max"].get<double>()) << what;
  };
  checkSummary(j["frame_ms"], "frame_ms ");
  checkSummary(j["gpu_ms"], "gpu_ms ");
  checkSummary(j["terrain_ms"], "terrain_ms ");
  for (const char* pass : {"heights", "terrain"}) checkSummary(j["passes"][pass], pass);
  EXPECT_GT(j["fps"].get<double>(), 0.0);
  EXPECT_GT(j["nadir_m_per_vertex_min"].get<double>(), 0.0);
  EXPECT_GT(j["triangles_median"].get<int64_t>(), 0);
  for (const char* mode : {"vertex_shader", "cpu", "octaves_off"}) {
    ASSERT_TRUE(j["compare"].contains(mode)) << mode;
    EXPECT_GT(j["compare"][mode].get<double>(), 0.0) << mode;
    checkSummary(j["modes"][mode]["terrain_ms"], mode);
  }
  ASSERT_EQ(j["per_frame"].size(), 3u);
  for (const auto& f : j["per_frame"]) {
    double sum = 0.0;
    for (const auto& [name, ms] : f["passes"].items()) {
      EXPECT_GT(ms.get<double>(), 0.0) << name;
      sum += ms.get<double>();
    }
    // Passes run one after another inside the frame's first-to-last timestamp span, and the
    // wall-clock frame contains that span.
    EXPECT_LE(sum, f["gpu_ms"].get<double>() + 1e-6) << f.dump();
    EXPECT_LE(f["gpu_ms"].get<double>(), f["frame_ms"].get<double>()) << f.dump();
    EXPECT_GT(f["triangles"].get<int64_t>(), 0);
    EXPECT_GT(f["vertices_evaluated"].get<int64_t>(), 0);
    EXPECT_GT(f["m_per_vertex_nadir"].get<double>(), 0.0);
  }
  // The CSV: a header and one row per timed frame of each of the four modes.
  const std::string table = readFile(csv);
  EXPECT_EQ(lineCount(table), 1u + 4u * 3u);
  EXPECT_EQ(table.substr(0, table.find(',')), "mode");
  EXPECT_NE(table.find("pass_heights_ms"), std::string::npos);
}

TEST(Cli, BenchPlotIsAPngOrAOneLineErrorAboutMatplotlib) {
  const std::filesystem::path png = tempDir() / "frames.png";
  CommandResult run = planet("bench --size 32x18 --frames 2 --warmup 0 --no-patches --path " + shortPath().string() +
                             " --plot " + png.string());
  if (noDevice(run)) GTEST_SKIP() << "no Vulkan device on this machine";
  if (run.exitCode == 0) {
    EXPECT_EQ(readFile(png).substr(1, 3), "PNG");
  } else {
    // No Python with matplotlib: said before the benchmark runs, in one line, nothing written.
    EXPECT_EQ(run.exitCode, 1);
    EXPECT_EQ(lineCount(run.err), 1u) << run.err;
    EXPECT_NE(run.err.find("matplotlib"), std::string::npos) << run.err;
    EXPECT_EQ(run.out, "");
    EXPECT_FALSE(std::filesystem::exists(png));
  }
}

TEST(Cli, UnwritableJsonPathFailsWithoutLeavingFiles) {
  std::filesystem::path dir = tempDir() / "no-such-dir";
  CommandResult run = planet("validate --points 10 --json " + (dir / "x.json").string());
  if (noDevice(run)) GTEST_SKIP() << "no Vulkan device on this machine";
  EXPECT_EQ(run.exitCode, 1);
  EXPECT_NE(run.err.find("cannot write"), std::string::npos) << run.err;
  EXPECT_FALSE(std::filesystem::exists(dir));
}

}  // namespace
