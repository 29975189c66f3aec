// Output files are written whole or not at all: to a temporary name beside the target, then
// renamed over it, so an error or a crash never leaves a half-written file.
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <string_view>

namespace planet {

// Throws planet::Error naming the path and the system's reason on failure.
void writeFileAtomic(const std::string& path, std::string_view contents);

struct FileContents {
  std::string path;
  std::string_view contents;
};

// Several files that belong together (an image and the sidecar that describes it): each is
// written to its temporary twin, and only when all are complete are they renamed over their
// targets, in order. A failure while writing leaves none of them and no temporary file; only a
// rename failing after an earlier one succeeded (both in one directory: practically never) can
// leave some new files beside old ones. Throws planet::Error like writeFileAtomic.
void writeFilesAtomic(std::span<const FileContents> files);

// The contents of a file, at most limit + 1 bytes: a result longer than `limit` tells the caller
// the file is too large without reading all of it. Throws planet::Error ("cannot read 'path':
// reason") when the file cannot be opened or read.
std::string readFileUpTo(const std::string& path, size_t limit);

}  // namespace planet
