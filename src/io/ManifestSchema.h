#pragma once
// The schema of a LUT set's manifest.json (lut_formats/FORMAT.md §4), owned here for both
// directions: writers (`cloudlut bake`, the ground-truth bench) build their table entries and
// the document with these functions, and readLutSet (io/LutIo.h) checks a document with the
// same rules before it loads a table.
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "core/Table4D.h"
#include "io/LutIo.h"

namespace cloudlut::io {

inline constexpr const char* kManifestName = "manifest.json";
inline constexpr const char* kManifestFormat = "cloudlut-lut-set";

// The files a table is written to.
struct TableFormats {
  bool bin = true;
  bool exr = true;
};

// Writes `table` as DIR/NAME.bin and/or DIR/NAME.exr (each through a temporary file and a
// rename; EXR cannot hold u8 samples, so an 8-bit table's EXR copy is half) and returns its
// manifest entry (§4.1): describeTable(table, type), "files" and, when the EXR copy's sample
// type differs from `type`, "exr_sample_type".
nlohmann::json writeTableFiles(const Table4D& table, SampleType type, const std::filesystem::path& dir,
                               TableFormats formats);

// A manifest document: "format", "version" (kFormatVersion), "generator" and "tables" (table
// name → entry from writeTableFiles); a writer adds its free-form "parameters" and reports.
// Checked with checkManifest (and each entry with manifestTableFile): a writer cannot produce
// a document its readers refuse.
nlohmann::json makeManifest(const std::string& generator, const nlohmann::json& tables);

// Checks the document's header: an object whose "format" is kManifestFormat, an integer
// "version" in [kOldestFormatVersion, kFormatVersion] and a "tables" object. FileError(`where`,
// ...) naming the field otherwise.
void checkManifest(const nlohmann::json& manifest, const std::string& where);

// The file a table entry points to: "bin" when listed, else "exr"; a relative path inside the
// LUT directory (neither absolute nor through ".."). FileError(`where`, "table 'NAME' ...").
std::filesystem::path manifestTableFile(const std::string& where, const std::string& name, const nlohmann::json& entry);

// The entry's "dims", four integers; FileError(`file`, ...) naming the table when absent or bad.
std::array<int, 4> manifestTableDims(const std::string& file, const std::string& name, const nlohmann::json& entry);

}  // namespace cloudlut::io
