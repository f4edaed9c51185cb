#pragma once
// Option parsing shared by the verbs: cxxopts errors become UsageError, and the value
// formats every verb accepts (dimension lists, integer ranges) are parsed in one place.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include <cxxopts.hpp>

#include <tbb/global_control.h>

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

}  // namespace cloudlut::cli
