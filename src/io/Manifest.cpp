// manifest.json: the list of a LUT directory's tables and their files (FORMAT.md).
#include <fstream>
#include <sstream>

#include "core/Errors.h"
#include "io/LutIo.h"
#include "io/LutReaders.h"

namespace cloudlut::io {

namespace {

constexpr const char* kManifestName = "manifest.json";
constexpr const char* kManifestFormat = "cloudlut-lut-set";

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
  if (!m.is_object() || !m.contains("format") || m["format"] != kManifestFormat)
    throw FileError(path.string(), std::string("not a cloudlut manifest (\"format\" is not \"") +
                                       kManifestFormat + "\")");
  if (!m.contains("version") || !m["version"].is_number_integer())
    throw FileError(path.string(), "manifest has no integer \"version\"");
  if (m["version"].get<long long>() < kOldestFormatVersion || m["version"].get<long long>() > kFormatVersion)
    throw FileError(path.string(), "unsupported manifest version " +
                                       std::to_string(m["version"].get<long long>()) +
                                       " (this build reads " + std::to_string(kOldestFormatVersion) + " to " +
                                       std::to_string(kFormatVersion) + ")");
  if (!m.contains("tables") || !m["tables"].is_object())
    throw FileError(path.string(), "manifest has no \"tables\" object");
  return m;
}

// The file a table entry points to: "bin" when listed, else "exr"; a relative path inside the
// LUT directory (no absolute paths, no "..").
std::filesystem::path tableFile(const std::filesystem::path& manifestPath, const std::string& name,
                                const nlohmann::json& entry) {
  const auto fail = [&](const std::string& problem) {
    throw FileError(manifestPath.string(), "table '" + name + "' " + problem);
  };
  if (!entry.is_object() || !entry.contains("files") || !entry["files"].is_object())
    fail("has no \"files\" object");
  const nlohmann::json& files = entry["files"];
  const char* key = files.contains("bin") ? "bin" : files.contains("exr") ? "exr" : nullptr;
  if (key == nullptr) fail("lists neither a \"bin\" nor an \"exr\" file");
  if (!files[key].is_string()) fail(std::string("has a non-string \"") + key + "\" file");
  const std::filesystem::path file = files[key].get<std::string>();
  if (file.empty() || file.is_absolute()) fail("names a file outside the LUT directory");
  for (const auto& part : file)
    if (part == "..") fail("names a file outside the LUT directory");
  return file;
}

// Throws FileError(file, ...) unless the loaded table's dims (and channel count, when the
// manifest lists channels) are the manifest's.
void checkAgainstManifest(const std::filesystem::path& file, const std::string& name,
                          const nlohmann::json& entry, const Table4D& table) {
  if (!entry.contains("dims") || !entry["dims"].is_array() || entry["dims"].size() != 4)
    throw FileError(file.string(), "manifest.json gives no \"dims\" for table '" + name + "'");
  std::array<int, 4> listed{};
  for (std::size_t k = 0; k < 4; ++k) {
    const nlohmann::json& v = entry["dims"][k];
    if (!v.is_number_integer())
      throw FileError(file.string(), "manifest.json has bad \"dims\" for table '" + name + "'");
    listed[k] = v.get<int>();
  }
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
    const std::filesystem::path file = dir / tableFile(manifestPath, name, entry);
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
