#pragma once
// Table4D: a 4D look-up table of float samples with named axes and channels.
//
// Layout (the same in memory, in binary files and in the GL 3D texture): axis 0 varies fastest,
// then axis 1, then axes 2 and 3, which the 3D texture folds into its depth
// (depth = i2 + N2 · i3); channels are interleaved. Node i of an axis of n nodes sits at the
// axis fraction i / (n - 1): both ends of every axis are stored, so periodic axes repeat their
// first node as their last one and need no wrap-around when sampled.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace cloudlut {

// One axis: a physical quantity sampled at `size` nodes from `min` to `max`.
struct Axis {
  std::string name;     // e.g. "phi_s"
  std::string unit;     // "rad", "log2" ...
  double min = 0.0;     // value at node 0
  double max = 1.0;     // value at node size-1
  int size = 1;         // number of nodes, >= 2 for an interpolated axis
  bool periodic = false;
  // Concentration of the nodes about the middle of the axis (concentratedFraction in
  // cloudlut_geometry.glsl); 0 = uniformly spaced nodes.
  double warp = 0.0;
  // Mirror symmetry (format version 3): the table's quantity is symmetric about the axis's max,
  // value(max + d) = value(max − d), and only [min, max] is stored; a query beyond max samples
  // at 2·max − x (the scattering tables' φv over [0, π], mirroredAzimuth in
  // cloudlut_geometry.glsl).
  bool folded = false;
  // Interpolation (format version 3): the axis is a log2 (nodes uniform in s) and the table is
  // interpolated between two neighbouring nodes linearly in 2^s, not in s (the scattering
  // tables' density axis: linear in ρ, densityAxisLinearInRho in cloudlut_geometry.glsl).
  bool linearInExp2 = false;
  // The physical value at node i: min + (max − min) · concentratedFraction(i / (size − 1), warp).
  double value(int i) const;
};

struct Channel {
  std::string name;     // e.g. "mean_density"
  std::string meaning;  // one line for people
};

class Table4D {
 public:
  Table4D() = default;
  Table4D(std::string name, std::array<Axis, 4> axes, std::vector<Channel> channels);

  const std::string& name() const { return name_; }
  const std::array<Axis, 4>& axes() const { return axes_; }
  const std::vector<Channel>& channels() const { return channels_; }
  int channelCount() const { return static_cast<int>(channels_.size()); }
  std::array<int, 4> dims() const;
  std::size_t nodeCount() const;
  std::size_t valueCount() const { return data_.size(); }

  std::size_t index(int i0, int i1, int i2, int i3) const {
    return ((static_cast<std::size_t>(i3) * axes_[2].size + i2) * axes_[1].size + i1) *
               axes_[0].size + i0;
  }
  float& at(std::size_t node, int channel) { return data_[node * channels_.size() + channel]; }
  float at(std::size_t node, int channel) const { return data_[node * channels_.size() + channel]; }

  std::vector<float>& data() { return data_; }
  const std::vector<float>& data() const { return data_; }

  // Parameters that produced the table (extinction, radius, phase, model, seed ...).
  nlohmann::json& parameters() { return parameters_; }
  const nlohmann::json& parameters() const { return parameters_; }

  // Quadrilinear interpolation at axis fractions x ∈ [0, 1]⁴ (clamped), one value per channel
  // written to out (sampleQuadrilinear, lut_formats/cloudlut_quadrilinear.h). This is what the
  // renderer's hardware trilinear filter plus its manual interpolation of axis 3 compute.
  void sample(const std::array<float, 4>& x, float* out) const;

  // Bytes a table of these dimensions and channels occupies in memory as float.
  static std::uint64_t bytesFor(const std::array<int, 4>& dims, int channels);

 private:
  std::string name_;
  std::array<Axis, 4> axes_{};
  std::vector<Channel> channels_;
  std::vector<float> data_;
  nlohmann::json parameters_ = nlohmann::json::object();
};

// Throws std::runtime_error with a clear message if a table of this size would not fit in
// the memory this machine has (checked before anything is allocated).
void checkTableFitsInMemory(const std::array<int, 4>& dims, int channels, int tableCount = 1);

}  // namespace cloudlut
