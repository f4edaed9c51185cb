// readLut: picks the reader by the file's first bytes, then checks the table's physical parameters.
#include <cstring>
#include <fstream>

#include "core/Errors.h"
#include "io/BinaryHeader.h"
#include "io/LutReaders.h"
#include "io/TableDescription.h"

namespace cloudlut::io {

// The size of `path`, after checking that it exists and is a regular file.
std::uint64_t existingFileSize(const std::filesystem::path& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status)) throw FileError(path.string(), "missing");
  if (!std::filesystem::is_regular_file(status))
    throw FileError(path.string(), "not a regular file");
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) throw FileError(path.string(), "cannot be read (" + ec.message() + ")");
  return size;
}

// "CLOUDLUT" (or a prefix of it, which the binary reader reports as truncated) selects the
// binary reader, 0x76 0x2f 0x31 0x01 the EXR reader; anything else is not a LUT.
LoadedTable readLut(const std::filesystem::path& path) {
  const std::uint64_t size = existingFileSize(path);
  if (size == 0) throw FileError(path.string(), "not a cloudlut LUT (empty file)");
  std::ifstream in(path, std::ios::binary);
  char magic[8] = {};
  in.read(magic, sizeof magic);
  const auto got = static_cast<std::size_t>(in.gcount());
  if (got == 0) throw FileError(path.string(), "cannot be read");
  const unsigned char exr[4] = {0x76, 0x2f, 0x31, 0x01};
  const bool binary = std::string_view(magic, got) == std::string_view(binary::kMagic, got);
  if (!binary && !(got >= 4 && std::memcmp(magic, exr, 4) == 0))
    throw FileError(path.string(), "not a cloudlut LUT (bad magic)");
  LoadedTable loaded = binary ? readBinaryLut(path) : readExrLut(path);
  // physical parameters obey the command line's rules, whatever the format (core/ParameterRules.h)
  checkTableParameters(loaded.table.parameters(), path);
  return loaded;
}

}  // namespace cloudlut::io
