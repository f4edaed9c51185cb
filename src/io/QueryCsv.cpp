#include "io/QueryCsv.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include <glm/geometric.hpp>

#include "core/Errors.h"

namespace cloudlut::io {

namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  const auto e = s.find_last_not_of(" \t\r");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

// `text` with every byte outside printable ASCII as \xNN, so that a message carries all of it
// (a NUL byte would end it).
std::string printable(const std::string& text) {
  std::string out;
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (u >= 0x20 && u < 0x7f) {
      out += c;
    } else {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", u);
      out += buf;
    }
  }
  return out;
}

}  // namespace

QueryCsv readQueryCsv(const std::filesystem::path& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status)) throw FileError(path.string(), "missing (no such CSV file)");
  if (std::filesystem::is_directory(status)) throw FileError(path.string(), "is a directory, not a CSV file");
  std::ifstream in(path);
  if (!in) throw FileError(path.string(), "cannot open the CSV file");
  QueryCsv csv;
  std::string line;
  if (!std::getline(in, line)) throw FileError(path.string(), "empty file: expected a header line");
  csv.header = trim(line);
  int lineNo = 1;
  while (std::getline(in, line)) {
    ++lineNo;
    line = trim(line);
    if (line.empty()) continue;
    float values[10];
    int count = 0;
    std::stringstream ss(line);
    std::string field;
    const std::string where = "line " + std::to_string(lineNo) + ": ";
    while (std::getline(ss, field, ',')) {
      if (count == 10) throw FileError(path.string(), where + "more than 10 columns");
      field = trim(field);
      float v = 0.0f;
      const auto res = std::from_chars(field.data(), field.data() + field.size(), v);
      if (res.ec != std::errc() || res.ptr != field.data() + field.size() || !std::isfinite(v))
        throw FileError(path.string(), where + "'" + printable(field) + "' is not a finite number");
      values[count++] = v;
    }
    if (count != 10)
      throw FileError(path.string(), where + "expected 10 columns (sx,sy,sz,vx,vy,vz,lx,ly,lz,density), found " +
                                         std::to_string(count));
    QueryRow row;
    const glm::vec3 S(values[0], values[1], values[2]), v(values[3], values[4], values[5]),
        l(values[6], values[7], values[8]);
    if (glm::length(S) < 1e-6f || glm::length(v) < 1e-6f || glm::length(l) < 1e-6f)
      throw FileError(path.string(), where + "S, v and l must be non-zero vectors");
    if (!(values[9] > 0.0f)) throw FileError(path.string(), where + "density must be positive");
    row.S = glm::normalize(S);
    row.v = glm::normalize(v);
    row.l = glm::normalize(l);
    row.density = values[9];
    row.text = line;
    csv.rows.push_back(std::move(row));
  }
  return csv;
}

}  // namespace cloudlut::io
