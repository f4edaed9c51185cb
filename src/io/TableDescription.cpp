// The JSON self-description of tables, and checks on the sizes that descriptions claim.
#include "io/TableDescription.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "core/AngularClosure.h"
#include "core/Errors.h"
#include "core/ParameterRules.h"
#include "core/ReferenceParticle.h"
#include "core/Defaults.h"
#include "io/Fnv1a.h"
#include "io/SampleCodec.h"

namespace cloudlut::io {

std::string checksumHex(std::uint64_t checksum) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(checksum));
  return text;
}

bool parseChecksumHex(const std::string& text, std::uint64_t& checksum) {
  if (text.size() != 16) return false;
  std::uint64_t v = 0;
  for (const char c : text) {
    int digit = -1;
    if (c >= '0' && c <= '9') digit = c - '0';
    else if (c >= 'a' && c <= 'f') digit = c - 'a' + 10;
    else if (c >= 'A' && c <= 'F') digit = c - 'A' + 10;
    if (digit < 0) return false;
    v = (v << 4) | static_cast<std::uint64_t>(digit);
  }
  checksum = v;
  return true;
}

nlohmann::json describeTableWith(const Table4D& table, SampleType type, std::uint64_t payloadBytes,
                                 std::uint64_t checksum) {
  using nlohmann::json;
  const auto d = table.dims();
  json axes = json::array();
  for (const Axis& a : table.axes())
    axes.push_back({{"name", a.name}, {"unit", a.unit}, {"min", a.min}, {"max", a.max},
                    {"size", a.size}, {"periodic", a.periodic}, {"warp", a.warp},
                    {"folded", a.folded}, {"linear_in_exp2", a.linearInExp2}});
  json channels = json::array();
  for (const Channel& c : table.channels())
    channels.push_back({{"name", c.name}, {"meaning", c.meaning}});
  return {{"name", table.name()},
          {"dims", {d[0], d[1], d[2], d[3]}},
          {"texture_size", {d[0], d[1], d[2] * d[3]}},
          {"axes", axes},
          {"channels", channels},
          {"parameters", table.parameters()},
          {"sample_type", toString(type)},
          {"payload_bytes", payloadBytes},
          {"payload_fnv1a64", checksumHex(checksum)}};
}

nlohmann::json describeTable(const Table4D& table, SampleType type) {
  const std::string payload = encodePayload(table, type);
  return describeTableWith(table, type, payload.size(), fnv1a64(payload));
}

void checkClaimedSize(const std::array<std::uint32_t, 4>& dims, std::uint32_t channels,
                      const std::filesystem::path& path) {
  std::array<int, 4> asInt{};
  for (int k = 0; k < 4; ++k) {
    if (dims[k] < 1 || dims[k] > 0x7fffffffu)
      throw FileError(path.string(), "corrupt header (axis " + std::to_string(k) + " has " +
                                         std::to_string(dims[k]) + " nodes)");
    // core's check wants every axis to have 2 nodes or more; a 1-node axis costs no more.
    asInt[k] = std::max(2, static_cast<int>(dims[k]));
  }
  try {
    checkTableFitsInMemory(asInt, static_cast<int>(channels));
  } catch (const std::exception& e) {
    throw FileError(path.string(), std::string("claims a table too large to load: ") + e.what());
  }
}

void checkTableParameters(const nlohmann::json& p, const std::filesystem::path& path) {
  if (p.is_null()) return;
  if (!p.is_object()) throw FileError(path.string(), "parameters: expected a JSON object");
  const auto fail = [&](const std::string& field, const std::string& problem) {
    throw FileError(path.string(), "parameters." + field + ": " + problem);
  };
  std::string problem;
  double beta = defaults::kExtinctionPerMetre, radius = defaults::kParticleRadiusMetres;
  if (p.contains("extinction_per_m")) {
    const std::optional<double> v = rules::numberFromJson(p["extinction_per_m"], problem);
    if (!v) fail("extinction_per_m", problem);
    if (problem = rules::extinctionProblem(*v); !problem.empty()) fail("extinction_per_m", problem);
    beta = *v;
  }
  if (p.contains("radius_m")) {
    const std::optional<double> v = rules::numberFromJson(p["radius_m"], problem);
    if (!v) fail("radius_m", problem);
    if (problem = rules::radiusProblem(*v); !problem.empty()) fail("radius_m", problem);
    radius = *v;
  }
  if (problem = rules::opticalRadiusProblem(beta, radius); !problem.empty()) fail("extinction_per_m", problem);
  for (const char* key : {"first_phase", "later_phase"})
    if (p.contains(key) && !rules::phaseFromJsonChecked(p[key], problem)) fail(key, problem);
  if (p.contains("seed") && !rules::seedFromJson(p["seed"], problem)) fail("seed", problem);
  if (p.contains("chord_outer_third_share")) {
    const std::optional<double> v = rules::numberFromJson(p["chord_outer_third_share"], problem);
    if (!v) fail("chord_outer_third_share", problem);
    if (problem = rules::chordOuterThirdProblem(*v); !problem.empty()) fail("chord_outer_third_share", problem);
  }
  if (p.contains("angular_closure") && !angularClosureFromJson(p["angular_closure"], problem))
    fail("angular_closure", problem);
  if (p.contains("density_model")) {
    const nlohmann::json& m = p["density_model"];
    if (!m.is_string() || !parseDensityModel(m.get<std::string>()))
      fail("density_model", "expected one of noise, threshold, pyroclastic, radial, sphere, got " + m.dump());
  }
}

