// manifest.json: the list of a LUT directory's tables and their files (FORMAT.md §4; the
// schema's rules are io/ManifestSchema.h's).
#include <fstream>
#include <sstream>

#include "core/Errors.h"
#include "io/LutIo.h"
#include "io/LutReaders.h"
#include "io/ManifestSchema.h"

namespace cloudlut::io {

namespace {

// "AxBxCxD".
std::string dimsText(const std::array<int, 4>& d) {
  return std::to_string(d[0]) + "x" + std::to_string(d[1]) + "x" + std::to_string(d[2]) + "x" +
         std::to_string(d[3]);
}

// The manifest document at `path`, checked to be a cloudlut LUT set of a supported version.
nlohmann::json readManifestDocument(const std::filesystem::path& path) {
  existingFileSize(path);
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  if (!in) throw FileError(path.string(), "cannot be read");
  nlohmann::json m = nlohmann::json::parse(text.str(), nullptr, false);
  if (m.is_discarded()) throw FileError(path.string(), "invalid JSON");
  checkManifest(m, path.string());
  return m;
}

// Throws FileError(file, ...) unless the loaded table's dims (and channel count, when the
// manifest lists channels) are the manifest's.
void checkAgainstManifest(const std::filesystem::path& file, const std::string& name,
                          const nlohmann::json& entry, const Table4D& table) {
  const std::array<int, 4> listed = manifestTableDims(file.string(), name, entry);
  if (listed != table.dims())
    throw FileError(file.string(), "dimensions " + dimsText(table.dims()) +
                                       " do not match manifest.json's " + dimsText(listed));
  if (entry.contains("channels") && entry["channels"].is_array() &&
      entry["channels"].size() != table.channels().size())
    throw FileError(file.string(), std::to_string(table.channels().size()) +
                                       " channels, manifest.json lists " +
                                       std::to_string(entry["channels"].size()));
}

}  // namespace

// Writes the document, indented, through writeFileAtomically.
void writeManifest(const std::filesystem::path& dir, const nlohmann::json& manifest) {
  if (!manifest.is_object()) throw UsageError("a manifest must be a JSON object");
  writeFileAtomically(dir / kManifestName, manifest.dump(2) + "\n");
}

// Reads and checks manifest.json, then loads each table's preferred file and checks it
// against its entry.
LutSet readLutSet(const std::filesystem::path& dir) {
  const std::filesystem::path manifestPath = dir / kManifestName;
  LutSet set{dir, readManifestDocument(manifestPath), {}};
  for (const auto& [name, entry] : set.manifest["tables"].items()) {
    const std::filesystem::path file = dir / manifestTableFile(manifestPath.string(), name, entry);
    std::error_code ec;
    if (!std::filesystem::exists(file, ec))
      throw FileError(file.string(), "missing (listed in " + manifestPath.string() + ")");
    LoadedTable loaded = readLut(file);
    checkAgainstManifest(file, name, entry, loaded.table);
    set.tables.emplace(name, std::move(loaded));
  }
  return set;
}

}  // namespace cloudlut::io
