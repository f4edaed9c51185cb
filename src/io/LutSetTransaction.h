#pragma once
// Replacing a LUT set as one transaction: a re-bake into an existing LUT directory leaves,
// whatever moment it is killed at (SIGKILL, SIGTERM, SIGINT, a full disk), either the old set
// or the new set, complete and consistent (lut_formats/FORMAT.md §4: the manifest and the
// tables it lists agree).
//
// The new set is written into a staging directory beside the final one, ".NAME.baking.PID" in
// the same parent (so on the same file system). commit() then swaps the two directories in one
// step (renameat2 RENAME_EXCHANGE; a plain rename when there is no old set) and removes the old
// set, now under the staging name. Entries of the old directory that are no part of its set
// (files the user keeps there; its own manifest, tables and temporary files excepted) are
// carried over: files as hard links into the staging directory before the swap, directories by
// a rename after it. A transaction that is never committed removes its staging directory;
// staging directories left by killed processes are removed by the next transaction on the same
// directory (those holding a subdirectory are kept, and named in a warning).
#include <filesystem>
#include <string>
#include <vector>

namespace cloudlut::io {

class LutSetTransaction {
 public:
  // Creates the staging directory beside `finalDir` (whose parent must exist and be
  // writable: UsageError otherwise) after removing stale ones.
  explicit LutSetTransaction(const std::filesystem::path& finalDir);
  ~LutSetTransaction();
  LutSetTransaction(const LutSetTransaction&) = delete;
  LutSetTransaction& operator=(const LutSetTransaction&) = delete;

  // Where the new set is written.
  const std::filesystem::path& stagingDir() const { return staging_; }
  const std::filesystem::path& finalDir() const { return final_; }

  // Swaps the staged set in and removes the old one. FileError naming the directory when the
  // swap fails (the old set is then untouched). Warnings (an old directory that could not be
  // removed completely) are returned, one line each.
  std::vector<std::string> commit();

 private:
  std::filesystem::path final_, staging_;
  bool committed_ = false;
};

}  // namespace cloudlut::io
