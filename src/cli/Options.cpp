#include "cli/Options.h"

#include <charconv>
#include <cmath>
#include <cstdio>

#include <tbb/global_control.h>

#include "core/Errors.h"

namespace cloudlut::cli {

bool parseOptions(cxxopts::Options& options, int argc, char** argv, cxxopts::ParseResult& out) {
  options.add_options("help")("h,help", "print this help");
  try {
    out = options.parse(argc, argv);
  } catch (const cxxopts::exceptions::exception& e) {
    throw UsageError(e.what());
  }
  if (out.count("help")) {
    std::printf("%s\n", options.help().c_str());
    return false;
  }
  if (!out.unmatched().empty()) throw UsageError("unexpected argument '" + out.unmatched().front() + "'");
  return true;
}

namespace {
int parseInt(const std::string& s, const std::string& option) {
  int v = 0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || r.ec != std::errc() || r.ptr != s.data() + s.size())
    throw UsageError("--" + option + ": '" + s + "' is not an integer");
  return v;
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const auto pos = s.find(sep, start);
    parts.push_back(s.substr(start, pos == std::string::npos ? std::string::npos : pos - start));
    if (pos == std::string::npos) break;
    start = pos + 1;
  }
  return parts;
}
}  // namespace

std::array<int, 4> parseDims(const std::string& text, const std::string& option) {
  const auto parts = split(text, ',');
  if (parts.size() != 4) throw UsageError("--" + option + ": expected four comma-separated dimensions, got '" + text + "'");
  std::array<int, 4> dims{};
  for (int i = 0; i < 4; ++i) {
    dims[i] = parseInt(parts[i], option);
    if (dims[i] < 2 || dims[i] > 65536)
      throw UsageError("--" + option + ": dimension " + std::to_string(dims[i]) + " is out of range [2, 65536]");
  }
  return dims;
}

std::vector<int> parseIntList(const std::string& text, const std::string& option) {
  std::vector<int> values;
  const auto colon = text.find(':');
  if (colon != std::string::npos) {
    const int a = parseInt(text.substr(0, colon), option), b = parseInt(text.substr(colon + 1), option);
    if (b < a) throw UsageError("--" + option + ": empty range '" + text + "'");
    for (int i = a; i <= b; ++i) values.push_back(i);
  } else {
    for (const auto& p : split(text, ',')) values.push_back(parseInt(p, option));
  }
  return values;
}

std::unique_ptr<tbb::global_control> limitThreads(int threads) {
  if (threads < 0) throw UsageError("--threads must be 0 (all cores) or positive");
  if (threads == 0) return nullptr;
  return std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                               static_cast<std::size_t>(threads));
}

double requirePositive(double value, const std::string& option) {
  if (!(value > 0.0) || !std::isfinite(value))
    throw UsageError("--" + option + " must be a positive number");
  return value;
}

}  // namespace cloudlut::cli
