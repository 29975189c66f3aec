// `planet` as a user runs it: values on stdout, one-line errors naming the bad value,
// non-zero exit codes, JSON outputs that parse, and no partial output files.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <utility>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/image_file.h"
#include "test_support.h"

namespace {

using CommandResult = planet::test::ShellRun;

using planet::test::readFileBytes;
std::string readFile(const std::filesystem::path& path) { return readFileBytes(path); }
std::filesystem::path tempDir() { return planet::test::processTempDir("cli_test"); }

// Runs `planet ARGS` with `input` on stdin.
// `environment`: shell assignments put before the command (NAME=value ...).
CommandResult planet(const std::string& args, const std::string& input = "", const std::string& environment = "") {
  return planet::test::runShell(environment + PLANET_EXE, args, input, tempDir());
}

// planet with the Vulkan loader pointed at a driver list that does not exist.
CommandResult planetWithoutDriver(const std::string& args, const std::string& input) {
  return planet(args, input, "VK_DRIVER_FILES=/nonexistent/icd.json VK_ICD_FILENAMES=/nonexistent/icd.json ");
}

size_t lineCount(const std::string& s) { return size_t(std::count(s.begin(), s.end(), '\n')); }

bool noDevice(const CommandResult& run) { return run.err.find("no Vulkan") != std::string::npos; }

TEST(Cli, HelpListsTheSubcommands) {
  CommandResult run = planet("--help");
  EXPECT_EQ(run.exitCode, 0);
  for (const char* cmd : {"noise", "validate", "bench", "height", "export", "stats", "render", "view"})
    EXPECT_NE(run.out.find(cmd), std::string::npos) << cmd;
  CommandResult sub = planet("noise --help");
  EXPECT_EQ(sub.exitCode, 0);
  EXPECT_NE(sub.out.find("--lacunarity"), std::string::npos);
  // The viewer's help names its scripting flags and the keys.
  CommandResult view = planet("view --help");
  EXPECT_EQ(view.exitCode, 0);
  for (const char* text : {"--frames", "--screenshot", "--path", "--quality", "--vsync", "F1", "F12", "Tab"})
    EXPECT_NE(view.out.find(text), std::string::npos) << text << "\n" << view.out;
  // The export commands name their formats and the sidecar.
  CommandResult exportHelp = planet("export --help");
  EXPECT_EQ(exportHelp.exitCode, 0);
  for (const char* text : {"heightmap", "mesh"}) EXPECT_NE(exportHelp.out.find(text), std::string::npos) << text;
  CommandResult heightmap = planet("export heightmap --help");
  for (const char* text : {"--projection", "equirect", "cubemap", "png16", "raw", "--size", "--filtered", "FILE.json"})
    EXPECT_NE(heightmap.out.find(text), std::string::npos) << text << "\n" << heightmap.out;
  CommandResult mesh = planet("export mesh --help");
  for (const char* text : {"--region", "--resolution", "gltf", "glb", "obj", "30m"})
    EXPECT_NE(mesh.out.find(text), std::string::npos) << text << "\n" << mesh.out;
}

TEST(Cli, NoisePrintsOneValuePerPointWithNineDigits) {
  // Golden values from tools/golden/simplex_reference.py (see noise_golden_test.cpp).
  CommandResult run = planet("noise --type simplex --hash reference", "0.1 0.2 0.3\n1.5,-2.25,3.75\n# comment\n\n");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(run.err, "");
  std::istringstream values(run.out);
  double a, b;
  values >> a >> b;
  EXPECT_NEAR(a, 0.48001603375764107, 2e-6);
  EXPECT_NEAR(b, -0.59356689453124922, 2e-6);
  EXPECT_EQ(lineCount(run.out), 2u);
  // %.9g: nine significant digits, enough to round-trip a float.
  std::string first = run.out.substr(0, run.out.find('\n'));
  EXPECT_EQ(first.substr(0, 2), "0.");
  EXPECT_EQ(first.size(), 2u + 9u) << first;
}

// Files a user might hand to --preset and --path by mistake, made once per run.
std::filesystem::path hostileFiles() {
  static std::filesystem::path dir = [] {
    const std::filesystem::path d = tempDir() / "hostile";
    std::filesystem::create_directories(d / "dir.toml");
    auto write = [&](const char* name, const std::string& bytes) {
      std::ofstream(d / name, std::ios::binary) << bytes;
    };
    std::string garbage(4096, '\0');
    uint32_t state = 12345;
    for (char& c : garbage) c = char((state = state * 1664525u + 1013904223u) >> 24);
    write("garbage.bin", garbage);
    write("latin1.toml", "[planet]\nname = \"Caf\xe9\"\n");
    write("truncated.toml", "[planet]\nname = \"Ear");
    write("empty.toml", "");
    std::string deep = "[";
    for (int i = 0; i < 40000; ++i) deep += "a.";
    write("deep.toml", deep + "a]\n");
    write("huge.toml", std::string(2 << 20, '#'));
    write("latin1.path", "0 20 -30 2e7 0 -90\n1 21 -29 1e7 10 \xb0-80\n");
    write("truncated.path", "0 20 -30 2e7 0 -90\n1 21 -29 1e");
    write("empty.path", "");
    write("nul.path", std::string("0 20 -30 2e7 0 -90\n1 21 -29 1e7 10 ") + '\0' + "\n");
    write("hugetime.path", "0 20 -30 2e7 0 -90\n1e300 21 -29 1e7 10 -80\n");
    return d;
  }();
  return dir;
}

// `text` with every "{h}" replaced by the hostile files' folder and every "{out}" by `out`.
std::string expand(std::string text, const std::string& out) {
  for (auto [key, value] : {std::pair<std::string, std::string>{"{h}", hostileFiles().string()}, {"{out}", out}})
    for (size_t at; (at = text.find(key)) != std::string::npos;) text.replace(at, key.size(), value);
  return text;
}

// Every front door of every subcommand (issue 7): empty, NaN/Inf, negative, wrong type and
// absurd values, unknown flags, and files that are binary, not UTF-8, truncated, empty, too
// large or a directory. Each gives one line on stderr naming the value, nothing on stdout, a
// non-zero exit, and no file in the folder `{out}` that outputs point into. The cases run with
// no Vulkan driver to be found: a command that reached for the device before checking its input
// would fail with the driver's error instead of the expected one (a time limit said the same
// but failed under ASan on a loaded machine).
TEST(Cli, BadFlagsAndLinesGiveOneLineErrorsNamingTheValue) {
  struct Case {
    std::string args, input, mustContain;
    int exitCode = 2;
  } cases[] = {
      // planet noise: flags and the point stream on stdin.
      {"noise --type fbm --octaves 0", "1 2 3\n", "octaves must be in 1..32, got 0"},
      {"noise --type fbm --octaves 1000", "1 2 3\n", "octaves must be in 1..32, got 1000"},
      {"noise --type fbm --octaves -1", "1 2 3\n", "octaves must be in 1..32, got -1"},
      {"noise --type fbm --octaves ''", "1 2 3\n", "--octaves expects a whole number, got ''"},
      {"noise --type fbm --octaves many", "1 2 3\n", "--octaves expects a whole number, got 'many'"},
      {"noise --type fbm --octaves 4.5", "1 2 3\n", "--octaves expects a whole number, got '4.5'"},
      {"noise --type fbm --octaves 1e3", "1 2 3\n", "--octaves expects a whole number, got '1e3'"},
      {"noise --type fbm --octaves 99999999999", "1 2 3\n", "--octaves = 99999999999"},
      {"noise --type fbm --octaves 99999999999999999999", "1 2 3\n",
       "--octaves is out of range, got 99999999999999999999"},
      {"noise --type perlin", "1 2 3\n", "'perlin'"},
      {"noise --type ''", "1 2 3\n", "unknown noise type ''"},
      {"noise --type fbm --lacunarity 1", "1 2 3\n", "lacunarity must be in (1, 8], got 1"},
      {"noise --type fbm --lacunarity -2", "1 2 3\n", "lacunarity must be in (1, 8], got -2"},
      {"noise --type fbm --lacunarity inf", "1 2 3\n", "lacunarity must be a finite number, got inf"},
      {"noise --type fbm --H nan", "1 2 3\n", "H must be a finite number"},
      {"noise --type fbm --H ''", "1 2 3\n", "--H expects a number, got ''"},
      {"noise --type fbm --H 1e400", "1 2 3\n", "--H is out of range, got 1e400"},
      {"noise --type fbm --offset nan", "1 2 3\n", "offset must be a finite number, got nan"},
      {"noise --type fbm --offset ''", "1 2 3\n", "--offset expects a number, got ''"},
      {"noise --type fbm --gain -1", "1 2 3\n", "gain must be in [0, 16], got -1"},
      {"noise --type fbm --gain abc", "1 2 3\n", "--gain expects a number, got 'abc'"},
      {"noise --type fbm --hash slow", "1 2 3\n", "'slow'"},
      {"noise --type fbm --hash ''", "1 2 3\n", "unknown noise hash ''"},
      {"noise --type fbm --backend tpu", "1 2 3\n", "'tpu'"},
      {"noise --type fbm --backend ''", "1 2 3\n", "unknown backend ''"},
      {"noise --type fbm --seed -1", "1 2 3\n", "--seed must not be negative, got -1"},
      {"noise --type fbm --seed ''", "1 2 3\n", "--seed expects a whole number, got ''"},
      {"noise --type fbm --seed 1e12", "1 2 3\n", "--seed expects a whole number, got '1e12'"},
      {"noise --type fbm --seed 4294967296", "1 2 3\n", "--seed = 4294967296"},
      {"noise --type fbm", "1 2 3\n4 5\n", "line 2: expected 3 numbers"},
      {"noise --type fbm", "1 2 zz\n", "line 1: 'zz' is not a number"},
      {"noise --type fbm", "1 2 3\nnan 0 0\n", "line 2: 'nan' is not a finite number"},
      {"noise --type fbm", "0 -inf 0\n", "line 1: '-inf' is not a finite number"},
      {"noise --type fbm", "1e39 0 0\n", "line 1: '1e39' is out of range for a float"},
      {"noise --type fbm", "1 2 3 4\n", "line 1: expected 3 numbers 'x y z', got more"},
      {"noise --type fbm", std::string("\x7f\x45\x4c\x46\x02\x01\n", 7), "line 1:"},
      {"noise --type fbm", std::string("1 2 3\0\n", 7), "line 1: '3?' is not a number"},
      {"noise --type fbm", "1 2 \xe9\n", "line 1: '?' is not a number"},
      {"noise --type fbm", "1 2 " + std::string(1 << 20, '9') + "\n", "line 1: '99999999"},
      {"noise", "1 2 3\n", "--type"},
      {"noise --type fbm --frobnicate", "1 2 3\n", "--frobnicate"},
      {"noise --type faults --count 0", "1 2 3\n", "faults (the number of great circles) must be in 1..10000, got 0"},
      {"noise --type faults --count 10001", "1 2 3\n", "must be in 1..10000, got 10001"},
      {"noise --type faults --width -1", "1 2 3\n", "width of faults must be in [0, 1.5] radians, got -1"},
      {"noise --type fbm --count 5", "1 2 3\n", "--count and --width apply to --type faults only, not to fbm"},
      {"noise --type mpd --levels 25", "1 2 3\n", "levels of mpd must be in 1..24, got 25"},
      {"noise --type mpd --octaves 5", "1 2 3\n", "--octaves does not apply to mpd or mpd_ico: give --levels"},
      {"noise --type faults --multifractal", "1 2 3\n",
       "--levels and --multifractal apply to --type mpd and mpd_ico only"},
      // planet validate
      {"validate --points 0", "", "--points must be in 1..10000000, got 0"},
      {"validate --points 1e12", "", "--points expects a whole number, got '1e12'"},
      {"validate --points -1", "", "--points must not be negative, got -1"},
      {"validate --points ''", "", "--points expects a whole number, got ''"},
      {"validate --points abc", "", "--points expects a whole number, got 'abc'"},
      {"validate --points 99999999999999999999999", "", "--points is out of range, got 99999999999999999999999"},
      {"validate --points 10000001 --json {out}/v.json", "", "--points must be in 1..10000000, got 10000001"},
      {"validate --json ''", "", "--json must name a file"},
      {"validate --json {out}", "", "--json must name a file, got '"},
      {"validate --json {out}/", "", "--json must name a file, got '"},
      {"validate --json {out}/no_such_dir/v.json", "", "cannot write '", 1},
      {"validate --frobnicate", "", "--frobnicate"},
      // planet bench noise
      {"bench noise --octaves 33", "", "--octaves must be in 1..32, got 33"},
      {"bench noise --octaves 1000", "", "--octaves must be in 1..32, got 1000"},
      {"bench noise --octaves -1", "", "--octaves must be in 1..32, got -1"},
      {"bench noise --octaves nan", "", "nan"},
      {"bench noise --repeats 2", "", "--repeats must be in 5..1000, got 2"},
      {"bench noise --repeats -1", "", "--repeats must be in 5..1000, got -1"},
      {"bench noise --repeats 1e12", "", "1e12"},
      {"bench noise --points 0 --json {out}/b.json", "", "--points must be in 1..50000000, got 0"},
      {"bench noise --points 1e12", "", "1e12"},
      {"bench noise --points abc", "", "abc"},
      {"bench noise --frobnicate", "", "--frobnicate"},
      {"bench noise --points -1", "", "--points must not be negative, got -1"},
      {"bench noise --points 99999999999999999999", "", "--points is out of range, got 99999999999999999999"},
      {"bench noise --octaves ''", "", "--octaves expects a whole number, got ''"},
      {"bench noise --json ''", "", "--json must name a file"},
      {"bench noise --json {out}", "", "--json must name a file, got '"},
      // planet bench (the frame benchmark)
      {"bench", "", "a command is required"},
      {"bench frobnicate", "", "frobnicate"},
      {"bench --frames 0", "", "--frames must be in 1..100000, got 0"},
      {"bench --frames -5", "", "--frames must be in 1..100000, got -5"},
      {"bench --frames 1e12", "", "1e12"},
      {"bench --frames abc", "", "abc"},
      {"bench --warmup -1", "", "--warmup must be in 0..10000, got -1"},
      {"bench --warmup 1e12", "", "1e12"},
      {"bench --size 0x0", "", "--size 0x0 is outside 1x1 .. 8192x8192"},
      {"bench --size 100000x100000", "", "--size 100000x100000 is outside 1x1 .. 8192x8192"},
      {"bench --size ''", "", "--size expects WIDTHxHEIGHT in pixels, got ''"},
      {"bench --size wide", "", "--size expects WIDTHxHEIGHT in pixels, got 'wide'"},
      {"bench --mesh 16x", "", "--mesh expects auto or RINGSxVERTICES (e.g. 16x128), got '16x'"},
      {"bench --mesh 300x128", "", "--mesh 300x128: rings per level must be in 1..256, got 300"},
      {"bench --mesh 16x5000", "", "--mesh 16x5000: vertices per ring must be in 3..4096, got 5000"},
      {"bench --terrain-shading compute", "", "--terrain-shading must be forward or deferred, got 'compute'"},
      {"bench --fov 180", "", "--fov must be in (0, 179] degrees, got 180"},
      {"bench --fov nan", "", "--fov must be in (0, 179] degrees, got nan"},
      {"bench --fov -1", "", "--fov must be in (0, 179] degrees, got -1"},
      {"bench --flight-fps 0.5", "", "--flight-fps must be 0 or in 1..1000, got 0.5"},
      {"bench --flight-fps -60", "", "--flight-fps must be 0 or in 1..1000, got -60"},
      {"bench --flight-fps nan", "", "--flight-fps must be 0 or in 1..1000, got nan"},
      {"bench --flight-fps 5000", "", "--flight-fps must be 0 or in 1..1000, got 5000"},
      {"bench --in-flight 3", "", "--in-flight must be 1 or 2, got 3"},
      {"bench --in-flight 0", "", "--in-flight must be 1 or 2, got 0"},
      {"bench --in-flight 2 --flight-fps 0", "",
       "--in-flight 2 times each frame behind a real-time one: it needs --flight-fps above 0"},
      {"bench --sun 0,95", "", "sun elevation 95 is outside [-90, 90] degrees"},
      {"bench --sun nan,nan", "", "'nan' is not a finite number"},
      {"bench --preset nosuch", "", "unknown planet preset 'nosuch'"},
      {"bench --preset {h}/garbage.bin", "", "garbage.bin:1:1: not"},
      {"bench --preset {h}/latin1.toml", "", "latin1.toml:2:12: not UTF-8 text (invalid byte 0xe9)"},
      {"bench --preset {h}/truncated.toml", "", "truncated.toml:2:"},
      {"bench --preset {h}/empty.toml", "", "empty.toml: empty document"},
      {"bench --preset {h}/dir.toml", "", "dir.toml': Is a directory"},
      {"bench --preset {h}/deep.toml", "", "deep.toml:1: a key path of 40001 parts nests too deep"},
      {"bench --preset {h}/huge.toml", "", "huge.toml: too large"},
      {"bench --path /nonexistent/path.txt", "", "cannot read '/nonexistent/path.txt'"},
      {"bench --path ''", "", "--path must name a file"},
      {"bench --path {h}/garbage.bin", "", "garbage.bin:1: '"},
      {"bench --path {h}/latin1.path", "", "latin1.path:2: '?-80' is not a number"},
      {"bench --path {h}/nul.path", "", "nul.path:2: '?' is not a number"},
      {"bench --path {h}/truncated.path", "", "truncated.path:2: '1e' is not a number"},
      {"bench --path {h}/empty.path", "", "empty.path: a camera path needs at least 2 keys, got 0"},
      {"bench --path {h}/hugetime.path", "", "hugetime.path:2: time_s 1e+300 is outside"},
      {"bench --path {h}/dir.toml", "", "dir.toml': Is a directory"},
      {"bench --json ''", "", "--json must name a file"},
      {"bench --csv ''", "", "--csv must name a file"},
      {"bench --plot ''", "", "--plot must name a file"},
      {"bench --frames 0 --json {out}/f.json --csv {out}/f.csv --plot {out}/f.png", "", "--frames"},
      {"bench noise --frames 3", "", "--frames belongs to the frame benchmark"},
      {"bench --warmup ''", "", "--warmup expects a whole number, got ''"},
      {"bench --sun ''", "", "''"},
      {"bench --frames ''", "", "--frames expects a whole number, got ''"},
      {"bench --fov ''", "", "--fov expects a number, got ''"},
      {"bench --frames 99999999999999999999", "", "--frames is out of range, got 99999999999999999999"},
      {"bench --json {out}", "", "--json must name a file, got '"},
      {"bench --csv {out}", "", "--csv must name a file, got '"},
      {"bench --plot {out}/", "", "--plot must name a file, got '"},
      // planet height
      {"height --at 95,0", "", "latitude must be in [-90, 90] degrees, got 95"},
      {"height --at 45", "", "--at expects LAT,LON in degrees, got '45'"},
      {"height --at ''", "", "--at expects LAT,LON in degrees, got ''"},
      {"height --at nan,0", "", "--at expects LAT,LON in degrees, got 'nan,0'"},
      {"height --at 1,inf", "", "--at expects LAT,LON in degrees, got '1,inf'"},
      {"height --at 1,2 --count 0", "", "--count must be in 1..1000000, got 0"},
      {"height --at 1,2 --count 1000001", "", "--count must be in 1..1000000, got 1000001"},
      {"height --at 1,2 --count 1e12", "", "--count expects a whole number, got '1e12'"},
      {"height --at 1,2 --count -1", "", "--count must not be negative, got -1"},
      {"height --at 1,2 --count ''", "", "--count expects a whole number, got ''"},
      {"height --at 1,2 --count 99999999999999999999", "", "--count is out of range, got 99999999999999999999"},
      {"height --at 1,2 --step-m -1", "", "--step-m must be in [0, 1e8], got -1"},
      {"height --at 1,2 --step-m inf", "", "--step-m must be in [0, 1e8], got inf"},
      {"height --at 1,2 --step-m ''", "", "--step-m expects a number, got ''"},
      {"height --at 1,2 --step-m 1e400", "", "--step-m is out of range, got 1e400"},
      {"height --at 1,2 --bearing nan", "", "--bearing must be finite, got nan"},
      {"height --at 1,2 --bearing ''", "", "--bearing expects a number, got ''"},
      {"height --at 1,2 --bearing north", "", "--bearing expects a number, got 'north'"},
      {"height --at 1,2 --backend tpu", "", "unknown backend 'tpu'"},
      {"height --at 1,2 --backend ''", "", "unknown backend ''"},
      {"height --at 1,2 --preset nosuch", "", "unknown planet preset 'nosuch'"},
      {"height --at 1,2 --preset ''", "", "unknown planet preset ''"},
      {"height --at 1,2 --preset {h}/garbage.bin", "", "garbage.bin:1:1: not"},
      {"height --at 1,2 --preset {h}/latin1.toml", "", "latin1.toml:2:12: not UTF-8 text (invalid byte 0xe9)"},
      {"height --at 1,2 --preset {h}/truncated.toml", "", "truncated.toml:2:"},
      {"height --at 1,2 --preset {h}/empty.toml", "", "empty.toml: empty document"},
      {"height --at 1,2 --preset {h}/dir.toml", "", "dir.toml': Is a directory"},
      {"height --at 1,2 --preset {h}/deep.toml", "", "deep.toml:1: a key path of 40001 parts nests too deep"},
      {"height --at 1,2 --preset {h}/huge.toml", "", "huge.toml: too large"},
      {"height --at 1,2 --preset {h}/missing.toml", "", "missing.toml': No such file or directory"},
      // planet export (no Vulkan at all; every check before the heights are evaluated)
      {"export", "", "a command is required after 'planet export': heightmap, mesh"},
      {"export heightmap", "", "--out is required"},
      {"export heightmap --out {out}/h.png --size 0", "", "--size 0 is outside 1x1 .. 16384x8192 for an equirect map"},
      {"export heightmap --out {out}/h.png --size 20000x10000", "", "--size 20000x10000 is outside 1x1 .. 16384x8192"},
      {"export heightmap --out {out}/h.png --size 16384x8193", "", "--size 16384x8193 is outside 1x1 .. 16384x8192"},
      {"export heightmap --out {out}/h.png --size ''", "", "--size expects W or WxH in pixels, got ''"},
      {"export heightmap --out {out}/h.png --size -5", "", "--size expects W or WxH in pixels, got '-5'"},
      {"export heightmap --out {out}/h.png --size 1e3", "", "--size expects W or WxH in pixels, got '1e3'"},
      {"export heightmap --out {out}/h.png --size 64x", "", "--size expects W or WxH in pixels, got '64x'"},
      {"export heightmap --out {out}/h.png --size 99999999999999999999", "", "got '99999999999999999999'"},
      {"export heightmap --out {out}/h.png --projection cubemap --size 5000", "",
       "--size 5000 is outside 1 .. 4096 for a cube-map face"},
      {"export heightmap --out {out}/h.png --projection cubemap --size 64x32", "",
       "--size 64x32 is not square: a cube-map face is N x N"},
      {"export heightmap --out {out}/h.png --projection cubemap --size abc", "",
       "--size expects the face size N (or NxN) in pixels, got 'abc'"},
      {"export heightmap --out {out}/h.png --projection mercator", "",
       "unknown projection 'mercator' (expected equirect or cubemap)"},
      {"export heightmap --out {out}/h.png --projection ''", "", "unknown projection ''"},
      {"export heightmap --out {out}/h.tif", "",
       "--format not given and --out '{out}/h.tif' does not end in .png or .raw"},
      {"export heightmap --out {out}/h.png --format jpeg", "", "unknown heightmap format 'jpeg'"},
      {"export heightmap --out {out}/h.png --format raw", "",
       "--format raw does not match --out '{out}/h.png' (a file of that name is png16)"},
      {"export heightmap --out ''", "", "--out must name a file"},
      {"export heightmap --out {out}", "", "--out must name a file, got '"},
      {"export heightmap --out {out}/", "", "--out must name a file, got '"},
      {"export heightmap --out {out}/no_such_dir/h.png", "", "cannot write '{out}/no_such_dir/h.png'", 1},
      {"export heightmap --out {out}/h.png --threads 1000", "",
       "--threads must be in 0..256 (0: one per core), got 1000"},
      {"export heightmap --out {out}/h.png --threads -1", "", "--threads must not be negative, got -1"},
      {"export heightmap --out {out}/h.png --threads ''", "", "--threads expects a whole number, got ''"},
      {"export heightmap --out {out}/h.png --seed 99999999999", "", "--seed must be in 0..4294967295, got 99999999999"},
      {"export heightmap --out {out}/h.png --seed -1", "", "--seed must not be negative, got -1"},
      {"export heightmap --out {out}/h.png --preset nosuch", "", "unknown planet preset 'nosuch'"},
      {"export heightmap --out {out}/h.png --preset {h}/garbage.bin", "", "garbage.bin:1:1: not"},
      {"export heightmap --out {out}/h.png --preset {h}/dir.toml", "", "dir.toml': Is a directory"},
      {"export heightmap --out {out}/h.png --preset {h}/huge.toml", "", "huge.toml: too large"},
      {"export heightmap --out {out}/h.png --frobnicate", "", "--frobnicate"},
      {"export mesh --out {out}/m.obj", "", "--region is required"},
      {"export mesh --region 1,2,3 --out {out}/m.obj", "",
       "--region expects SOUTH,WEST,NORTH,EAST in degrees, got '1,2,3'"},
      {"export mesh --region 1,2,3,4,5 --out {out}/m.obj", "", "got '1,2,3,4,5'"},
      {"export mesh --region '' --out {out}/m.obj", "", "--region expects SOUTH,WEST,NORTH,EAST in degrees, got ''"},
      {"export mesh --region nan,0,1,1 --out {out}/m.obj", "", "got 'nan,0,1,1'"},
      {"export mesh --region 0,0,1,inf --out {out}/m.obj", "", "got '0,0,1,inf'"},
      {"export mesh --region 0,0,95,1 --out {out}/m.obj", "",
       "--region 0,0,95,1: region latitude 95 is outside [-90, 90] degrees"},
      {"export mesh --region 5,0,1,1 --out {out}/m.obj", "",
       "region south latitude 5 must be less than north latitude 1"},
      {"export mesh --region 0,170,1,-170 --out {out}/m.obj", "",
       "region west longitude 170 must be less than east longitude -170"},
      {"export mesh --region 0,-200,1,200 --out {out}/m.obj", "", "region spans 400 degrees of longitude, at most 360"},
      {"export mesh --region 0,0,1,400 --out {out}/m.obj", "", "region longitude 400 is outside [-360, 360] degrees"},
      {"export mesh --region 0,0,1,1 --resolution 1 --out {out}/m.obj", "",
       "--resolution 1 is outside 2..2048 vertices per side"},
      {"export mesh --region 0,0,1,1 --resolution 5000 --out {out}/m.obj", "", "--resolution 5000 is outside 2..2048"},
      {"export mesh --region 0,0,1,1 --resolution 1m --out {out}/m.obj", "",
       "--resolution 1m needs 111196 vertices per side for this region, at most 2048"},
      {"export mesh --region 0,0,1,1 --resolution -3m --out {out}/m.obj", "",
       "--resolution expects vertices per side N or a spacing in metres like 30m, got '-3m'"},
      {"export mesh --region 0,0,1,1 --resolution 0m --out {out}/m.obj", "", "got '0m'"},
      {"export mesh --region 0,0,1,1 --resolution '' --out {out}/m.obj", "", "got ''"},
      {"export mesh --region 0,0,1,1 --resolution abc --out {out}/m.obj", "", "got 'abc'"},
      {"export mesh --region 0,0,1,1 --out {out}/m.stl", "",
       "--format not given and --out '{out}/m.stl' does not end in .gltf, .glb or .obj"},
      {"export mesh --region 0,0,1,1 --out {out}/m.obj --format fbx", "", "unknown mesh format 'fbx'"},
      {"export mesh --region 0,0,1,1 --out {out}/m.obj --format gltf", "", "--format gltf does not match --out"},
      {"export mesh --region 0,0,1,1 --out ''", "", "--out must name a file"},
      {"export mesh --region 0,0,1,1 --out {out}/", "", "--out must name a file, got '"},
      {"export mesh --region 0,0,1,1 --out {out}/no_such_dir/m.glb", "", "cannot write '{out}/no_such_dir/m.glb'", 1},
      {"export mesh --region 0,0,1,1 --out {out}/m.obj --threads 257", "", "--threads must be in 0..256"},
      {"export mesh --region 0,0,1,1 --out {out}/m.obj --preset {h}/truncated.toml", "", "truncated.toml:2:"},
      {"export mesh --region 0,0,1,1 --out {out}/m.obj --seed 4294967296", "", "--seed must be in 0..4294967295"},
      {"height --at 1,2 --seed 4294967296", "", "--seed must be in 0..4294967295, got 4294967296"},
      {"height --at 1,2 --seed -1", "", "--seed must not be negative, got -1"},
      // planet render
      {"render --size 0x0 --out {out}/r.png", "", "--size 0x0 is outside 1x1 .. 8192x8192"},
      {"render --size 100000x100000 --out {out}/r.png", "", "--size 100000x100000 is outside"},
      {"render --size big", "", "--size expects WIDTHxHEIGHT in pixels, got 'big'"},
      {"render --size ''", "", "--size expects WIDTHxHEIGHT in pixels, got ''"},
      {"render --size -1x-1", "", "--size expects WIDTHxHEIGHT in pixels, got '-1x-1'"},
      {"render --size nanxnan", "", "--size expects WIDTHxHEIGHT in pixels, got 'nanxnan'"},
      {"render --size 1e3x1e3", "", "--size expects WIDTHxHEIGHT in pixels, got '1e3x1e3'"},
      {"render --size 99999999999999999999x2", "", "got '99999999999999999999x2'"},
      {"render --size '64\nx36'", "", "--size expects WIDTHxHEIGHT in pixels, got '64?x36'"},
      {"render --mesh abc --out {out}/r.png", "", "--mesh expects auto or RINGSxVERTICES (e.g. 16x128), got 'abc'"},
      {"render --mesh 0x128 --out {out}/r.png", "", "--mesh 0x128: rings per level must be in 1..256, got 0"},
      {"render --mesh 16x2 --out {out}/r.png", "", "--mesh 16x2: vertices per ring must be in 3..4096, got 2"},
      {"render --mesh ''", "", "--mesh expects auto or RINGSxVERTICES (e.g. 16x128), got ''"},
      {"render --terrain-shading deffered --out {out}/r.png", "",
       "--terrain-shading must be forward or deferred, got 'deffered'"},
      {"render --terrain-shading ''", "", "--terrain-shading must be forward or deferred, got ''"},
      {"render --camera 95,0,100", "", "camera latitude 95 is outside [-90, 90] degrees"},
      {"render --camera 1,2", "", "expected 3 or 5 numbers"},
      {"render --camera 1,2,x", "", "'x' is not a finite number"},
      {"render --camera nan,0,0", "", "'nan' is not a finite number"},
      {"render --camera 0,0,1e400", "", "'1e400' is not a finite number"},
      {"render --camera 0,0,-1e12", "", "camera altitude -1000000000000 m is outside"},
      {"render --camera ''", "", "camera '': '' is not a finite number"},
      {"render --scene pluto", "", "unknown scene 'pluto' (built-in: system; or a FILE.toml)"},
      {"render --scene system --camera Pluto:0,0,1", "",
       "scene 'Three worlds' has no body 'Pluto' (bodies: Giant, Terra, Moon)"},
      {"render --scene system --camera 0,0,1", "",
       "--camera with --scene is BODY:LAT,LON,ALT[,HEADING,PITCH], got '0,0,1'"},
      {"render --scene system --camera Moon:95,0,1", "", "camera latitude 95 is outside [-90, 90] degrees"},
      {"render --scene system --camera Moon:0,0,1 --look-at Moon", "", "--look-at Moon names the camera's own body"},
      {"render --scene system --preset earth", "", "--preset and --scene exclude each other"},
      {"render --scene system --sun 10,10", "", "--sun does not apply to --scene"},
      {"render --look-at Terra", "", "--look-at needs --scene (it names a body of the scene)"},
      {"render --scene {out}/missing.toml", "", "missing.toml"},
      {"render --sun 10,100", "", "sun elevation 100 is outside [-90, 90] degrees"},
      {"render --sun nan,1", "", "'nan' is not a finite number"},
      {"render --sun ''", "", "sun '': '' is not a finite number"},
      {"render --fov 0", "", "--fov must be in (0, 179] degrees, got 0"},
      {"render --fov -5", "", "--fov must be in (0, 179] degrees, got -5"},
      {"render --fov inf", "", "--fov must be in (0, 179] degrees, got inf"},
      {"render --fov ''", "", "--fov expects a number, got ''"},
      {"render --time nan", "", "--time must be a number of seconds within ±1e9, got nan"},
      {"render --time 1e12", "", "--time must be a number of seconds within ±1e9, got 1000000000000"},
      {"render --time ''", "", "--time expects a number, got ''"},
      {"render --exposure -1", "", "--exposure must be 'auto' or a number in (0, 1e6], got '-1'"},
      {"render --exposure ''", "", "--exposure must be 'auto' or a number in (0, 1e6], got ''"},
      {"render --seed 99999999999", "", "--seed must be in 0..4294967295"},
      {"render --seed -1", "", "--seed must not be negative, got -1"},
      {"render --seed ''", "", "--seed expects a whole number, got ''"},
      {"render --seed 1e12", "", "--seed expects a whole number, got '1e12'"},
      {"render --out ''", "", "--out must name a file"},
      {"render --out {out}", "", "--out must name a file, got '"},
      {"render --out {out}/", "", "--out must name a file, got '"},
      {"render --out {out}/no_such_dir/r.png", "", "cannot write '", 1},
      {"render --preset nosuch", "", "unknown planet preset 'nosuch'"},
      {"render --preset {h}/garbage.bin --out {out}/r.png", "", "garbage.bin:1:1: not"},
      {"render --preset {h}/latin1.toml --out {out}/r.png", "", "latin1.toml:2:12: not UTF-8 text"},
      {"render --preset {h}/truncated.toml --out {out}/r.png", "", "truncated.toml:2:"},
      {"render --preset {h}/empty.toml --out {out}/r.png", "", "empty.toml: empty document"},
      {"render --preset {h}/dir.toml --out {out}/r.png", "", "dir.toml': Is a directory"},
      {"render --preset {h}/deep.toml --out {out}/r.png", "", "deep.toml:1: a key path of 40001 parts"},
      {"render --preset {h}/huge.toml --out {out}/r.png", "", "huge.toml: too large"},
      {"render --frobnicate", "", "--frobnicate"},
      // planet view (every check comes before a window opens)
      {"view --size 0x0", "", "--size 0x0 is outside 1x1 .. 8192x8192"},
      {"view --terrain-shading FORWARD", "", "--terrain-shading must be forward or deferred, got 'FORWARD'"},
      {"view --size 100000x100000", "", "--size 100000x100000 is outside"},
      {"view --size ''", "", "--size expects WIDTHxHEIGHT in pixels, got ''"},
      {"view --vsync maybe", "", "--vsync must be 'on' or 'off', got 'maybe'"},
      {"view --scene system --travel Pluto", "", "scene 'Three worlds' has no body 'Pluto'"},
      {"view --scene system --camera Moon:0,0,1 --travel Moon", "",
       "--travel Moon names the body the camera starts on"},
      {"view --travel Terra", "", "--travel needs --scene (it names a body of the scene)"},
      {"view --scene system --path x.path", "", "--path does not apply to --scene"},
      {"view --scene system --time-scale -1", "", "--time-scale must be in [0, 1e6], got -1"},
      {"view --scene system --time nan", "", "--time must be a number of seconds within"},
      {"view --scene nowhere.toml", "", "nowhere.toml"},
      {"view --vsync ''", "", "--vsync must be 'on' or 'off', got ''"},
      {"view --quality best", "", "unknown quality 'best'"},
      {"view --quality ''", "", "unknown quality ''"},
      {"view --frames -1", "", "--frames must not be negative, got -1"},
      {"view --frames 1e12", "", "--frames expects a whole number, got '1e12'"},
      {"view --frames ''", "", "--frames expects a whole number, got ''"},
      {"view --frames 4294967295", "", "--frames must be at most 100000000, got 4294967295"},
      {"view --frames 5000000000", "", "--frames = 5000000000"},
      {"view --fov nan", "", "--fov must be in (0, 179] degrees, got nan"},
      {"view --fov ''", "", "--fov expects a number, got ''"},
      {"view --camera 1,2,nan", "", "'nan' is not a finite number"},
      {"view --camera ''", "", "camera '': '' is not a finite number"},
      {"view --sun ''", "", "sun '': '' is not a finite number"},
      {"view --preset nosuch", "", "unknown planet preset 'nosuch'"},
      {"view --preset {h}/garbage.bin", "", "garbage.bin:1:1: not"},
      {"view --preset {h}/latin1.toml", "", "latin1.toml:2:12: not UTF-8 text"},
      {"view --preset {h}/truncated.toml", "", "truncated.toml:2:"},
      {"view --preset {h}/empty.toml", "", "empty.toml: empty document"},
      {"view --preset {h}/dir.toml", "", "dir.toml': Is a directory"},
      {"view --preset {h}/deep.toml", "", "deep.toml:1: a key path of 40001 parts"},
      {"view --path /nonexistent/path.txt", "", "cannot read '/nonexistent/path.txt'"},
      {"view --path ''", "", "--path must name a file"},
      {"view --path {h}/garbage.bin", "", "garbage.bin:1: '"},
      {"view --path {h}/latin1.path", "", "latin1.path:2: '?-80' is not a number"},
      {"view --path {h}/nul.path", "", "nul.path:2: '?' is not a number"},
      {"view --path {h}/truncated.path", "", "truncated.path:2: '1e' is not a number"},
      {"view --path {h}/empty.path", "", "empty.path: a camera path needs at least 2 keys, got 0"},
      // planet stats (no Vulkan; every check before the heights are evaluated)
      {"stats --size 0x0", "", "--size 0x0 is outside 1x1 .. 8192x4096"},
      {"stats --size 8193x4096", "", "--size 8193x4096 is outside 1x1 .. 8192x4096"},
      {"stats --size 256", "", "--size expects WIDTHxHEIGHT in pixels, got '256'"},
      {"stats --size ''", "", "--size expects WIDTHxHEIGHT in pixels, got ''"},
      {"stats --size -5x3", "", "--size expects WIDTHxHEIGHT in pixels, got '-5x3'"},
      {"stats --size 64x", "", "--size expects WIDTHxHEIGHT in pixels, got '64x'"},
      {"stats --seed 99999999999", "", "--seed must be in 0..4294967295, got 99999999999"},
      {"stats --seed -1", "", "--seed must not be negative, got -1"},
      {"stats --seed many", "", "--seed expects a whole number, got 'many'"},
      {"stats --preset nosuch", "", "unknown planet preset 'nosuch'"},
      {"stats --preset {h}/garbage.bin", "", "garbage.bin:1:1: not"},
      {"stats --preset {h}/dir.toml", "", "dir.toml': Is a directory"},
      {"stats --json ''", "", "--json must name a file"},
      {"stats --json {out}", "", "--json must name a file, got '"},
      {"stats --json {out}/no_such_dir/s.json", "", "cannot write '{out}/no_such_dir/s.json'", 1},
      {"stats --frobnicate", "", "--frobnicate"},
      {"view --path {h}/hugetime.path", "", "hugetime.path:2: time_s 1e+300 is outside"},
      {"view --path {h}/dir.toml", "", "dir.toml': Is a directory"},
      {"view --screenshot /tmp/", "", "--screenshot must name a file, got '/tmp/'"},
      {"view --screenshot ''", "", "--screenshot must name a file"},
      {"view --screenshot {out}", "", "--screenshot must name a file, got '"},
      {"view --screenshot {out}/no_such_dir/s.png", "", "cannot write '", 1},
      {"view --size 0x0 --screenshot {out}/s.png", "", "--size 0x0 is outside"},
      {"view --frobnicate", "", "--frobnicate"},
      // planet itself
      {"frobnicate", "", "frobnicate"},
      {"", "", "a command is required"},
  };
  int index = 0;
  for (const Case& c : cases) {
    // A fresh folder per case for the outputs it names: it must stay empty (no file, no temporary).
    const std::filesystem::path out = tempDir() / ("out" + std::to_string(index++));
    std::filesystem::create_directories(out);
    const std::string args = expand(c.args, out.string());
    const CommandResult run = planetWithoutDriver(args, c.input);
    EXPECT_EQ(run.exitCode, c.exitCode) << args << "\n" << run.err;
    EXPECT_EQ(lineCount(run.err), 1u) << args << "\n" << run.err;
    EXPECT_NE(run.err.find(expand(c.mustContain, out.string())), std::string::npos) << args << "\n" << run.err;
    EXPECT_EQ(run.out, "") << args << ": nothing may be printed on an error";
    EXPECT_TRUE(std::filesystem::is_empty(out)) << args << ": left a file behind";
    std::filesystem::remove_all(out);
  }
}

// The point stream's friendly forms: CRLF line ends, a byte order mark, '+' signs, comments
// after a point and a last line without a newline give the same values as plain lines.
TEST(Cli, NoiseReadsCrlfByteOrderMarksCommentsAndALastLineWithoutNewline) {
  CommandResult plain = planet("noise --type fbm --seed 3", "0.1 0.2 0.3\n1.5 -2.25 3.75\n4 5 6\n");
  ASSERT_EQ(plain.exitCode, 0) << plain.err;
  CommandResult friendly =
      planet("noise --type fbm --seed 3", "\xef\xbb\xbf+0.1 0.2 0.3 # first\r\n1.5, -2.25, 3.75\r\n\r\n4 5 6");
  ASSERT_EQ(friendly.exitCode, 0) << friendly.err;
  EXPECT_EQ(friendly.out, plain.out);
  EXPECT_EQ(lineCount(plain.out), 3u);
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

TEST(Cli, GeneratorTypesPrintTheirValuesAndTheGpuAgrees) {
  std::string input;
  for (int i = 0; i < 300; ++i)
    input += std::to_string(i * 0.37 - 50) + " " + std::to_string(std::fmod(i * 7.1, 40.0) - 20) + " " +
             std::to_string(i * 0.11 - 15) + "\n";
  // One fault: two heights only, +r on one side of its circle and -r on the other.
  CommandResult one = planet("noise --type faults --count 1 --seed 3", input);
  ASSERT_EQ(one.exitCode, 0) << one.err;
  std::set<std::string> distinct;
  std::istringstream lines(one.out);
  for (std::string line; std::getline(lines, line);) distinct.insert(line);
  ASSERT_EQ(distinct.size(), 2u) << one.out;
  EXPECT_EQ(std::stod(*distinct.begin()), -std::stod(*distinct.rbegin()));
  for (const char* args : {"--type faults --count 50 --width 0.1", "--type mpd --levels 12 --multifractal",
                           "--type mpd_ico --levels 20 --H 0.7"}) {
    CommandResult cpu = planet(std::string("noise ") + args, input);
    ASSERT_EQ(cpu.exitCode, 0) << cpu.err;
    EXPECT_EQ(lineCount(cpu.out), 300u);
    CommandResult gpu = planet(std::string("noise ") + args + " --backend gpu", input);
    if (noDevice(gpu)) GTEST_SKIP() << "no Vulkan device on this machine";
    ASSERT_EQ(gpu.exitCode, 0) << gpu.err;
    EXPECT_EQ(gpu.out, cpu.out) << args << ": lavapipe must agree bit for bit";
  }
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
  // The mesh follows the image (36 lines: the floors of meshForImage).
  EXPECT_NE(run.out.find("mesh: 2 rings per level x 16 vertices per ring (auto for 36 lines at 60 degrees)\n"),
            std::string::npos)
      << run.out;
  EXPECT_NE(run.out.find("metres per vertex at the nadir: "), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("triangles drawn: "), std::string::npos) << run.out;
  for (const char* pass : {"GPU time per pass: sky tables ", " heights ", " terrain ", " sky ", " tonemap "})
    EXPECT_NE(run.out.find(pass), std::string::npos) << pass << "\n" << run.out;
  // 5 km below the reference sphere is below any ground: raised to eye height, with a warning.
  EXPECT_NE(run.err.find("warning: camera altitude -5000.00 m is below the ground"), std::string::npos) << run.err;
}

TEST(Cli, RenderSceneFromTheMoonLooksAtTerra) {
  const std::filesystem::path png = tempDir() / "scene.png";
  CommandResult run = planet("render --scene system --camera Moon:58,-134.8,-5000 --look-at Terra --time 30000 "
                             "--size 64x36 --out " + png.string());
  if (noDevice(run)) GTEST_SKIP() << run.err;
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(readFile(png).substr(1, 3), "PNG");
  EXPECT_NE(run.out.find("scene 'Three worlds' at t = 30000 s"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("camera: on Moon at lat 58.0000 lon -134.8000"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("(1.70 m above the ground)"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("overhead on Moon: Giant at lat "), std::string::npos) << run.out;
  EXPECT_NE(run.out.find(" rings "), std::string::npos) << run.out;
  EXPECT_NE(run.err.find("warning: the camera was below the ground of Moon"), std::string::npos) << run.err;
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
  // 2 hashes x (8 fractals x 3 parameter sets + simplex x 2), and with the fast hash only faults x 2
  // and mpd, mpd_ico x 3.
  ASSERT_EQ(j["cases"].size(), 60u);
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
  checkSummary(j["prepare_ms"], "prepare_ms ");
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
    // The CPU's preparation comes before the submission, outside the GPU's span.
    EXPECT_GT(f["prepare_ms"].get<double>(), 0.0) << f.dump();
    EXPECT_LE(f["prepare_ms"].get<double>(), f["cpu_ms"].get<double>() + 1e-6) << f.dump();
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

// With two frames in flight, as the viewer draws, each timed frame is prepared while the frame
// before it executes and is timed from that frame's end to its own on the GPU's clock: the
// interval holds the frame's GPU span (lavapipe runs the queue's frames one after the other;
// a GPU may start a frame's first commands before the one before has drained, so a little less).
TEST(Cli, BenchWithTwoFramesInFlightTimesEachFrameBehindTheOneBefore) {
  const std::filesystem::path json = tempDir() / "in_flight.json";
  CommandResult run = planet("bench --size 64x36 --frames 3 --warmup 0 --in-flight 2 --path " + shortPath().string() +
                             " --json " + json.string());
  if (noDevice(run)) GTEST_SKIP() << "no Vulkan device on this machine";
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_NE(run.out.find("2 frames in flight, as the viewer draws"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("frame (GPU clock, end to end)"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("GPU waiting (frame - GPU)"), std::string::npos) << run.out;
  const nlohmann::json j = nlohmann::json::parse(readFile(json));
  EXPECT_EQ(j["frames_in_flight"].get<int>(), 2);
  ASSERT_EQ(j["per_frame"].size(), 3u);
  for (const auto& f : j["per_frame"]) {
    double sum = 0.0;
    for (const auto& [name, ms] : f["passes"].items()) sum += ms.get<double>();
    EXPECT_GT(sum, 0.0) << f.dump();
    EXPECT_LE(sum, f["gpu_ms"].get<double>() + 1e-6) << f.dump();
    EXPECT_GE(f["frame_ms"].get<double>(), 0.9 * f["gpu_ms"].get<double>()) << f.dump();
    EXPECT_LT(f["frame_ms"].get<double>(), 60'000.0) << f.dump();  // two frames' clocks, not an epoch
    EXPECT_GT(f["prepare_ms"].get<double>(), 0.0) << f.dump();
    EXPECT_GT(f["triangles"].get<int64_t>(), 0);
  }
}

// The lead-in frame makes a timed frame do what a frame of a real-time flight does: over a
// low traverse, timed frames 5 s of flight apart move most patch levels (rebuilt),
// but after a lead-in 1/60 s before, a frame rebuilds only the levels that one frame's
// movement (7 m) recentred.
TEST(Cli, BenchLeadInFramesRebuildWhatARealTimeFrameRebuilds) {
  const std::filesystem::path path = tempDir() / "traverse_path.txt";
  std::ofstream(path) << "0 33.8 -90 300 60 -20\n10 33.82 -89.96 300 60 -20\n";  // ~400 m/s
  auto rebuilt = [&](const std::string& flight) {
    const std::filesystem::path json = tempDir() / (flight.empty() ? "lead_in.json" : "no_lead_in.json");
    CommandResult run = planet("bench --size 64x36 --frames 3 --warmup 0 --path " + path.string() + flight +
                               " --json " + json.string());
    if (noDevice(run)) return std::vector<uint32_t>{};
    EXPECT_EQ(run.exitCode, 0) << run.err;
    EXPECT_NE(run.out.find(flight.empty() ? "follows an untimed one 1/60 s of flight before it" : "no lead-in frames"),
              std::string::npos)
        << run.out;
    const nlohmann::json j = nlohmann::json::parse(readFile(json));
    EXPECT_EQ(j["flight_fps"].get<double>(), flight.empty() ? 60.0 : 0.0);
    // Apart: the levels each frame had to change, those it rebuilt and those the texel budget
    // left for later frames (TerrainSettings::patchTexelsPerFrame: a recentre step's texels a
    // frame). Real time: the levels it rebuilt (the finest's strips may take two frames).
    std::vector<uint32_t> levels;
    for (const auto& f : j["per_frame"])
      levels.push_back(f["patch_levels_rebuilt"].get<uint32_t>() +
                       (flight.empty() ? 0u : f["patch_levels_deferred"].get<uint32_t>()));
    return levels;
  };
  const std::vector<uint32_t> apart = rebuilt(" --flight-fps 0");
  if (apart.empty()) GTEST_SKIP() << "no Vulkan device on this machine";
  const std::vector<uint32_t> realTime = rebuilt("");
  ASSERT_EQ(apart.size(), 3u);
  ASSERT_EQ(realTime.size(), 3u);
  // The first frame of either run builds every level from nothing; after it the frames apart
  // rebuild the levels whose recentre step is under 2 km (measured: 2 and 5 of the six), the
  // real-time ones at most the finest.
  for (size_t i = 1; i < 3; ++i) {
    EXPECT_GE(apart[i], 2u) << "frame " << i;
    EXPECT_LE(realTime[i], 1u) << "frame " << i;
  }
}

// --no-lights (issue 14): render's night side from orbit has its cities with the flag left out
// and is dark with it (the middle of the disc, all of it more than 18° past the terminator: at
// most 3 of 255); bench reports the flag; view and bench offer it.
TEST(Cli, NoLightsLeavesOutTheCityLights) {
  const std::filesystem::path on = tempDir() / "on.png", off = tempDir() / "off.png";
  const std::string night = "render --preset earth --size 160x90 --camera 20,-30,1.2e7,0,-90 --sun 135,-60 --out ";
  CommandResult lit = planet(night + on.string());
  if (noDevice(lit)) GTEST_SKIP() << lit.err;
  ASSERT_EQ(lit.exitCode, 0) << lit.err;
  CommandResult dark = planet(night + off.string() + " --no-lights");
  ASSERT_EQ(dark.exitCode, 0) << dark.err;
  const planet::Rgba8Image litImage = planet::readPng(on.string()), darkImage = planet::readPng(off.string());
  int litPixels = 0, darkMax = 0;
  for (uint32_t y = 30; y < 60; ++y)
    for (uint32_t x = 65; x < 95; ++x) {  // the disc's middle: about 30 pixels across of its 60
      const size_t i = (size_t(y) * 160 + x) * 4;
      const int a = std::max({litImage.pixels[i], litImage.pixels[i + 1], litImage.pixels[i + 2]});
      const int b = std::max({darkImage.pixels[i], darkImage.pixels[i + 1], darkImage.pixels[i + 2]});
      litPixels += a > b + 8 ? 1 : 0;
      darkMax = std::max(darkMax, b);
    }
  EXPECT_GE(litPixels, 10);
  EXPECT_LE(darkMax, 3);

  const std::filesystem::path json = tempDir() / "bench.json";
  CommandResult bench = planet("bench --size 32x18 --frames 1 --warmup 0 --no-patches --no-lights --path " +
                               shortPath().string() + " --json " + json.string());
  ASSERT_EQ(bench.exitCode, 0) << bench.err;
  EXPECT_NE(bench.out.find("without lights"), std::string::npos) << bench.out;
  EXPECT_FALSE(nlohmann::json::parse(readFile(json))["lights"].get<bool>());
  for (const char* command : {"render", "bench", "view"}) {
    CommandResult help = planet(std::string(command) + " --help");
    EXPECT_NE(help.out.find("--no-lights"), std::string::npos) << command << "\n" << help.out;
  }
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
