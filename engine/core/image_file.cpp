#include "core/image_file.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>
#include <string_view>

#include "core/error.h"
#include "core/file.h"

// stb's implementations live in this file only. STATIC keeps every stb symbol (and stb's
// global settings) private to this translation unit, so no other user of stb can clash with it
// or change its settings. Files are read and written here, so stb's stdio variants are left out;
// the reader decodes PNG only. The parts of stb this file does not call would each warn as an
// unused static function if stb were not in a system include directory.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#define STBI_WRITE_NO_STDIO
#include <stb/stb_image_write.h>

#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#define STBI_ONLY_PNG
#define STBI_NO_STDIO
#define STBI_NO_LINEAR
#include <stb/stb_image.h>
#pragma GCC diagnostic pop

namespace planet {
namespace {

// Deflate level of stb's own compressor (its default, set here so that it is a stated fixed
// value: the bytes of a PNG depend on it). Higher is smaller and slower.
constexpr int kPngCompressionLevel = 8;
// Row filter: -1 lets stb pick per row by a fixed heuristic (deterministic); 0..5 would force one.
constexpr int kPngFilter = -1;

// The last 12 bytes of every complete PNG: the IEND chunk (length 0, type, CRC).
constexpr uint8_t kPngEnd[12] = {0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xAE, 0x42, 0x60, 0x82};
constexpr uint8_t kPngSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};

std::string sizeText(const Rgba8Image& image) {
  return std::to_string(image.width) + "x" + std::to_string(image.height);
}

// Why `image` cannot be encoded or compared, or "" when it is fine.
std::string imageProblem(const Rgba8Image& image) {
  if (image.width == 0 || image.height == 0) return "image is empty (" + sizeText(image) + ")";
  uint64_t expected = uint64_t(image.width) * image.height * 4;
  if (image.pixels.size() != expected) {
    return "image of " + sizeText(image) + " needs " + std::to_string(expected) + " RGBA bytes, has " +
           std::to_string(image.pixels.size());
  }
  return "";
}

// stb_image_write indexes its buffers with int (the filtered data is (width·4 + 1)·height bytes).
std::string encodeProblem(const Rgba8Image& image) {
  std::string problem = imageProblem(image);
  if (problem.empty() && (uint64_t(image.width) * 4 + 1) * image.height > uint64_t(INT_MAX)) {
    problem = "image of " + sizeText(image) + " is too large to encode";
  }
  return problem;
}

void appendBytes(void* context, void* data, int size) {
  auto* bytes = static_cast<std::vector<uint8_t>*>(context);
  const auto* begin = static_cast<const uint8_t*>(data);
  bytes->insert(bytes->end(), begin, begin + size);
}

std::vector<uint8_t> encodeChecked(const Rgba8Image& image) {
  // Set once (thread-safe static initialisation); afterwards stb only reads them.
  static const bool settingsApplied = [] {
    stbi_write_png_compression_level = kPngCompressionLevel;
    stbi_write_force_png_filter = kPngFilter;
    return true;
  }();
  (void)settingsApplied;

  std::vector<uint8_t> bytes;
  int width = int(image.width), height = int(image.height);
  if (!stbi_write_png_to_func(appendBytes, &bytes, width, height, 4, image.pixels.data(), width * 4)) {
    throw Error("PNG encoding failed (out of memory)");
  }
  return bytes;
}

std::vector<uint8_t> readWholeFile(const std::string& path) {
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), std::fclose);
  if (!file) throw Error("cannot read " + quotedPath(path) + ": " + std::strerror(errno));
  std::vector<uint8_t> bytes;
  uint8_t buffer[1 << 16];
  size_t got;
  while ((got = std::fread(buffer, 1, sizeof buffer, file.get())) > 0) bytes.insert(bytes.end(), buffer, buffer + got);
  if (std::ferror(file.get())) throw Error("cannot read " + quotedPath(path) + ": " + std::strerror(errno));
  return bytes;
}

