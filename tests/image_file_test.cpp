// PNG files (round trip, deterministic bytes, one-line errors naming the path, nothing left
// behind on failure), PSNR and difference images, and the golden-image test helper.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <unistd.h>

#include "core/image_file.h"
#include "image_compare.h"
#include "test_support.h"

namespace planet {
namespace {

namespace fs = std::filesystem;
using test::errorOf;

// A deterministic pattern that uses every channel, alpha included (0 and 255 among them).
Rgba8Image patternImage(uint32_t width, uint32_t height, uint32_t seed = 1) {
  Rgba8Image image{width, height, std::vector<uint8_t>(size_t(width) * height * 4)};
  uint32_t state = seed * 2654435761u + 12345u;
  for (uint8_t& value : image.pixels) {
    state = state * 1664525u + 1013904223u;
    value = uint8_t(state >> 24);
  }
  return image;
}

Rgba8Image solidImage(uint32_t width, uint32_t height, uint8_t r, uint8_t g, uint8_t b, uint8_t a = 255) {
  Rgba8Image image{width, height, std::vector<uint8_t>(size_t(width) * height * 4)};
  for (size_t i = 0; i < image.pixels.size(); i += 4) {
    image.pixels[i] = r;
    image.pixels[i + 1] = g;
    image.pixels[i + 2] = b;
    image.pixels[i + 3] = a;
  }
  return image;
}

std::vector<uint8_t> readBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void writeBytes(const fs::path& path, const std::vector<uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

std::vector<std::string> filesIn(const fs::path& dir) {
  std::vector<std::string> names;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename());
  std::sort(names.begin(), names.end());
  return names;
}

// A minimal PNG written by hand (one stored, uncompressed deflate block), to check that the
// reader converts what the writer never produces: grey, grey + alpha, RGB, 16-bit.
std::vector<uint8_t> handMadePng(uint32_t width, uint32_t height, uint8_t bitDepth, uint8_t colourType,
                                 const std::vector<uint8_t>& rows) {
  auto crc32 = [](const uint8_t* data, size_t size) {
    uint32_t crc = 0xFFFFFFFFu;
    for (size_t i = 0; i < size; ++i) {
      crc ^= data[i];
      for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
    }
    return ~crc;
  };
  auto put32 = [](std::vector<uint8_t>& out, uint32_t v) {
    out.insert(out.end(), {uint8_t(v >> 24), uint8_t(v >> 16), uint8_t(v >> 8), uint8_t(v)});
  };
  std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  auto chunk = [&](const char* type, const std::vector<uint8_t>& data) {
    put32(png, uint32_t(data.size()));
    std::vector<uint8_t> typed(type, type + 4);
    typed.insert(typed.end(), data.begin(), data.end());
    png.insert(png.end(), typed.begin(), typed.end());
    put32(png, crc32(typed.data(), typed.size()));
  };
  std::vector<uint8_t> header;
  put32(header, width);
  put32(header, height);
  header.insert(header.end(), {bitDepth, colourType, 0, 0, 0});
  chunk("IHDR", header);
  // zlib stream: header, one final stored block (rows must be < 64 KiB), Adler-32.
  std::vector<uint8_t> zlib = {0x78,
                               0x01,
                               0x01,
                               uint8_t(rows.size()),
                               uint8_t(rows.size() >> 8),
                               uint8_t(~rows.size()),
                               uint8_t(~rows.size() >> 8)};
  zlib.insert(zlib.end(), rows.begin(), rows.end());
  uint32_t s1 = 1, s2 = 0;
  for (uint8_t value : rows) {
    s1 = (s1 + value) % 65521u;
    s2 = (s2 + s1) % 65521u;
  }
  put32(zlib, (s2 << 16) | s1);
  chunk("IDAT", zlib);
  chunk("IEND", {});
  return png;
}

// Each test gets an empty directory of its own, and a clean PLANET_UPDATE_GOLDEN.
class ImageFile : public testing::Test {
 protected:
  void SetUp() override {
    const testing::TestInfo* info = testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("planet_image_file_test_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    if (const char* value = std::getenv("PLANET_UPDATE_GOLDEN")) savedUpdate_ = value;
    ::unsetenv("PLANET_UPDATE_GOLDEN");
  }
  void TearDown() override {
    fs::remove_all(dir_);
    if (savedUpdate_) {
      ::setenv("PLANET_UPDATE_GOLDEN", savedUpdate_->c_str(), 1);
    } else {
      ::unsetenv("PLANET_UPDATE_GOLDEN");
    }
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  fs::path dir_;
  std::optional<std::string> savedUpdate_;
};

TEST_F(ImageFile, PngRoundTripKeepsEveryPixelForOddSizes) {
  for (auto [width, height] : {std::pair{1u, 1u}, {3u, 5u}, {5u, 3u}, {17u, 2u}, {64u, 33u}}) {
    SCOPED_TRACE(std::to_string(width) + "x" + std::to_string(height));
    Rgba8Image image = patternImage(width, height, width * 100 + height);
    writePng(path("round_trip.png"), image);
    Rgba8Image back = readPng(path("round_trip.png"));
    EXPECT_EQ(back.width, width);
    EXPECT_EQ(back.height, height);
    EXPECT_EQ(back.pixels, image.pixels);
  }
}

TEST_F(ImageFile, EncodingTwiceGivesIdenticalBytesAndWritePngWritesThem) {
  Rgba8Image image = patternImage(31, 7);
  std::vector<uint8_t> first = encodePng(image);
  EXPECT_EQ(encodePng(image), first);
  writePng(path("a.png"), image);
  writePng(path("b.png"), image);
  EXPECT_EQ(readBytes(path("a.png")), first);
  EXPECT_EQ(readBytes(path("b.png")), first);
}

TEST_F(ImageFile, WritePngToMissingDirectoryThrowsNamingThePathAndLeavesNothing) {
  std::string target = path("no-such-dir/out.png");
  std::string error = errorOf([&] { writePng(target, patternImage(3, 5)); });
  EXPECT_NE(error.find("'" + target + "'"), std::string::npos) << error;
  EXPECT_NE(error.find("No such file or directory"), std::string::npos) << error;
  EXPECT_EQ(error.find('\n'), std::string::npos) << error;
  EXPECT_TRUE(filesIn(dir_).empty());
}

TEST_F(ImageFile, WritePngRejectsBadImagesNamingThePathAndLeavesNothing) {
  std::string target = path("out.png");
  EXPECT_EQ(errorOf([&] { writePng(target, Rgba8Image{}); }), "cannot write '" + target + "': image is empty (0x0)");
  EXPECT_EQ(errorOf([&] {
              writePng(target, Rgba8Image{0, 4, {}});
            }),
            "cannot write '" + target + "': image is empty (0x4)");
  Rgba8Image mismatch = patternImage(3, 5);
  mismatch.pixels.pop_back();
  EXPECT_EQ(errorOf([&] { writePng(target, mismatch); }),
            "cannot write '" + target + "': image of 3x5 needs 60 RGBA bytes, has 59");
  EXPECT_EQ(errorOf([&] { encodePng(mismatch); }), "cannot encode PNG: image of 3x5 needs 60 RGBA bytes, has 59");
  EXPECT_TRUE(filesIn(dir_).empty());
}

TEST_F(ImageFile, WritePngOverADirectoryFailsAtRenameAndRemovesItsTemporaryFile) {
  fs::create_directory(dir_ / "taken");
  std::string error = errorOf([&] { writePng(path("taken"), patternImage(2, 2)); });
  EXPECT_NE(error.find("'" + path("taken") + "'"), std::string::npos) << error;
  EXPECT_EQ(filesIn(dir_), std::vector<std::string>{"taken"});
}

TEST_F(ImageFile, WritePngReplacesAnExistingFileWhole) {
  writePng(path("out.png"), patternImage(9, 9, 1));
  writePng(path("out.png"), patternImage(2, 3, 2));
  EXPECT_EQ(readPng(path("out.png")).pixels, patternImage(2, 3, 2).pixels);
  EXPECT_EQ(filesIn(dir_), std::vector<std::string>{"out.png"});
}

TEST_F(ImageFile, ReadPngOfMissingTextTruncatedOrCorruptFileThrowsNamingThePath) {
  std::string missing = path("missing.png");
  EXPECT_EQ(errorOf([&] { readPng(missing); }), "cannot read '" + missing + "': No such file or directory");

  std::string text = path("text.png");
  writeBytes(text, {'h', 'e', 'l', 'l', 'o', '\n'});
  EXPECT_EQ(errorOf([&] { readPng(text); }), "cannot read '" + text + "': not a PNG file");

  std::string empty = path("empty.png");
  writeBytes(empty, {});
  EXPECT_EQ(errorOf([&] { readPng(empty); }), "cannot read '" + empty + "': not a PNG file");

  std::vector<uint8_t> png = encodePng(patternImage(16, 16));
  std::string truncated = path("truncated.png");
  for (size_t keep : {png.size() / 2, png.size() - 1, size_t(8)}) {
    writeBytes(truncated, std::vector<uint8_t>(png.begin(), png.begin() + ptrdiff_t(keep)));
    EXPECT_EQ(errorOf([&] { readPng(truncated); }),
              "cannot read '" + truncated + "': truncated PNG (it does not end with IEND)")
        << "kept " << keep << " of " << png.size() << " bytes";
  }

  // Signature and IEND, nothing between: stb_image's reason is passed on.
  std::string hollow = path("hollow.png");
  std::vector<uint8_t> bytes(png.begin(), png.begin() + 8);
  bytes.insert(bytes.end(), png.end() - 12, png.end());
  writeBytes(hollow, bytes);
  std::string error = errorOf([&] { readPng(hollow); });
  EXPECT_EQ(error.rfind("cannot read '" + hollow + "': corrupt PNG (", 0), 0u) << error;

  EXPECT_EQ(errorOf([&] { readPng(dir_.string()); }), "cannot read '" + dir_.string() + "': Is a directory");

  // A name with a newline and an escape (a file may be called that) is shown with '?' for
  // each, so the message stays one line and cannot drive the terminal.
  std::string odd = path("two\nlines\x1b[2J.png");
  writeBytes(odd, {'x'});
  EXPECT_EQ(errorOf([&] { readPng(odd); }), "cannot read '" + path("two?lines?[2J.png") + "': not a PNG file");
}

TEST_F(ImageFile, ReadPngConvertsGreyGreyAlphaAndRgbToRgba) {
  // Each row starts with its filter byte (0: none).
  writeBytes(path("grey.png"), handMadePng(2, 1, 8, 0, {0, 10, 200}));
  EXPECT_EQ(readPng(path("grey.png")).pixels, (std::vector<uint8_t>{10, 10, 10, 255, 200, 200, 200, 255}));

  writeBytes(path("grey_alpha.png"), handMadePng(1, 2, 8, 4, {0, 7, 8, 0, 9, 0}));
  EXPECT_EQ(readPng(path("grey_alpha.png")).pixels, (std::vector<uint8_t>{7, 7, 7, 8, 9, 9, 9, 0}));

  writeBytes(path("rgb.png"), handMadePng(2, 1, 8, 2, {0, 1, 2, 3, 4, 5, 6}));
  Rgba8Image rgb = readPng(path("rgb.png"));
  EXPECT_EQ(rgb.width, 2u);
  EXPECT_EQ(rgb.height, 1u);
  EXPECT_EQ(rgb.pixels, (std::vector<uint8_t>{1, 2, 3, 255, 4, 5, 6, 255}));
}

TEST_F(ImageFile, ReadPngRejects16BitFiles) {
  std::string wide = path("wide.png");
  writeBytes(wide, handMadePng(1, 1, 16, 2, {0, 1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(errorOf([&] { readPng(wide); }), "cannot read '" + wide + "': 16-bit PNG (only 8-bit is supported)");
}

// Every 16-bit value, in rows that exercise each PNG filter (smooth ramps, noise, constant rows).
Grey16Image pattern16(uint32_t width, uint32_t height) {
  Grey16Image image{width, height, std::vector<uint16_t>(size_t(width) * height)};
  uint32_t state = 7;
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    state = state * 1664525u + 1013904223u;
    const size_t row = i / width;
    image.pixels[i] = row % 3 == 0 ? uint16_t(i) : row % 3 == 1 ? uint16_t(state >> 16) : uint16_t(row * 257);
  }
  return image;
}

TEST_F(ImageFile, Png16RoundTripKeepsEveryValueAndIsDeterministic) {
  for (auto [width, height] : {std::pair{256u, 256u}, {1u, 1u}, {3u, 7u}, {1000u, 3u}}) {
    SCOPED_TRACE(std::to_string(width) + "x" + std::to_string(height));
    const Grey16Image image = pattern16(width, height);
    const std::vector<uint8_t> png = encodePng16(image);
    EXPECT_EQ(encodePng16(image), png);
    writeBytes(path("grey16.png"), png);
    const Grey16Image back = readPng16(path("grey16.png"));
    EXPECT_EQ(back.width, width);
    EXPECT_EQ(back.height, height);
    EXPECT_EQ(back.pixels, image.pixels);
  }
  // Each of the 65,536 values once.
  Grey16Image every{256, 256, std::vector<uint16_t>(65536)};
  for (size_t i = 0; i < every.pixels.size(); ++i) every.pixels[i] = uint16_t(i * 40503u);  // odd: a permutation
  writeBytes(path("every.png"), encodePng16(every));
  EXPECT_EQ(readPng16(path("every.png")).pixels, every.pixels);
  EXPECT_EQ(std::set<uint16_t>(every.pixels.begin(), every.pixels.end()).size(), 65536u);
}

TEST_F(ImageFile, Png16IsGreySixteenBitWithBigEndianSamples) {
  // A 2x1 image: the IHDR says 16-bit grey, and the (unfiltered or filtered) data decodes to
  // big-endian samples, as every other PNG reader expects (stb reads them back above).
  const std::vector<uint8_t> png = encodePng16({2, 1, {0x1234, 0xABCD}});
  ASSERT_GT(png.size(), 33u);
  EXPECT_EQ(std::string(png.begin() + 12, png.begin() + 16), "IHDR");
  EXPECT_EQ(png[24], 16);  // bit depth
  EXPECT_EQ(png[25], 0);   // colour type grey
  writeBytes(path("two.png"), png);
  EXPECT_EQ(readPng16(path("two.png")).pixels, (std::vector<uint16_t>{0x1234, 0xABCD}));
  // The 8-bit reader still refuses it rather than dropping the low bytes.
  EXPECT_EQ(errorOf([&] { readPng(path("two.png")); }),
            "cannot read '" + path("two.png") + "': 16-bit PNG (only 8-bit is supported)");
}

TEST_F(ImageFile, ReadPng16RejectsEightBitAndColourFilesAndEncodePng16BadImages) {
  writePng(path("rgba8.png"), patternImage(2, 2));
  EXPECT_EQ(errorOf([&] { readPng16(path("rgba8.png")); }),
            "cannot read '" + path("rgba8.png") + "': 8-bit PNG (a 16-bit grey heightmap was expected)");
  writeBytes(path("rgb16.png"), handMadePng(1, 1, 16, 2, {0, 1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(errorOf([&] { readPng16(path("rgb16.png")); }),
            "cannot read '" + path("rgb16.png") + "': 3-channel PNG (a 16-bit grey heightmap was expected)");
  EXPECT_EQ(errorOf([&] { readPng16(path("missing.png")); }),
            "cannot read '" + path("missing.png") + "': No such file or directory");
  EXPECT_EQ(errorOf([&] { encodePng16({0, 0, {}}); }), "cannot encode PNG: image is empty (0x0)");
  EXPECT_EQ(errorOf([&] { encodePng16({2, 2, {1, 2, 3}}); }), "cannot encode PNG: image of 2x2 needs 4 values, has 3");
}

TEST(ImagePsnr, IdenticalImagesGiveInfinity) {
  Rgba8Image image = patternImage(3, 5);
  EXPECT_EQ(psnrRgb(image, image), std::numeric_limits<double>::infinity());
}

TEST(ImagePsnr, KnownDifferenceGivesTheClosedFormValueAndIgnoresAlpha) {
  Rgba8Image a = solidImage(2, 2, 100, 100, 100);
  Rgba8Image b = a;
  b.pixels[0] = 110;  // pixel 0, red: +10
  b.pixels[6] = 97;   // pixel 1, blue: -3
  b.pixels[11] = 0;   // pixel 2, alpha: ignored
  // MSE = (10² + 3²) / (2·2 pixels · 3 channels) = 109 / 12.
  double expected = 10.0 * std::log10(255.0 * 255.0 / (109.0 / 12.0));
  EXPECT_DOUBLE_EQ(psnrRgb(a, b), expected);
  EXPECT_NEAR(psnrRgb(a, b), 38.54835, 1e-5);
  EXPECT_DOUBLE_EQ(psnrRgb(b, a), expected);

  // Every value off by one everywhere: MSE 1, PSNR 20·log10(255).
  Rgba8Image c = solidImage(3, 5, 101, 99, 101, 7);
  EXPECT_DOUBLE_EQ(psnrRgb(solidImage(3, 5, 100, 100, 100), c), 20.0 * std::log10(255.0));
}

TEST(ImagePsnr, SizeMismatchThrows) {
  EXPECT_EQ(errorOf([] { psnrRgb(patternImage(3, 5), patternImage(5, 3)); }),
            "cannot compare images: sizes differ (3x5 vs 5x3)");
  Rgba8Image broken = patternImage(3, 5);
  broken.pixels.resize(4);
  EXPECT_EQ(errorOf([&] { psnrRgb(patternImage(3, 5), broken); }),
            "cannot compare images: image of 3x5 needs 60 RGBA bytes, has 4");
  EXPECT_EQ(errorOf([] { psnrRgb(Rgba8Image{}, Rgba8Image{}); }), "cannot compare images: image is empty (0x0)");
}

TEST(ImageDiff, ScalesAbsoluteDifferencesClampsAndSetsAlphaOpaque) {
  Rgba8Image a{2, 1, {100, 100, 100, 0, 0, 255, 50, 10}};
  Rgba8Image b{2, 1, {110, 97, 100, 200, 40, 0, 50, 10}};
  Rgba8Image diff = diffImage(a, b);
  EXPECT_EQ(diff.width, 2u);
  EXPECT_EQ(diff.height, 1u);
  // |Δ|·8: 10 → 80, 3 → 24, 0 → 0; 40 → 320 and 255 → 2040 clamp to 255; alpha always 255.
  EXPECT_EQ(diff.pixels, (std::vector<uint8_t>{80, 24, 0, 255, 255, 255, 0, 255}));
  EXPECT_EQ(diffImage(b, a).pixels, diff.pixels);
  EXPECT_EQ(diffImage(a, b, 1.0).pixels, (std::vector<uint8_t>{10, 3, 0, 255, 40, 255, 0, 255}));
  EXPECT_EQ(diffImage(a, b, 0.5).pixels, (std::vector<uint8_t>{5, 2, 0, 255, 20, 128, 0, 255}));  // rounded
  EXPECT_EQ(errorOf([&] { diffImage(a, patternImage(1, 2)); }), "cannot compare images: sizes differ (2x1 vs 1x2)");
  EXPECT_EQ(errorOf([&] { diffImage(a, b, -1.0); }), "diff image gain must be finite and >= 0");
}

TEST_F(ImageFile, GoldenMatchPassesAboveTheThresholdAndWritesNothing) {
  Rgba8Image golden = patternImage(8, 8);
  writePng(path("golden.png"), golden);
  Rgba8Image actual = golden;
  actual.pixels[0] ^= 1;  // PSNR ≈ 71 dB
  testing::AssertionResult result = test::matchesGolden(actual, path("golden.png"), 40.0, path("out"), "case");
  EXPECT_TRUE(result) << result.message();
  EXPECT_TRUE(test::matchesGolden(golden, path("golden.png"), 1000.0, path("out"), "case"));  // +inf passes any
  EXPECT_EQ(filesIn(dir_), std::vector<std::string>{"golden.png"});
}

TEST_F(ImageFile, GoldenMismatchFailsWritingActualAndDiffAndNamingThem) {
  Rgba8Image golden = solidImage(2, 2, 100, 100, 100);
  writePng(path("golden.png"), golden);
  Rgba8Image actual = golden;
  actual.pixels[0] = 110;
  actual.pixels[6] = 97;
  testing::AssertionResult result = test::matchesGolden(actual, path("golden.png"), 40.0, path("out"), "case");
  ASSERT_FALSE(result);
  std::string message = result.message();
  std::string actualPath = path("out") + "/case.actual.png";
  std::string diffPath = path("out") + "/case.diff.png";
  EXPECT_NE(message.find("PSNR 38.55 dB"), std::string::npos) << message;
  EXPECT_NE(message.find("threshold 40.00 dB"), std::string::npos) << message;
  EXPECT_NE(message.find(actualPath), std::string::npos) << message;
  EXPECT_NE(message.find(diffPath), std::string::npos) << message;
  EXPECT_EQ(readPng(actualPath).pixels, actual.pixels);
  EXPECT_EQ(readPng(diffPath).pixels, diffImage(actual, golden).pixels);
  EXPECT_EQ(readPng(path("golden.png")).pixels, golden.pixels);  // the golden file is left alone
}

TEST_F(ImageFile, GoldenMissingOrOfAnotherSizeFailsWritingTheActualImage) {
  Rgba8Image actual = patternImage(3, 5);
  testing::AssertionResult missing = test::matchesGolden(actual, path("none.png"), 40.0, path("out"), "missing");
  ASSERT_FALSE(missing);
  EXPECT_NE(std::string(missing.message()).find("is missing"), std::string::npos) << missing.message();
  EXPECT_EQ(readPng(path("out/missing.actual.png")).pixels, actual.pixels);

  writePng(path("other.png"), patternImage(5, 3));
  testing::AssertionResult other = test::matchesGolden(actual, path("other.png"), 40.0, path("out"), "other");
  ASSERT_FALSE(other);
  EXPECT_NE(std::string(other.message()).find("sizes differ (3x5 vs 5x3)"), std::string::npos) << other.message();
  EXPECT_TRUE(fs::exists(path("out/other.actual.png")));
  EXPECT_EQ(filesIn(path("out")), (std::vector<std::string>{"missing.actual.png", "other.actual.png"}));
}

TEST_F(ImageFile, GoldenUpdateModeWritesTheGoldenFileAndPasses) {
  ::setenv("PLANET_UPDATE_GOLDEN", "1", 1);
  Rgba8Image actual = patternImage(4, 3);
  std::string golden = path("goldens/new.png");  // its directory is created
  testing::AssertionResult created = test::matchesGolden(actual, golden, 40.0, path("out"), "new");
  EXPECT_TRUE(created);
  EXPECT_NE(std::string(created.message()).find("updated golden image " + golden), std::string::npos)
      << created.message();
  EXPECT_EQ(readPng(golden).pixels, actual.pixels);

  Rgba8Image changed = patternImage(4, 3, 99);
  EXPECT_TRUE(test::matchesGolden(changed, golden, 40.0, path("out"), "new"));  // rewritten
  EXPECT_EQ(readPng(golden).pixels, changed.pixels);
  EXPECT_FALSE(fs::exists(path("out")));

  ::unsetenv("PLANET_UPDATE_GOLDEN");
  EXPECT_TRUE(test::matchesGolden(changed, golden, 40.0, path("out"), "new"));
  EXPECT_FALSE(test::matchesGolden(actual, golden, 40.0, path("out"), "new"));
}

}  // namespace
}  // namespace planet
