#include "core/file.h"

#include <cerrno>
#include <cstdio>
#include <cstring>

#include <sys/stat.h>
#include <unistd.h>

#include "core/error.h"

namespace planet {

namespace {

std::string temporaryName(const std::string& path) { return path + ".tmp-" + std::to_string(::getpid()); }

// Writes `contents` to the temporary twin of `path`; on failure removes it and throws.
void writeTemporary(const std::string& path, std::string_view contents) {
  if (path.empty()) throw Error("output file name is empty");
  const std::string temp = temporaryName(path);
  std::FILE* file = std::fopen(temp.c_str(), "wb");
  if (!file) throw Error("cannot write " + quotedPath(path) + ": " + std::strerror(errno));
  bool ok = std::fwrite(contents.data(), 1, contents.size(), file) == contents.size();
  int writeErrno = errno;
  ok = (std::fclose(file) == 0) && ok;
  if (!ok) {
    std::remove(temp.c_str());
    throw Error("cannot write " + quotedPath(path) + ": " + std::strerror(writeErrno ? writeErrno : errno));
  }
}

}  // namespace

void writeFileAtomic(const std::string& path, std::string_view contents) {
  const FileContents file{path, contents};
  writeFilesAtomic({&file, 1});
}

void writeFilesAtomic(std::span<const FileContents> files) {
  size_t written = 0;
  try {
    for (; written < files.size(); ++written) writeTemporary(files[written].path, files[written].contents);
  } catch (const Error&) {
    for (size_t i = 0; i < written; ++i) std::remove(temporaryName(files[i].path).c_str());
    throw;
  }
  // A directory in a target's place would fail its rename after earlier files were replaced.
  for (const FileContents& file : files) {
    struct stat info {};
    if (::stat(file.path.c_str(), &info) == 0 && S_ISDIR(info.st_mode)) {
      for (const FileContents& f : files) std::remove(temporaryName(f.path).c_str());
      throw Error("cannot write " + quotedPath(file.path) + ": " + std::strerror(EISDIR));
    }
  }
  for (size_t i = 0; i < files.size(); ++i) {
    const std::string temp = temporaryName(files[i].path);
    if (std::rename(temp.c_str(), files[i].path.c_str()) != 0) {
      int renameErrno = errno;
      for (size_t j = i; j < files.size(); ++j) std::remove(temporaryName(files[j].path).c_str());
      throw Error("cannot write " + quotedPath(files[i].path) + ": " + std::strerror(renameErrno));
    }
  }
}

std::string readFileUpTo(const std::string& path, size_t limit) {
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (!file) throw Error("cannot read " + quotedPath(path) + ": " + std::strerror(errno));
  std::string text(limit + 1, '\0');
  const size_t size = std::fread(text.data(), 1, text.size(), file);
  const bool failed = std::ferror(file);
  const int readErrno = errno;
  std::fclose(file);
  if (failed) throw Error("cannot read " + quotedPath(path) + ": " + std::strerror(readErrno));
  text.resize(size);
  return text;
}

}  // namespace planet