bool startsWith(const std::vector<uint8_t>& bytes, const uint8_t* prefix, size_t size) {
  return bytes.size() >= size && std::equal(prefix, prefix + size, bytes.begin());
}

bool endsWith(const std::vector<uint8_t>& bytes, const uint8_t* suffix, size_t size) {
  return bytes.size() >= size && std::equal(suffix, suffix + size, bytes.end() - ptrdiff_t(size));
}

// The bytes of a PNG file after the checks every reader makes before stb sees them.
std::vector<uint8_t> readCheckedPng(const std::string& path) {
  std::vector<uint8_t> bytes = readWholeFile(path);
  std::string prefix = "cannot read " + quotedPath(path) + ": ";
  if (!startsWith(bytes, kPngSignature, sizeof kPngSignature)) throw Error(prefix + "not a PNG file");
  // stb_image reads zeros past the end of its buffer, so a cut-off file is caught here.
  if (!endsWith(bytes, kPngEnd, sizeof kPngEnd)) throw Error(prefix + "truncated PNG (it does not end with IEND)");
  if (bytes.size() > size_t(INT_MAX)) throw Error(prefix + "PNG file larger than 2 GiB");
  return bytes;
}

void putBigEndian32(uint8_t* out, uint32_t value) {
  for (int i = 0; i < 4; ++i) out[i] = uint8_t(value >> (24 - 8 * i));
}

// CRC-32 as the PNG specification defines it for chunks (polynomial 0xEDB88320, reflected),
// over the chunk type and data.
uint32_t pngCrc(const uint8_t* type, const uint8_t* data, size_t size) {
  static const auto table = [] {
    std::array<uint32_t, 256> t{};
    for (uint32_t n = 0; n < 256; ++n) {
      uint32_t c = n;
      for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      t[n] = c;
    }
    return t;
  }();
  uint32_t crc = 0xFFFFFFFFu;
  auto add = [&](const uint8_t* bytes, size_t count) {
    for (size_t i = 0; i < count; ++i) crc = table[(crc ^ bytes[i]) & 0xFFu] ^ (crc >> 8);
  };
  add(type, 4);
  add(data, size);
  return ~crc;
}

void appendChunk(std::vector<uint8_t>& png, const char* type, const uint8_t* data, size_t size) {
  uint8_t length[4];
  putBigEndian32(length, uint32_t(size));
  png.insert(png.end(), length, length + 4);
  const auto* typeBytes = reinterpret_cast<const uint8_t*>(type);
  png.insert(png.end(), typeBytes, typeBytes + 4);
  if (size > 0) png.insert(png.end(), data, data + size);
  uint8_t crc[4];
  putBigEndian32(crc, pngCrc(typeBytes, data, size));
  png.insert(png.end(), crc, crc + 4);
}

// The Paeth predictor (PNG specification, filter type 4).
int paethPredictor(int left, int up, int upLeft) {
  const int p = left + up - upLeft;
  const int pa = std::abs(p - left), pb = std::abs(p - up), pc = std::abs(p - upLeft);
  if (pa <= pb && pa <= pc) return left;
  return pb <= pc ? up : upLeft;
}

