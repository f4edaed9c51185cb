#pragma once
// Option parsing shared by the verbs: cxxopts errors become UsageError, and the value
// formats every verb accepts (dimension lists, integer ranges, vectors, the phase functions)
// are parsed in one place.
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <cxxopts.hpp>
#include <glm/vec3.hpp>

#include <tbb/global_control.h>

#include "core/Phase.h"

namespace cloudlut::cli {

// Parses argv. Returns false (after printing the help text to stdout) when --help was given.
// Unknown options, missing values and stray positional arguments throw UsageError.
bool parseOptions(cxxopts::Options& options, int argc, char** argv, cxxopts::ParseResult& out);

// "64,32,64,32" → {64, 32, 64, 32}; each in [2, 65536]. Throws UsageError naming the option.
std::array<int, 4> parseDims(const std::string& text, const std::string& option);

// "a:b" (inclusive range) or "a,b,c" → the integers; throws UsageError naming the option.
std::vector<int> parseIntList(const std::string& text, const std::string& option);

// Limits oneTBB to `threads` workers for the lifetime of the returned object (0 = all cores).
std::unique_ptr<tbb::global_control> limitThreads(int threads);

// The value of an option that must be positive.
double requirePositive(double value, const std::string& option);

// "lo,hi": two finite numbers with lo < hi whose difference is finite in float (a colour scale
// divides by it); UsageError naming the option.
std::pair<float, float> parseRangeOption(const std::string& text, const std::string& option);

// --extinction β (1/m) and --radius R (m) by the rules a file obeys too (core/ParameterRules.h):
// each in range and their product, the optical radius, too. UsageError naming the option.
void checkExtinctionRadius(double extinction, double radius);

// A default value as an option's text: "0.9", "183.8", "10" (six significant digits).
std::string defaultText(double value);

// "x,y,z" → three finite numbers (non-negative when `colour`); UsageError naming the option.
glm::vec3 parseVec3Option(const std::string& text, const std::string& option, bool colour);

// The phase-function options of every verb that takes them: --phase cs (Cornette–Shanks), hg
// (Henyey–Greenstein), jd (Jendersie–d'Eon) or iso; --g1 and --gm, the g of sunlight's first
// scattering and of every later one (cs, hg; in (−1, 1)); --droplet-um, the droplet diameter of
// jd (one phase for every order; [5, 50] µm, the fit's range). Defaults from core/Defaults.h.
// `defaultFromLuts`: --phase has no default (the verb takes the LUT set's phase functions, else
// the defaults); otherwise it defaults to cs.
void addPhaseOptions(cxxopts::Options& options, bool defaultFromLuts);

struct PhasePair {
  Phase first, later;  // sunlight's first scattering, every later one
};
// The phase functions the options name; nothing when --phase was not given and has no default.
// UsageError naming the option for an unknown kind or a value out of range.
std::optional<PhasePair> parsePhaseOptions(const cxxopts::ParseResult& args);

}  // namespace cloudlut::cli