namespace {

// The value of key `key` of `object` if it has type `T`, else a FileError naming the key.
template <typename T>
T required(const nlohmann::json& object, const char* key, const std::filesystem::path& path) {
  if (!object.is_object() || !object.contains(key))
    throw FileError(path.string(), std::string("table description lacks \"") + key + "\"");
  try {
    return object.at(key).get<T>();
  } catch (const nlohmann::json::exception&) {
    throw FileError(path.string(), std::string("table description has a bad \"") + key + "\"");
  }
}

}  // namespace

Table4D tableFromDescription(const nlohmann::json& description, const std::filesystem::path& path,
                             std::uint64_t maxSamples) {
  using nlohmann::json;
  const auto axesJson = required<json>(description, "axes", path);
  const auto channelsJson = required<json>(description, "channels", path);
  if (!axesJson.is_array() || axesJson.size() != 4)
    throw FileError(path.string(), "table description must have 4 axes");
  if (!channelsJson.is_array() || channelsJson.empty() || channelsJson.size() > 4)
    throw FileError(path.string(), "table description must have 1 to 4 channels");
  std::array<Axis, 4> axes;
  std::array<std::uint32_t, 4> dims{};
  for (int k = 0; k < 4; ++k) {
    const json& a = axesJson[static_cast<std::size_t>(k)];
    axes[k].name = required<std::string>(a, "name", path);
    axes[k].unit = required<std::string>(a, "unit", path);
    axes[k].min = required<double>(a, "min", path);
    axes[k].max = required<double>(a, "max", path);
    axes[k].periodic = required<bool>(a, "periodic", path);
    if (!std::isfinite(axes[k].min) || !std::isfinite(axes[k].max) || !(axes[k].min <= axes[k].max))
      throw FileError(path.string(), "axes[" + std::to_string(k) + "]: min and max must be finite with min <= max");
    // "warp" (node concentration, cloudlut_geometry.glsl) is absent from older files: uniform.
    if (a.contains("warp")) {
      axes[k].warp = required<double>(a, "warp", path);
      if (!(axes[k].warp >= 0.0 && axes[k].warp <= 20.0))
        throw FileError(path.string(), "axis " + std::to_string(k) + " has a bad node concentration");
    }
    // "folded" and "linear_in_exp2" (version 3, FORMAT.md section 1) are absent from older files.
    if (a.contains("folded")) axes[k].folded = required<bool>(a, "folded", path);
    if (a.contains("linear_in_exp2")) axes[k].linearInExp2 = required<bool>(a, "linear_in_exp2", path);
    if (axes[k].folded && axes[k].periodic)
      throw FileError(path.string(), "axis " + std::to_string(k) + " is both periodic and folded");
    const auto size = required<std::int64_t>(a, "size", path);
    if (size < 1 || size > 0x7fffffff)
      throw FileError(path.string(), "axis " + std::to_string(k) + " has " + std::to_string(size) +
                                         " nodes");
    axes[k].size = static_cast<int>(size);
    dims[k] = static_cast<std::uint32_t>(size);
  }
  std::vector<Channel> channels;
  for (const json& c : channelsJson)
    channels.push_back({required<std::string>(c, "name", path),
                        c.is_object() && c.contains("meaning") && c["meaning"].is_string()
                            ? c["meaning"].get<std::string>()
                            : std::string()});
  // each size is below 2^31 and there are at most 4 channels: the product needs 126 bits at most,
  // so it is formed in long double, exact up to 2^64
  long double samples = static_cast<long double>(channels.size());
  for (const std::uint32_t d : dims) samples *= d;
  if (samples > static_cast<long double>(maxSamples))
    throw FileError(path.string(), "the description claims a table of " + std::to_string(dims[0]) + "x" +
                                       std::to_string(dims[1]) + "x" + std::to_string(dims[2]) + "x" +
                                       std::to_string(dims[3]) + " nodes x " + std::to_string(channels.size()) +
                                       " channels, more than the " + std::to_string(maxSamples) +
                                       " samples its data holds");
  checkClaimedSize(dims, static_cast<std::uint32_t>(channels.size()), path);
  Table4D table(required<std::string>(description, "name", path), axes, std::move(channels));
  if (description.contains("parameters") && description["parameters"].is_object())
    table.parameters() = description["parameters"];
  return table;
}

}  // namespace cloudlut::io
