// Fuzzes a table's JSON description (lut_formats/FORMAT.md §3): the parse, the empty table it
// describes (io/TableDescription) and the physical-parameter rules (core/ParameterRules.h), then
// the lookups `query` makes with a table that passed them. A bad description throws; nothing
// crashes, and a table that passes yields finite optical depths.
#include <cmath>
#include <cstdlib>
#include <exception>
#include <string>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "core/Phase.h"
#include "core/TableLookup.h"
#include "io/TableDescription.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const nlohmann::json description =
      nlohmann::json::parse(std::string(reinterpret_cast<const char*>(data), size), nullptr, false);
  if (description.is_discarded()) return 0;
  try {
    // as if the data that came with it held 2^24 samples (64 MiB of floats)
    cloudlut::Table4D table = cloudlut::io::tableFromDescription(description, "fuzz.json", 1u << 24);
    cloudlut::io::checkTableParameters(table.parameters(), "fuzz.json");
    const float sigma = cloudlut::unitOpticalRadius(table);
    if (!(sigma > 0.0f) || !std::isfinite(sigma)) std::abort();  // the rules promise a positive, finite σ
    const cloudlut::Phase first = cloudlut::recordedPhase(table.parameters(), "first_phase", cloudlut::Phase{});
    if (!(cloudlut::phaseValue(first, 0.5f) >= 0.0f)) std::abort();  // a valid phase is never negative
    if (table.nodeCount() <= 4096) {  // the lookup itself, on small tables (their values are 0)
      const glm::vec3 S(0.0f, 0.0f, 1.0f), v = glm::normalize(glm::vec3(0.3f, 0.1f, -1.0f));
      (void)cloudlut::lookupOpticalDepth(table, S, v, 1.0f);
    }
  } catch (const std::exception&) {
  }
  return 0;
}
