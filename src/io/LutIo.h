#pragma once
// Reading and writing LUT files: the binary format, the EXR atlas format and the manifest.
// Byte-level specification: lut_formats/FORMAT.md.
//
// Every writer writes to a temporary file in the destination directory and renames it over
// the final name, so a final name holds either nothing or a complete file.
// Every reader throws cloudlut::FileError naming the file and the problem (missing, truncated,
// checksum mismatch, wrong version, not a cloudlut LUT); none crashes on corrupt input.
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "core/Table4D.h"

namespace cloudlut::io {

// Version of the LUT formats (binary header, EXR "cloudlutVersion", manifest "version").
// 2 adds each axis's node concentration ("warp") and the scattering tables' log2 mean-source
// encoding; 3 adds the axis flags "folded" (mirror symmetry about the axis's max) and
// "linear in 2^value" (interpolation of a log2 axis). Versions 1 and 2 are still read (their
// axes are neither).
inline constexpr int kFormatVersion = 3;
inline constexpr int kOldestFormatVersion = 1;

// How the samples are stored: 8-bit unsigned normalised ([0, 1] → 0…255, round to nearest),
// IEEE half, or IEEE float.
enum class SampleType { U8 = 0, Half = 1, Float = 2 };

std::optional<SampleType> parseSampleType(std::string_view name);  // "u8", "half", "float"
std::string toString(SampleType type);

// FNV-1a 64-bit hash of the payload bytes as stored (little-endian samples).
std::uint64_t payloadChecksum(const Table4D& table, SampleType type);

// The table's self-description (name, dims, axes, channels, parameters, sample type,
// checksum): the object stored in the manifest and in the EXR header.
nlohmann::json describeTable(const Table4D& table, SampleType type);

// Binary format (FORMAT.md): fixed little-endian header, then the payload in Table4D layout.
void writeBinaryLut(const Table4D& table, SampleType type, const std::filesystem::path& path);

// EXR format: a 2D atlas of the 3D texture's depth slices, described in header attributes.
// SampleType::U8 is not representable in EXR and is rejected with UsageError.
void writeExrLut(const Table4D& table, SampleType type, const std::filesystem::path& path);

struct LoadedTable {
  Table4D table;          // values decoded to float
  SampleType sampleType;  // as stored
  bool checksumOk = true; // always true when returned: a mismatch throws
  std::filesystem::path path;
};

// Reads a binary or EXR LUT (chosen by the file's magic bytes, not its name).
LoadedTable readLut(const std::filesystem::path& path);

// A LUT directory: manifest.json plus one file (or one per format) per table.
struct LutSet {
  std::filesystem::path dir;
  nlohmann::json manifest;
  std::map<std::string, LoadedTable> tables;  // by table name, e.g. "optical_depth"
};

// Writes manifest.json atomically. `manifest` is the whole document (see FORMAT.md).
void writeManifest(const std::filesystem::path& dir, const nlohmann::json& manifest);

// Reads manifest.json and every table it lists (the binary file when there is one, else EXR).
LutSet readLutSet(const std::filesystem::path& dir);

// Writes `bytes` to `path` through a temporary file and a rename.
void writeFileAtomically(const std::filesystem::path& path, std::string_view bytes);

}  // namespace cloudlut::io
