// The staging directory, the swap, and the clean-up of a LUT set transaction.
#include "io/LutSetTransaction.h"

#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <set>

#include <nlohmann/json.hpp>

#include "core/Errors.h"
#include "io/ManifestSchema.h"

namespace cloudlut::io {

namespace fs = std::filesystem;

namespace {

std::string osProblem(const std::string& what) { return what + ": " + std::strerror(errno); }

// ".NAME.baking." — the prefix of every staging directory of `finalDir`.
std::string stagingPrefix(const fs::path& finalDir) { return "." + finalDir.filename().string() + ".baking."; }

bool processAlive(long pid) { return pid > 0 && (::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM); }

bool holdsDirectory(const fs::path& dir) {
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    if (it->is_directory(ec) && !it->is_symlink(ec)) return true;
  return false;
}

// Removes the staging directories of dead processes beside `finalDir`.
void removeStale(const fs::path& finalDir) {
  const std::string prefix = stagingPrefix(finalDir);
  std::error_code ec;
  for (fs::directory_iterator it(finalDir.parent_path(), ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    char* tail = nullptr;
    const long pid = std::strtol(name.c_str() + prefix.size(), &tail, 10);
    if (tail == nullptr || (*tail != '\0' && std::strcmp(tail, ".old") != 0) || processAlive(pid)) continue;
    if (holdsDirectory(it->path())) {
      std::fprintf(stderr, "cloudlut: warning: kept '%s', left by an interrupted bake: it holds a directory\n",
                   it->path().c_str());
      continue;
    }
    std::error_code rm;
    fs::remove_all(it->path(), rm);
  }
}

// The names that belong to the LUT set in `dir`: its manifest, the files its manifest lists
// and temporary files of its writers ("*.tmp.*").
std::set<std::string> setMembers(const fs::path& dir) {
  std::set<std::string> names{kManifestName};
  std::ifstream in(dir / kManifestName);
  const nlohmann::json m = in ? nlohmann::json::parse(in, nullptr, false) : nlohmann::json();
  if (m.is_object() && m.contains("tables") && m["tables"].is_object())
    for (const auto& [name, entry] : m["tables"].items()) {
      if (!entry.is_object() || !entry.contains("files") || !entry["files"].is_object()) continue;
      for (const auto& [format, file] : entry["files"].items())
        if (file.is_string()) names.insert(fs::path(file.get<std::string>()).filename().string());
    }
  return names;
}

bool isTemporary(const std::string& name) { return name.find(".tmp.") != std::string::npos; }

// Hard-links the regular files of `from` that are not set members and not in `to` into `to`;
// returns the directories among them (moved after the swap).
std::vector<std::string> carryFiles(const fs::path& from, const fs::path& to) {
  std::vector<std::string> directories;
  const std::set<std::string> members = setMembers(from);
  std::error_code ec;
  for (fs::directory_iterator it(from, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (members.count(name) || isTemporary(name) || fs::exists(to / name)) continue;
    std::error_code kind;
    if (it->is_directory(kind) && !it->is_symlink(kind)) {
      directories.push_back(name);
      continue;
    }
    if (::link(it->path().c_str(), (to / name).c_str()) != 0) {
      // a symbolic link or a file on which hard links fail: copy it
      std::error_code copy;
      fs::copy(it->path(), to / name, fs::copy_options::copy_symlinks, copy);
      if (copy) throw FileError(it->path().string(), "cannot carry over into the new LUT set: " + copy.message());
    }
  }
  return directories;
}

}  // namespace

LutSetTransaction::LutSetTransaction(const fs::path& finalDir) {
  fs::path dir = fs::absolute(finalDir).lexically_normal();
  if (dir.filename().empty()) dir = dir.parent_path();  // "out/luts/" → "out/luts"
  final_ = dir;
  std::error_code ec;
  if (!fs::is_directory(final_.parent_path(), ec))
    throw UsageError("cannot bake into '" + finalDir.string() + "': directory '" + final_.parent_path().string() +
                     "' does not exist");
  if (fs::exists(final_, ec) && !fs::is_directory(final_, ec))
    throw UsageError("cannot bake into '" + finalDir.string() + "': it is not a directory");
  removeStale(final_);
  staging_ = final_.parent_path() / (stagingPrefix(final_) + std::to_string(static_cast<long>(::getpid())));
  fs::remove_all(staging_, ec);  // a staging directory of an earlier process that had this pid
  if (::mkdir(staging_.c_str(), 0755) != 0)
    throw UsageError(osProblem("cannot create the staging directory '" + staging_.string() + "' beside '" +
                               final_.string() + "'"));
}

LutSetTransaction::~LutSetTransaction() {
  if (committed_) return;
  std::error_code ec;
  fs::remove_all(staging_, ec);
}

std::vector<std::string> LutSetTransaction::commit() {
  std::vector<std::string> warnings;
  std::error_code ec;
  const bool hadOld = fs::is_directory(final_, ec);
  std::vector<std::string> directories;
  if (hadOld) directories = carryFiles(final_, staging_);
  // Make the staged files durable before they become the set.
  if (const int fd = ::open(staging_.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC); fd >= 0) {
    ::fsync(fd);
    ::close(fd);
  }
  if (!hadOld) {
    if (::rename(staging_.c_str(), final_.c_str()) != 0)
      throw FileError(final_.string(), osProblem("cannot move the new LUT set into place"));
  } else if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, final_.c_str(), RENAME_EXCHANGE) != 0) {
    if (errno != EINVAL && errno != ENOSYS && errno != ENOTSUP)
      throw FileError(final_.string(), osProblem("cannot swap in the new LUT set"));
    // No atomic exchange on this file system: move the old set aside, then the new one in (a
    // moment without either name, never a mixed set).
    const fs::path aside = staging_.string() + ".old";
    if (::rename(final_.c_str(), aside.c_str()) != 0)
      throw FileError(final_.string(), osProblem("cannot move the old LUT set aside"));
    if (::rename(staging_.c_str(), final_.c_str()) != 0) {
      const std::string problem = osProblem("cannot move the new LUT set into place");
      ::rename(aside.c_str(), final_.c_str());
      throw FileError(final_.string(), problem);
    }
    ::rename(aside.c_str(), staging_.c_str());
  }
  committed_ = true;
  if (const int fd = ::open(final_.parent_path().c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC); fd >= 0) {
    ::fsync(fd);
    ::close(fd);
  }
  if (!hadOld) return warnings;
  // staging_ now holds the old set: carry the user's directories over, then remove it
  for (const std::string& name : directories)
    if (::rename((staging_ / name).c_str(), (final_ / name).c_str()) != 0)
      warnings.push_back(osProblem("cannot move '" + (staging_ / name).string() + "' into '" + final_.string() + "'"));
  if (holdsDirectory(staging_)) {
    warnings.push_back("kept the old LUT set in '" + staging_.string() + "': it still holds a directory");
    return warnings;
  }
  fs::remove_all(staging_, ec);
  if (ec) warnings.push_back("cannot remove the old LUT set in '" + staging_.string() + "': " + ec.message());
  return warnings;
}

}  // namespace cloudlut::io
