#include "core/file.h"

#include <cerrno>
#include <cstdio>
#include <cstring>

#include <unistd.h>

#include "core/error.h"

namespace planet {

void writeFileAtomic(const std::string& path, std::string_view contents) {
  if (path.empty()) throw Error("output file name is empty");
  std::string temp = path + ".tmp-" + std::to_string(::getpid());
  std::FILE* file = std::fopen(temp.c_str(), "wb");
  if (!file) throw Error("cannot write '" + path + "': " + std::strerror(errno));
  bool ok = std::fwrite(contents.data(), 1, contents.size(), file) == contents.size();
  int writeErrno = errno;
  ok = (std::fclose(file) == 0) && ok;
  if (!ok) {
    std::remove(temp.c_str());
    throw Error("cannot write '" + path + "': " + std::strerror(writeErrno ? writeErrno : errno));
  }
  if (std::rename(temp.c_str(), path.c_str()) != 0) {
    int renameErrno = errno;
    std::remove(temp.c_str());
    throw Error("cannot write '" + path + "': " + std::strerror(renameErrno));
  }
}

std::string readFileUpTo(const std::string& path, size_t limit) {
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (!file) throw Error("cannot read '" + path + "': " + std::strerror(errno));
  std::string text(limit + 1, '\0');
  const size_t size = std::fread(text.data(), 1, text.size(), file);
  const bool failed = std::ferror(file);
  const int readErrno = errno;
  std::fclose(file);
  if (failed) throw Error("cannot read '" + path + "': " + std::strerror(readErrno));
  text.resize(size);
  return text;
}

}  // namespace planet
