#pragma once
// The geometry CSV read by `cloudlut query` and `cloudlut reference sphere`: a header line,
// then rows `sx,sy,sz,vx,vy,vz,lx,ly,lz,density` in particle space (docs/ENGINE_GUIDE.md §2:
// S on the unit sphere, v pointing into it, l toward the sun; density = the particle's
// density scale ρ).
#include <filesystem>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace cloudlut::io {

struct QueryRow {
  glm::vec3 S;    // entry point, normalised on read
  glm::vec3 v;    // view direction, normalised on read
  glm::vec3 l;    // toward the sun, normalised on read
  float density;  // ρ > 0
  std::string text;  // the row as read, echoed in the output
};

struct QueryCsv {
  std::string header;  // the header line as read
  std::vector<QueryRow> rows;
};

// Throws FileError naming the file and line for a missing file, a short row, a value that is
// not a finite number, a zero vector or a non-positive density.
QueryCsv readQueryCsv(const std::filesystem::path& path);

}  // namespace cloudlut::io
