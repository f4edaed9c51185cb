// writeFileAtomically: a final name holds either nothing or a complete file.
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <system_error>

#include "core/Errors.h"
#include "io/LutIo.h"

namespace cloudlut::io {

namespace {

// "problem: strerror(errno)" for an OS call that just failed.
std::string osProblem(const std::string& what) {
  return what + ": " + std::strerror(errno);
}

// Writes every byte of `bytes` to the descriptor, retrying after short writes and signals.
bool writeAll(int fd, std::string_view bytes) {
  const char* p = bytes.data();
  std::size_t left = bytes.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  return true;
}

}  // namespace

// Writes `bytes` to "NAME.tmp.<pid>" beside `path`, flushes it to the disk (fsync), and renames
// it over `path`. The temporary file is removed if any step fails. A directory that does not
// exist or cannot be written to raises UsageError naming the directory; a failed write, flush or
// rename (a full disk) raises FileError naming the file (exit 1).
void writeFileAtomically(const std::filesystem::path& path, std::string_view bytes) {
  namespace fs = std::filesystem;
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw UsageError("cannot write '" + path.string() + "': directory '" + dir.string() +
                     "' does not exist");
  if (path.filename().empty())
    throw UsageError("cannot write '" + path.string() + "': not a file name");
  const fs::path temp =
      dir / (path.filename().string() + ".tmp." + std::to_string(static_cast<long>(::getpid())));

  const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0)
    throw UsageError(osProblem("cannot write to directory '" + dir.string() + "'"));
  std::string problem;
  if (!writeAll(fd, bytes)) problem = osProblem("cannot write '" + temp.string() + "'");
  else if (::fsync(fd) != 0) problem = osProblem("cannot flush '" + temp.string() + "'");
  if (::close(fd) != 0 && problem.empty())
    problem = osProblem("cannot close '" + temp.string() + "'");
  if (problem.empty() && ::rename(temp.c_str(), path.c_str()) != 0)
    problem = osProblem("cannot rename '" + temp.string() + "' to '" + path.string() + "'");
  if (!problem.empty()) {  // a full disk (ENOSPC), an I/O error: the file could not be written
    ::unlink(temp.c_str());
    throw FileError(path.string(), problem);
  }
}

}  // namespace cloudlut::io