// The scanlines of a 16-bit grey image as deflate input: per row a filter byte and the row's
// big-endian samples filtered by it. Each row takes the filter (none, sub, up, average, Paeth)
// whose output has the smallest sum of absolute values as signed bytes, the heuristic the PNG
// specification recommends; smooth heightmaps shrink to about half with it.
std::vector<uint8_t> filterRows16(const Grey16Image& image) {
  constexpr size_t kBytesPerPixel = 2;
  const size_t rowBytes = size_t(image.width) * kBytesPerPixel;
  std::vector<uint8_t> out((rowBytes + 1) * image.height);
  std::vector<uint8_t> previous(rowBytes, 0), current(rowBytes), candidate(rowBytes), best(rowBytes);
  for (uint32_t y = 0; y < image.height; ++y) {
    for (uint32_t x = 0; x < image.width; ++x) {
      const uint16_t value = image.pixels[size_t(y) * image.width + x];
      current[2 * x] = uint8_t(value >> 8);
      current[2 * x + 1] = uint8_t(value & 0xFFu);
    }
    uint64_t bestCost = UINT64_MAX;
    uint8_t bestFilter = 0;
    for (uint8_t filter = 0; filter < 5; ++filter) {
      uint64_t cost = 0;
      for (size_t i = 0; i < rowBytes; ++i) {
        const int left = i >= kBytesPerPixel ? current[i - kBytesPerPixel] : 0;
        const int up = previous[i];
        const int upLeft = i >= kBytesPerPixel ? previous[i - kBytesPerPixel] : 0;
        int prediction = 0;
        switch (filter) {
          case 1: prediction = left; break;
          case 2: prediction = up; break;
          case 3: prediction = (left + up) / 2; break;
          case 4: prediction = paethPredictor(left, up, upLeft); break;
          default: break;
        }
        candidate[i] = uint8_t(current[i] - prediction);
        cost += uint64_t(std::abs(int(int8_t(candidate[i]))));
      }
      if (cost < bestCost) {
        bestCost = cost;
        bestFilter = filter;
        best.swap(candidate);
      }
    }
    uint8_t* row = out.data() + size_t(y) * (rowBytes + 1);
    row[0] = bestFilter;
    std::copy(best.begin(), best.end(), row + 1);
    previous.swap(current);
  }
  return out;
}

void checkComparable(const Rgba8Image& a, const Rgba8Image& b) {
  for (const Rgba8Image* image : {&a, &b}) {
    std::string problem = imageProblem(*image);
    if (!problem.empty()) throw Error("cannot compare images: " + problem);
  }
  if (a.width != b.width || a.height != b.height) {
    throw Error("cannot compare images: sizes differ (" + sizeText(a) + " vs " + sizeText(b) + ")");
  }
}

}  // namespace

std::vector<uint8_t> encodePng(const Rgba8Image& image) {
  std::string problem = encodeProblem(image);
  if (!problem.empty()) throw Error("cannot encode PNG: " + problem);
  return encodeChecked(image);
}

