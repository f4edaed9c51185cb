#pragma once
// Tables written to their files (writeTableFiles) on background threads while the caller goes on
// computing: the optical-depth table's files (16 MB of samples, a zlib-compressed EXR and two
// fsyncs) were a single-threaded second of a bake, now spent beside the scattering tables' bake.
// The files are the same bytes as a direct writeTableFiles: only when they are written changes.
#include <filesystem>
#include <future>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/Table4D.h"
#include "io/ManifestSchema.h"

namespace cloudlut::io {

class BackgroundTableWrites {
 public:
  BackgroundTableWrites() = default;
  // Waits for the writes still running (their results and failures are dropped: finish() was
  // not reached, so the caller is unwinding from its own failure).
  ~BackgroundTableWrites();
  BackgroundTableWrites(const BackgroundTableWrites&) = delete;
  BackgroundTableWrites& operator=(const BackgroundTableWrites&) = delete;

  // Starts writing `table` (kept here until written) as writeTableFiles(table, type, dir,
  // formats) would, on a thread of its own.
  void write(Table4D table, SampleType type, const std::filesystem::path& dir,
             TableFormats formats);

  // Waits for every write and returns their manifest entries, table name → entry; rethrows the
  // first failure, in the order the writes were started.
  nlohmann::json finish();

 private:
  struct Pending {
    std::string name;
    std::shared_ptr<const Table4D> table;
    std::future<nlohmann::json> entry;
  };
  std::vector<Pending> pending_;
};

}  // namespace cloudlut::io
