#include "bench/BenchReport.h"

#include <algorithm>
#include <cstdio>
#include <numeric>
#include <sstream>

#include "io/LutIo.h"

namespace cloudlut::bench {

void BenchReport::add(BenchRow row) {
  rows_.push_back(std::move(row));
}

namespace {
std::string num(double v) {
  if (v < 0.0) return "";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}
}  // namespace

void BenchReport::writeCsv(const std::filesystem::path& path) const {
  std::ostringstream out;
  out << "suite,method,table,variant,resolution,orders,steps,threads,seconds,error_mean,error_p95,error_max,energy,note\n";
  for (const BenchRow& r : rows_)
    out << r.suite << ',' << r.method << ',' << r.table << ',' << r.variant << ',' << r.resolution << ','
        << r.orders << ',' << r.steps << ',' << r.threads << ',' << num(r.seconds) << ',' << num(r.errorMean)
        << ',' << num(r.errorP95) << ',' << num(r.errorMax) << ',' << num(r.energy) << ',' << r.note << '\n';
  io::writeFileAtomically(path, out.str());
}

void BenchReport::print() const {
  std::printf("%-14s %-8s %-20s %-12s %-13s %-9s %5s %3s %9s %10s %10s %10s %7s  %s\n", "suite", "method",
              "table", "variant", "resolution", "orders", "steps", "thr", "seconds", "err_mean", "err_p95",
              "err_max", "energy", "note");
  for (const BenchRow& r : rows_)
    std::printf("%-14s %-8s %-20s %-12s %-13s %-9s %5d %3d %9.4f %10s %10s %10s %7s  %s\n", r.suite.c_str(),
                r.method.c_str(), r.table.c_str(), r.variant.c_str(), r.resolution.c_str(), r.orders.c_str(),
                r.steps, r.threads, r.seconds, num(r.errorMean).c_str(), num(r.errorP95).c_str(),
                num(r.errorMax).c_str(), num(r.energy).c_str(), r.note.c_str());
}

ErrorStats summarizeErrors(std::vector<double> errors) {
  ErrorStats s;
  if (errors.empty()) return s;
  std::sort(errors.begin(), errors.end());
  s.mean = std::accumulate(errors.begin(), errors.end(), 0.0) / static_cast<double>(errors.size());
  s.p95 = errors[static_cast<std::size_t>(0.95 * static_cast<double>(errors.size() - 1))];
  s.max = errors.back();
  return s;
}

}  // namespace cloudlut::bench