void writePng(const std::string& path, const Rgba8Image& image) {
  std::string problem = encodeProblem(image);
  if (!problem.empty()) throw Error("cannot write " + quotedPath(path) + ": " + problem);
  std::vector<uint8_t> bytes;
  try {
    bytes = encodeChecked(image);
  } catch (const Error& e) {
    throw Error("cannot write " + quotedPath(path) + ": " + e.what());
  }
  writeFileAtomic(path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

Rgba8Image readPng(const std::string& path) {
  std::vector<uint8_t> bytes = readCheckedPng(path);
  std::string prefix = "cannot read " + quotedPath(path) + ": ";
  int length = int(bytes.size());
  if (stbi_is_16_bit_from_memory(bytes.data(), length)) throw Error(prefix + "16-bit PNG (only 8-bit is supported)");
  int width = 0, height = 0, channels = 0;
  std::unique_ptr<stbi_uc, void (*)(void*)> pixels(
      stbi_load_from_memory(bytes.data(), length, &width, &height, &channels, 4), stbi_image_free);
  if (!pixels) throw Error(prefix + "corrupt PNG (" + stbi_failure_reason() + ")");

  Rgba8Image image;
  image.width = uint32_t(width);
  image.height = uint32_t(height);
  image.pixels.assign(pixels.get(), pixels.get() + size_t(width) * size_t(height) * 4);
  return image;
}

std::vector<uint8_t> encodePng16(const Grey16Image& image) {
  const std::string size = std::to_string(image.width) + "x" + std::to_string(image.height);
  if (image.width == 0 || image.height == 0) throw Error("cannot encode PNG: image is empty (" + size + ")");
  if (image.pixels.size() != uint64_t(image.width) * image.height)
    throw Error("cannot encode PNG: image of " + size + " needs " +
                std::to_string(uint64_t(image.width) * image.height) + " values, has " +
                std::to_string(image.pixels.size()));
  // stb's deflate takes an int length.
  const uint64_t rowBytes = uint64_t(image.width) * 2;
  if ((rowBytes + 1) * image.height > uint64_t(INT_MAX))
    throw Error("cannot encode PNG: image of " + size + " is too large to encode");

  std::vector<uint8_t> filtered = filterRows16(image);
  int compressedSize = 0;
  std::unique_ptr<unsigned char, void (*)(void*)> compressed(
      stbi_zlib_compress(filtered.data(), int(filtered.size()), &compressedSize, kPngCompressionLevel), std::free);
  if (!compressed) throw Error("PNG encoding failed (out of memory)");

  std::vector<uint8_t> png(kPngSignature, kPngSignature + sizeof kPngSignature);
  uint8_t header[13];
  putBigEndian32(header, image.width);
  putBigEndian32(header + 4, image.height);
  // Bit depth 16, colour type 0 (grey), deflate, adaptive filtering, no interlace.
  const uint8_t rest[5] = {16, 0, 0, 0, 0};
  std::copy(rest, rest + 5, header + 8);
  appendChunk(png, "IHDR", header, sizeof header);
  appendChunk(png, "IDAT", compressed.get(), size_t(compressedSize));
  appendChunk(png, "IEND", nullptr, 0);
  return png;
}

Grey16Image readPng16(const std::string& path) {
  std::vector<uint8_t> bytes = readCheckedPng(path);
  std::string prefix = "cannot read " + quotedPath(path) + ": ";
  int length = int(bytes.size());
  int width = 0, height = 0, channels = 0;
  if (!stbi_info_from_memory(bytes.data(), length, &width, &height, &channels))
    throw Error(prefix + "corrupt PNG (" + stbi_failure_reason() + ")");
  if (!stbi_is_16_bit_from_memory(bytes.data(), length))
    throw Error(prefix + "8-bit PNG (a 16-bit grey heightmap was expected)");
  if (channels != 1)
    throw Error(prefix + std::to_string(channels) + "-channel PNG (a 16-bit grey heightmap was expected)");
  std::unique_ptr<stbi_us, void (*)(void*)> pixels(
      stbi_load_16_from_memory(bytes.data(), length, &width, &height, &channels, 1), stbi_image_free);
  if (!pixels) throw Error(prefix + "corrupt PNG (" + stbi_failure_reason() + ")");

  Grey16Image image;
  image.width = uint32_t(width);
  image.height = uint32_t(height);
  image.pixels.assign(pixels.get(), pixels.get() + size_t(width) * size_t(height));
  return image;
}

double psnrRgb(const Rgba8Image& a, const Rgba8Image& b) {
  checkComparable(a, b);
  // Exact integer sum of squared differences: at most 255² · 3 per pixel, far below 2^64.
  uint64_t sumSquares = 0;
  for (size_t i = 0; i < a.pixels.size(); i += 4) {
    for (size_t c = 0; c < 3; ++c) {
      int d = int(a.pixels[i + c]) - int(b.pixels[i + c]);
      sumSquares += uint64_t(d * d);
    }
  }
  if (sumSquares == 0) return std::numeric_limits<double>::infinity();
  double mse = double(sumSquares) / (double(a.width) * double(a.height) * 3.0);
  return 10.0 * std::log10(255.0 * 255.0 / mse);
}

Rgba8Image diffImage(const Rgba8Image& a, const Rgba8Image& b, double gain) {
  checkComparable(a, b);
  if (!std::isfinite(gain) || gain < 0.0) throw Error("diff image gain must be finite and >= 0");
  Rgba8Image diff{a.width, a.height, std::vector<uint8_t>(a.pixels.size())};
  for (size_t i = 0; i < a.pixels.size(); i += 4) {
    for (size_t c = 0; c < 3; ++c) {
      double d = std::abs(int(a.pixels[i + c]) - int(b.pixels[i + c])) * gain;
      diff.pixels[i + c] = uint8_t(std::lround(std::min(d, 255.0)));
    }
    diff.pixels[i + 3] = 255;
  }
  return diff;
}

}  // namespace planet
