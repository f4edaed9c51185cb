#include "io/BackgroundTableWrites.h"

#include <utility>

namespace cloudlut::io {

BackgroundTableWrites::~BackgroundTableWrites() {
  for (Pending& p : pending_)
    if (p.entry.valid()) p.entry.wait();
}

void BackgroundTableWrites::write(Table4D table, SampleType type, const std::filesystem::path& dir,
                                  TableFormats formats) {
  Pending p;
  p.name = table.name();
  p.table = std::make_shared<const Table4D>(std::move(table));
  // The task holds its own reference to the table: it stays alive until written.
  p.entry = std::async(std::launch::async, [t = p.table, type, dir, formats] {
    return writeTableFiles(*t, type, dir, formats);
  });
  pending_.push_back(std::move(p));
}

nlohmann::json BackgroundTableWrites::finish() {
  nlohmann::json entries = nlohmann::json::object();
  // every write ends before the first failure is raised
  for (Pending& p : pending_) p.entry.wait();
  for (Pending& p : pending_) entries[p.name] = p.entry.get();
  pending_.clear();
  return entries;
}

}  // namespace cloudlut::io
