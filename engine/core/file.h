// Output files are written whole or not at all: to a temporary name beside the target, then
// renamed over it, so an error or a crash never leaves a half-written file.
#pragma once

#include <string>
#include <string_view>

namespace planet {

// Throws planet::Error naming the path and the system's reason on failure.
void writeFileAtomic(const std::string& path, std::string_view contents);

}  // namespace planet
