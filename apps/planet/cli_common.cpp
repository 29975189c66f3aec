#include "cli_common.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstring>
#include <filesystem>
#include <utility>

#include "core/error.h"
#include "core/log.h"
#include "planet/planet_description.h"
#include "render/renderer.h"
#include "render/view_quality.h"

namespace planet::cli {

std::unique_ptr<vk::Context> openContext(const GlobalOptions& options) {
  vk::ContextOptions contextOptions = vk::contextOptionsFromEnvironment();
  if (options.validation) {
    contextOptions.validation = true;
    contextOptions.synchronizationValidation = true;
  }
  contextOptions.deviceName = options.device;
  return vk::createContext(contextOptions);
}

namespace {

// "AxB" as two unsigned decimal counts (--size, --mesh): false unless the whole text is that.
bool parseCountPair(std::string_view text, uint32_t& first, uint32_t& second) {
  const size_t x = text.find('x');
  auto number = [](std::string_view part, uint32_t& value) {
    auto [ptr, ec] = std::from_chars(part.data(), part.data() + part.size(), value);
    return !part.empty() && ec == std::errc() && ptr == part.data() + part.size();
  };
  return x != std::string_view::npos && number(text.substr(0, x), first) && number(text.substr(x + 1), second);
}

}  // namespace

void parseSize(const std::string& text, uint32_t& width, uint32_t& height, uint32_t maxWidth, uint32_t maxHeight) {
  if (!parseCountPair(text, width, height))
    throw UsageError("--size expects WIDTHxHEIGHT in pixels, got '" + text + "'");
  if (width == 0 || height == 0 || width > maxWidth || height > maxHeight)
    throw UsageError(fmt::format("--size {} is outside 1x1 .. {}x{}", text, maxWidth, maxHeight));
}

void parseSize(const std::string& text, uint32_t& width, uint32_t& height) {
  parseSize(text, width, height, kRenderMaxSize, kRenderMaxSize);
}

void checkFieldOfView(double degrees) {
  if (!(degrees > 0.0 && degrees <= kRenderMaxFovDeg))
    throw UsageError(fmt::format("--fov must be in (0, {}] degrees, got {}", kRenderMaxFovDeg, degrees));
}

namespace {

// A leading '+' is accepted (std::from_chars does not take one).
std::string_view withoutPlus(std::string_view text) {
  return text.size() > 1 && text[0] == '+' ? text.substr(1) : text;
}

}  // namespace

ExposureChoice parseExposure(const std::string& text) {
  if (text == "auto") return {true, 0.0};
  const std::string_view digits = withoutPlus(text);
  double value = 0.0;
  auto [ptr, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  const bool number = !digits.empty() && ec == std::errc() && ptr == digits.data() + digits.size();
  if (!number || !(value > 0.0 && value <= kMaxExposure))
    throw UsageError(fmt::format("--exposure must be 'auto' or a number in (0, 1e6], got '{}'", text));
  return {false, value};
}

namespace {

std::string withoutControlCharacters(std::string text) {
  for (char& c : text)
    if (uint8_t(c) < 0x20 || c == 0x7f) c = '?';
  return text;
}

// The check of one numeric option's text. CLI11 2.1 reads '' as 0 (or as "not given" for an
// optional), an unsigned '-1' as 2^64 - 1, an overflowing value as the type's largest and '010'
// as octal 8, so that the command's range message would name a value the user never gave; each
// of those is a UsageError here, quoting the text. Integers are rewritten in plain decimal for
// CLI11 to convert; the range of the option's own type and the command's checks come after.
template <typename Integer>
CLI::Validator integerText(const std::string& name) {
  return CLI::Validator(
      [name](std::string& text) {
        if (std::is_unsigned_v<Integer> && text.starts_with('-'))
          throw UsageError(fmt::format("{} must not be negative, got {}", name, text));
        const std::string_view digits = withoutPlus(text);
        Integer value = 0;
        auto [ptr, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
        if (ec == std::errc::result_out_of_range)
          throw UsageError(fmt::format("{} is out of range, got {}", name, text));
        if (digits.empty() || ec != std::errc() || ptr != digits.data() + digits.size())
          throw UsageError(fmt::format("{} expects a whole number, got '{}'", name, text));
        text = std::to_string(value);
        return std::string();
      },
      "");
}

CLI::Validator realText(const std::string& name) {
  return CLI::Validator(
      [name](std::string& text) {
        const std::string_view digits = withoutPlus(text);
        double value = 0.0;
        auto [ptr, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
        if (ec == std::errc::result_out_of_range)
          throw UsageError(fmt::format("{} is out of range, got {}", name, text));
        if (digits.empty() || ec != std::errc() || ptr != digits.data() + digits.size())
          throw UsageError(fmt::format("{} expects a number, got '{}'", name, text));
        return std::string();
      },
      "");
}

}  // namespace

UsageError::UsageError(const std::string& message) : std::runtime_error(withoutControlCharacters(message)) {}

void checkNumbersAsText(CLI::App& command) {
  for (CLI::Option* option : command.get_options()) {
    // The type names CLI11 gives int, unsigned and floating-point options (and optionals of them).
    const std::string type = option->get_type_name();
    if (type == "INT")
      option->check(integerText<int64_t>(option->get_name()));
    else if (type == "UINT")
      option->check(integerText<uint64_t>(option->get_name()));
    else if (type == "FLOAT")
      option->check(realText(option->get_name()));
  }
}

ProgressLine::ProgressLine(std::string label, std::string unit)
    : label_(std::move(label)),
      unit_(std::move(unit)),
      interactive_(::isatty(STDERR_FILENO)),
      start_(std::chrono::steady_clock::now()) {
  lastLine_ = start_;
}

ProgressLine::~ProgressLine() {
  if (interactive_ && printed_) std::fputs("\n", stderr);
}

void ProgressLine::operator()(size_t done, size_t total) {
  const auto now = std::chrono::steady_clock::now();
  const auto every = interactive_ ? std::chrono::milliseconds(200) : std::chrono::milliseconds(10'000);
  const bool last = done == total;
  if (now - lastLine_ < every && !(last && printed_)) return;
  lastLine_ = now;
  printed_ = true;
  const double fraction = total > 0 ? double(done) / double(total) : 1.0;
  const double seconds = std::chrono::duration<double>(now - start_).count();
  constexpr int kBarWidth = 30;
  const int filled = int(fraction * kBarWidth);
  const std::string bar = std::string(size_t(filled), '#') + std::string(size_t(kBarWidth - filled), '.');
  const std::string left =
      done > 0 && !last ? fmt::format(", ~{:.0f} s left", seconds * (1.0 - fraction) / fraction) : "";
  const std::string line = fmt::format("{} [{}] {:3.0f} %  {} of {} {}  {:.1f} s{}", label_, bar, 100.0 * fraction,
                                       done, total, unit_, seconds, left);
  std::fprintf(stderr, interactive_ ? "\r%s   " : "%s\n", line.c_str());
  std::fflush(stderr);
}

void checkOutputFile(const std::string& option, const std::string& path) {
  if (path.empty()) throw UsageError(option + " must name a file");
  std::error_code ignored;  // a path that cannot be examined is reported by the parent's check
  if (path.back() == '/' || std::filesystem::is_directory(path, ignored))
    throw UsageError(fmt::format("{} must name a file, got '{}'", option, path));
  // The directory the file (and its temporary twin) goes into must exist and take new files.
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  const std::string directory = parent.empty() ? "." : parent.string();
  struct stat info {};
  int error = 0;
  if (::stat(directory.c_str(), &info) != 0)
    error = errno;
  else if (!S_ISDIR(info.st_mode))
    error = ENOTDIR;
  else if (::access(directory.c_str(), W_OK | X_OK) != 0)
    error = errno;
  if (error != 0) throw Error(fmt::format("cannot write '{}': {}", path, std::strerror(error)));
}

void applySeedOffset(PlanetDescription& planet, uint64_t seed) {
  if (seed > 0xffffffffull) throw UsageError(fmt::format("--seed must be in 0..4294967295, got {}", seed));
  for (NoiseLayer& layer : planet.layers)
    layer.noise.seed = uint32_t((uint64_t(layer.noise.seed) + seed) & 0xffffffffu);
}

int finishWithValidation(const vk::Context& context, int exitCode) {
  if (context.validation && context.validationMessageCount() > 0) {
    logError("{} Vulkan validation message(s) were reported (see above)", context.validationMessageCount());
    return kExitFailure;
  }
  return exitCode;
}

SceneCamera parseSceneCamera(const SceneDescription& scene, const std::string& text) {
  const size_t colon = text.find(':');
  if (colon == std::string::npos)
    throw Error(fmt::format("--camera with --scene is BODY:LAT,LON,ALT[,HEADING,PITCH], got '{}'", text));
  SceneCamera camera;
  camera.body = sceneBodyIndex(scene, text.substr(0, colon));
  camera.pose = parseCameraPose(std::string_view(text).substr(colon + 1));
  return camera;
}

void checkSceneExcludes(const CLI::App& command) {
  if (command.count("--preset"))
    throw UsageError("--preset and --scene exclude each other (a scene names its presets)");
  if (command.count("--sun"))
    throw UsageError("--sun does not apply to --scene: the scene's sun lights it from its origin");
}

CLI::Option* addSkyModeOption(CLI::App& sub, std::string& mode) {
  return sub
      .add_option("--sky", mode,
                  "tables: the atmosphere from this frame's sky-view table and aerial-perspective volume; reference: "
                  "every pixel's ray marched through the air (slow; what the tables are tested against)")
      ->capture_default_str();
}

SkyMode checkSkyMode(const std::string& mode) {
  if (mode != "tables" && mode != "reference")
    throw UsageError(fmt::format("--sky must be tables or reference, got '{}'", mode));
  return parseSkyMode(mode);
}

CLI::Option* addTerrainShadingOption(CLI::App& sub, std::string& shading) {
  return sub
      .add_option("--terrain-shading", shading,
                  "forward: the ground shaded in the draw's fragment shader; deferred: the draw writes a G-buffer "
                  "and a compute pass shades each pixel once (one body only; the same picture)")
      ->capture_default_str();
}

bool checkTerrainShading(const std::string& shading) {
  if (shading != "forward" && shading != "deferred")
    throw UsageError(fmt::format("--terrain-shading must be forward or deferred, got '{}'", shading));
  return shading == "deferred";
}

CLI::Option* addMeshOption(CLI::App& sub, std::string& text) {
  return sub
      .add_option("--mesh", text,
                  fmt::format("auto: the clipmap's triangles the same size on screen at any image size ({}x{} at "
                              "{} lines and a {:g} degree field of view, scaled with the pixels per radian); or "
                              "RINGSxVERTICES: rings per level x vertices per ring",
                              TerrainSettings{}.mesh.ringsPerLevel, TerrainSettings{}.mesh.numPhi, kMeshReferenceLines,
                              kMeshReferenceFovDeg))
      ->capture_default_str();
}

std::optional<ClipmapParams> parseMesh(const std::string& text) {
  if (text == "auto") return std::nullopt;
  ClipmapParams mesh = TerrainSettings{}.mesh;
  if (!parseCountPair(text, mesh.ringsPerLevel, mesh.numPhi))
    throw UsageError(fmt::format("--mesh expects auto or RINGSxVERTICES (e.g. 16x128), got '{}'", text));
  if (mesh.ringsPerLevel < 1 || mesh.ringsPerLevel > kClipmapMaxRingsPerLevel)
    throw UsageError(fmt::format("--mesh {}: rings per level must be in 1..{}, got {}", text, kClipmapMaxRingsPerLevel,
                                 mesh.ringsPerLevel));
  if (mesh.numPhi < kClipmapMinNumPhi || mesh.numPhi > kClipmapMaxNumPhi)
    throw UsageError(fmt::format("--mesh {}: vertices per ring must be in {}..{}, got {}", text, kClipmapMinNumPhi,
                                 kClipmapMaxNumPhi, mesh.numPhi));
  return mesh;
}

ClipmapParams meshFor(const std::optional<ClipmapParams>& fixed, uint32_t imageHeight, double fovYDeg) {
  return fixed ? *fixed : meshForImage(TerrainSettings{}.mesh, imageHeight, fovYDeg);
}

}  // namespace planet::cli
