#pragma once
// The format-specific readers behind readLut (which picks one by the file's magic bytes).
#include <cstdint>
#include <filesystem>

#include "io/LutIo.h"

namespace cloudlut::io {

// Reads a binary-format LUT; throws FileError naming the file and the problem.
LoadedTable readBinaryLut(const std::filesystem::path& path);

// Reads an EXR-atlas LUT; throws FileError naming the file and the problem.
LoadedTable readExrLut(const std::filesystem::path& path);

// The size of an existing regular file in bytes; FileError "missing" or "not a regular file".
std::uint64_t existingFileSize(const std::filesystem::path& path);

}  // namespace cloudlut::io
