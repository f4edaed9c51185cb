#pragma once
// Rows of `cloudlut bench`: one measured configuration each, written as CSV and printed.
// Every row of one run is measured on the same machine in the same process, so ratios
// between rows are meaningful even when the machine is shared and noisy.
#include <filesystem>
#include <string>
#include <vector>

namespace cloudlut::bench {

struct BenchRow {
  std::string suite;       // "optical-depth", "scattering", ...
  std::string method;      // e.g. "gauss2", "fast", "paper"
  std::string table;       // e.g. "optical_depth", "multiple_scattering"
  std::string variant;     // model, phase or other setting
  std::string resolution;  // "64x32x64x32"
  std::string orders;      // "18", "converged", "" when not applicable
  int steps = 0;           // samples per diameter or integration steps, 0 when n/a
  int threads = 0;
  double seconds = 0.0;
  double errorMean = -1.0;  // against the suite's independent reference; -1 when not measured
  double errorP95 = -1.0;
  double errorMax = -1.0;
  double energy = -1.0;     // share of incident power accounted for, -1 when n/a
  std::string note;
};

class BenchReport {
 public:
  void add(BenchRow row);
  const std::vector<BenchRow>& rows() const { return rows_; }
  // Writes all rows as CSV (header included) atomically.
  void writeCsv(const std::filesystem::path& path) const;
  // Prints one aligned line per row to stdout.
  void print() const;

 private:
  std::vector<BenchRow> rows_;
};

// Summary statistics of absolute errors.
struct ErrorStats {
  double mean = 0.0, p95 = 0.0, max = 0.0;
};
ErrorStats summarizeErrors(std::vector<double> errors);

}  // namespace cloudlut::bench
