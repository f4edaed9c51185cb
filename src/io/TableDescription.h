#pragma once
// The JSON self-description of a table (describeTable) and the way back to an empty Table4D.
#include <array>
#include <cstdint>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "io/LutIo.h"

namespace cloudlut::io {

// describeTable with the payload size and checksum already known (avoids encoding twice).
nlohmann::json describeTableWith(const Table4D& table, SampleType type, std::uint64_t payloadBytes,
                                 std::uint64_t checksum);

// The checksum as written in JSON: 16 lowercase hexadecimal digits.
std::string checksumHex(std::uint64_t checksum);

// Parses 16 hexadecimal digits; false if `text` is not exactly that.
bool parseChecksumHex(const std::string& text, std::uint64_t& checksum);

// A table with the name, axes, channels and parameters of `description` and every value 0.
// Throws FileError(path, ...) if the description is incomplete or inconsistent, if the table it
// claims (nodes × channels) has more than `maxSamples` samples, the most the data that comes
// with it can hold, or if it would not fit in memory; all checked before allocating. A
// description is only a claim: a file of a few bytes must not make its reader allocate gigabytes.
Table4D tableFromDescription(const nlohmann::json& description, const std::filesystem::path& path,
                             std::uint64_t maxSamples);

// Checks the physical parameters a table records (lut_formats/FORMAT.md: extinction_per_m,
// radius_m, their product, first_phase, later_phase, seed, density_model; each when present)
// by the rules the command line applies (core/ParameterRules.h). FileError(path,
// "parameters.FIELD: problem") for the first that breaks one, wrong JSON types included.
void checkTableParameters(const nlohmann::json& parameters, const std::filesystem::path& path);

// Throws FileError(path, ...) if a table of these dims and channels would not fit in memory.
void checkClaimedSize(const std::array<std::uint32_t, 4>& dims, std::uint32_t channels,
                      const std::filesystem::path& path);

}  // namespace cloudlut::io
