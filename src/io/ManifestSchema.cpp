#include "io/ManifestSchema.h"

#include "core/Errors.h"

namespace cloudlut::io {

nlohmann::json writeTableFiles(const Table4D& table, SampleType type, const std::filesystem::path& dir,
                               TableFormats formats) {
  nlohmann::json entry = describeTable(table, type);
  nlohmann::json files = nlohmann::json::object();
  if (formats.bin) {
    const std::string name = table.name() + ".bin";
    writeBinaryLut(table, type, dir / name);
    files["bin"] = name;
  }
  if (formats.exr) {
    const SampleType exrType = type == SampleType::U8 ? SampleType::Half : type;
    const std::string name = table.name() + ".exr";
    writeExrLut(table, exrType, dir / name);
    files["exr"] = name;
    if (exrType != type) entry["exr_sample_type"] = toString(exrType);
  }
  entry["files"] = files;
  return entry;
}

nlohmann::json makeManifest(const std::string& generator, const nlohmann::json& tables) {
  nlohmann::json manifest;
  manifest["format"] = kManifestFormat;
  manifest["version"] = kFormatVersion;
  manifest["generator"] = generator;
  manifest["tables"] = tables;
  const std::string where = "(manifest written by " + generator + ")";
  checkManifest(manifest, where);
  for (const auto& [name, entry] : manifest["tables"].items()) {
    manifestTableFile(where, name, entry);
    manifestTableDims(where, name, entry);
  }
  return manifest;
}

void checkManifest(const nlohmann::json& m, const std::string& where) {
  if (!m.is_object() || !m.contains("format") || m["format"] != kManifestFormat)
    throw FileError(where, std::string("not a cloudlut manifest (\"format\" is not \"") + kManifestFormat + "\")");
  if (!m.contains("version") || !m["version"].is_number_integer())
    throw FileError(where, "manifest has no integer \"version\"");
  const long long version = m["version"].get<long long>();
  if (version < kOldestFormatVersion || version > kFormatVersion)
    throw FileError(where, "unsupported manifest version " + std::to_string(version) + " (this build reads " +
                               std::to_string(kOldestFormatVersion) + " to " + std::to_string(kFormatVersion) + ")");
  if (!m.contains("tables") || !m["tables"].is_object()) throw FileError(where, "manifest has no \"tables\" object");
}

std::filesystem::path manifestTableFile(const std::string& where, const std::string& name, const nlohmann::json& entry) {
  const auto fail = [&](const std::string& problem) { throw FileError(where, "table '" + name + "' " + problem); };
  if (!entry.is_object() || !entry.contains("files") || !entry["files"].is_object()) fail("has no \"files\" object");
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

std::array<int, 4> manifestTableDims(const std::string& file, const std::string& name, const nlohmann::json& entry) {
  if (!entry.contains("dims") || !entry["dims"].is_array() || entry["dims"].size() != 4)
    throw FileError(file, "manifest.json gives no \"dims\" for table '" + name + "'");
  std::array<int, 4> dims{};
  for (std::size_t k = 0; k < 4; ++k) {
    const nlohmann::json& v = entry["dims"][k];
    if (!v.is_number_integer()) throw FileError(file, "manifest.json has bad \"dims\" for table '" + name + "'");
    dims[k] = v.get<int>();
  }
  return dims;
}

}  // namespace cloudlut::io
