// Golden-image comparison for tests: PSNR against a PNG in the repository, with the actual and
// difference pictures written on failure so that a failing run can be looked at.
//
//   EXPECT_TRUE(planet::test::matchesGolden(image, goldenDir + "/sky.png", 40.0, outDir, "sky"));
//
// PLANET_UPDATE_GOLDEN=1 in the environment (re)writes the golden files from the actual images.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iomanip>
#include <sstream>
#include <string>
#include <system_error>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/image_file.h"

namespace planet::test {

// Passes when PSNR(actual, golden) >= minPsnrDb. On failure, and when the golden file is
// missing or unreadable, writes <outDir>/<name>.actual.png (and <name>.diff.png when both
// images have the same size; diffImage with its default gain) and fails with the PSNR, the
// threshold and the paths. With PLANET_UPDATE_GOLDEN=1 it writes the golden file instead
// (creating its directory) and passes, saying so on stdout.
inline testing::AssertionResult matchesGolden(const Rgba8Image& actual, const std::string& goldenPath, double minPsnrDb,
                                              const std::string& outDir, const std::string& name) {
  const char* update = std::getenv("PLANET_UPDATE_GOLDEN");
  if (update && std::strcmp(update, "1") == 0) {
    try {
      std::filesystem::path parent = std::filesystem::path(goldenPath).parent_path();
      if (!parent.empty()) std::filesystem::create_directories(parent);
      writePng(goldenPath, actual);
    } catch (const std::exception& e) {
      return testing::AssertionFailure() << "PLANET_UPDATE_GOLDEN=1: " << e.what();
    }
    std::printf("[ GOLDEN   ] updated %s\n", goldenPath.c_str());
    return testing::AssertionSuccess() << "updated golden image " << goldenPath << " (PLANET_UPDATE_GOLDEN=1)";
  }

  auto dB = [](double value) {
    std::ostringstream text;
    text << std::fixed << std::setprecision(2) << value << " dB";
    return text.str();
  };
  std::ostringstream why;  // what went wrong, before the list of written files
  std::string actualPath = outDir + "/" + name + ".actual.png";
  std::string diffPath = outDir + "/" + name + ".diff.png";
  bool writeDiff = false;
  Rgba8Image golden;
  std::error_code error;
  if (!std::filesystem::exists(goldenPath, error)) {
    why << "golden image " << goldenPath << " is missing (create it with PLANET_UPDATE_GOLDEN=1)";
  } else {
    try {
      golden = readPng(goldenPath);
      double psnr = psnrRgb(actual, golden);
      if (psnr >= minPsnrDb) return testing::AssertionSuccess() << "PSNR " << dB(psnr) << " >= " << dB(minPsnrDb);
      why << "PSNR " << dB(psnr) << " is below the threshold " << dB(minPsnrDb) << " against " << goldenPath;
      writeDiff = true;
    } catch (const Error& e) {
      why << "cannot compare with " << goldenPath << ": " << e.what();
    }
  }

  std::ostringstream written;
  try {
    std::filesystem::create_directories(outDir);
    writePng(actualPath, actual);
    written << "; actual: " << actualPath;
    if (writeDiff) {
      writePng(diffPath, diffImage(actual, golden));
      written << ", diff: " << diffPath;
    }
  } catch (const std::exception& e) {
    written << "; could not write the actual/diff images: " << e.what();
  }
  return testing::AssertionFailure() << why.str() << written.str();
}

}  // namespace planet::test
