// 8-bit RGBA images as PNG files, and the comparisons golden-image tests need (PSNR, a
// difference picture); 16-bit grey PNG files for heightmaps. PNG encoding and decoding are
// stb_image_write / stb_image, except the 16-bit encoder (stb writes 8 bits only), which
// frames stb's deflate in PNG chunks itself.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace planet {

struct Rgba8Image {
  uint32_t width = 0, height = 0;
  std::vector<uint8_t> pixels;  // RGBA, row-major, top row first: width * height * 4 bytes
};

// The PNG bytes of `image` (RGBA, 8 bits per channel). The same pixels always give the same
// bytes (fixed compression level and filter choice, no timestamps). Throws planet::Error when
// the image is empty, too large for PNG/stb or its pixel count does not match its size.
std::vector<uint8_t> encodePng(const Rgba8Image& image);

// Writes encodePng(image) to `path` atomically (core/file.h). Throws planet::Error naming the
// path on failure (missing directory, empty image, pixel count mismatch); nothing is left behind.
void writePng(const std::string& path, const Rgba8Image& image);

// Reads an 8-bit PNG of any channel count (grey, grey+alpha, RGB, RGBA, palette) as RGBA.
// Throws planet::Error naming the path for a missing or unreadable file, a file that is not a
// PNG, a truncated or corrupt one, and a 16-bit one (it would not round-trip exactly).
Rgba8Image readPng(const std::string& path);

// One 16-bit grey channel, row-major, top row first: width * height values.
struct Grey16Image {
  uint32_t width = 0, height = 0;
  std::vector<uint16_t> pixels;
};

// The PNG bytes of `image` (colour type 0, bit depth 16: samples big-endian in the file, as
// PNG requires). Deterministic like encodePng. Throws planet::Error when the image is empty,
// too large (a filtered row set over 2^31 bytes) or its pixel count does not match its size.
std::vector<uint8_t> encodePng16(const Grey16Image& image);

// Reads a 16-bit grey PNG, such as encodePng16 writes. Throws planet::Error naming the path for
// a missing, unreadable, truncated or corrupt file, a file that is not a PNG, and a PNG of
// another bit depth or with more than one channel (it would not hold the same values).
Grey16Image readPng16(const std::string& path);

// Peak signal-to-noise ratio over the RGB channels (alpha ignored), in dB, with MAX = 255:
// 10·log10(255² / MSE), MSE averaged over width·height·3 values. Identical images give
// +infinity. Throws planet::Error when the sizes differ or an image is empty or inconsistent.
double psnrRgb(const Rgba8Image& a, const Rgba8Image& b);

// The picture a failing golden test writes beside the actual image: per RGB channel
// min(255, round(|a − b| · gain)), alpha 255. Throws planet::Error like psnrRgb, and for a
// negative or non-finite gain.
Rgba8Image diffImage(const Rgba8Image& a, const Rgba8Image& b, double gain = 8.0);

}  // namespace planet
