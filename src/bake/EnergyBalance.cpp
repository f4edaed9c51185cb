#include "bake/EnergyBalance.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include <glm/geometric.hpp>
#include <tbb/parallel_for.h>

#include "bake/Quadrature.h"
#include "core/Glsl.h"
#include "core/TableLookup.h"
#include "cloudlut_quadrilinear.h"

namespace cloudlut::bake {

namespace {
constexpr double kPi = 3.14159265358979323846;
}

double unscatteredShareExact(double sigma) {
  if (sigma < 1e-4) return 1.0 - 4.0 * sigma / 3.0;
  return (1.0 - std::exp(-2.0 * sigma) * (1.0 + 2.0 * sigma)) / (2.0 * sigma * sigma);
}

nlohmann::json EnergyBalance::toJson() const {
  nlohmann::json arr = nlohmann::json::array();
  for (const EnergySlice& s : slices) {
    nlohmann::json j = {{"rho", s.rho}, {"sigma", s.sigma}, {"unscattered", s.unscattered}, {"total", s.total}};
    if (s.single >= 0) j["single"] = s.single;
    if (s.multiple >= 0) j["multiple"] = s.multiple;
    arr.push_back(j);
  }
  return {{"slices", arr}};
}

EnergyInputs energyInputsFromParameters(const Table4D* single, const Table4D* multiple) {
  const Table4D* t = single ? single : multiple;
  if (!t) throw std::invalid_argument("energy balance: no scattering table given");
  EnergyInputs in;
  const auto& p = t->parameters();
  in.unitOpticalRadius = p.value("extinction_per_m", defaults::kExtinctionPerMetre) *
                         p.value("radius_m", defaults::kParticleRadiusMetres);
  in.firstPhase = recordedPhase(single ? single->parameters() : p, "first_phase", defaults::kFirstPhase);
  return in;
}

namespace {

// A table's cell along its first three axes at the fractions x (locateCell), read on any
// density slice: what Table4D::sample (interpolateCell) computes, bit for bit. For a
// single-channel table with two or more nodes on every axis (the scattering tables) the eight
// corners of the first three axes (node offsets, weight products) are found once for every
// slice; any other table goes through interpolateCell itself.
struct CellOnSlices {
  std::uint32_t dims[4] = {0, 0, 0, 0}, i[4] = {0, 0, 0, 0};
  float f[4] = {0, 0, 0, 0};
  bool cornersKnown = false;
  std::size_t offset[8] = {};  // node of corner c in slice 0 (bit k of c: axis k's upper node)
  float weight[8] = {};        // Π_{k<3} (upper ? f_k : 1 − f_k), multiplied in axis order
  std::size_t sliceStride = 0;  // nodes per density slice

  // The table's (first) value between density nodes `slice` and `slice` + 1 at `fraction`:
  // Σ over the 16 corners (axis 3 the slowest bit, as interpolateCell orders them) of
  // weight · (upper ? fraction : 1 − fraction) · value, corners of weight 0 skipped.
  float sample(const Table4D& t, std::uint32_t slice, float fraction) {
    if (!cornersKnown) {
      i[3] = slice;
      f[3] = fraction;
      std::vector<float> out(t.channels().size());
      cloudlut_reader::interpolateCell(t.data().data(), dims, t.channels().size(), i, f, out.data());
      return out[0];
    }
    const float* values = t.data().data();
    float out = 0.0f;
    for (std::size_t upper = 0; upper < 2; ++upper) {
      const float w3 = upper ? fraction : 1.0f - fraction;
      const float* s = values + (slice + upper) * sliceStride;
      for (int c = 0; c < 8; ++c) {
        const float w = weight[c] * w3;
        if (w == 0.0f) continue;
        out += w * s[offset[c]];
      }
    }
    return out;
  }
};

CellOnSlices locateOnSlices(const Table4D& t, const glm::vec4& x) {
  CellOnSlices c;
  for (int a = 0; a < 4; ++a) c.dims[a] = static_cast<std::uint32_t>(t.axes()[a].size);
  for (int a = 0; a < 3; ++a) cloudlut_reader::locateCell(x[a], c.dims[a], c.i[a], c.f[a]);
  c.cornersKnown = t.channels().size() == 1;
  for (int a = 0; a < 4; ++a) c.cornersKnown = c.cornersKnown && c.dims[a] >= 2;
  if (!c.cornersKnown) return c;
  c.sliceStride = static_cast<std::size_t>(c.dims[0]) * c.dims[1] * c.dims[2];
  for (int corner = 0; corner < 8; ++corner) {
    std::uint32_t j[3];
    float w = 1.0f;
    for (int k = 0; k < 3; ++k) {
      const bool hi = ((corner >> k) & 1) != 0;
      j[k] = c.i[k] + (hi ? 1u : 0u);
      w *= hi ? c.f[k] : 1.0f - c.f[k];
    }
    c.offset[corner] = cloudlut_reader::nodeIndex(c.dims, j[0], j[1], j[2], 0);
    c.weight[corner] = w;
  }
  return c;
}

}  // namespace

EnergyBalance computeEnergyBalance(const Table4D* single, const Table4D* multiple,
                                   const EnergyInputs& in) {
  const Table4D* t = single ? single : multiple;
  if (!t) throw std::invalid_argument("energy balance: no scattering table given");
  if (single && multiple && single->axes()[3].size != multiple->axes()[3].size)
    throw std::invalid_argument("energy balance: the single and multiple tables have different density slices");
  // storage resolved (and validated) once, not per sample
  const ScatteringStorage storage1 = single ? scatteringStorage(*single) : ScatteringStorage::Log2MeanSource;
  const ScatteringStorage storageM = multiple ? scatteringStorage(*multiple) : ScatteringStorage::MeanSource;
  const Axis& dAx = t->axes()[3];
  // axes records (density range irrelevant: the slice is addressed by its node fraction below)
  const glm::vec4 axes1 = single ? scatteringAxesRecord(*single) : glm::vec4(0.0f);
  const glm::vec4 axesM = multiple ? scatteringAxesRecord(*multiple) : glm::vec4(0.0f);
  const int nSlices = dAx.size;
  // Quadrature: θS composite Gauss 8×8; α (angle between v and l) = π ξ², composite 12×8 in ξ;
  // β (azimuth of v about l) midpoints over [0, π], doubled by symmetry.
  const GaussRule& g = gaussLegendre(8);
  std::vector<double> thS, wS, alpha, wA;
  for (int c = 0; c < 8; ++c)
    for (int k = 0; k < 8; ++k) {
      const double th = kPi * (c + g.x[k]) / 8.0;
      thS.push_back(th);
      wS.push_back(kPi / 8.0 * g.w[k] * 2.0 * kPi * std::sin(th));
    }
  for (int c = 0; c < 12; ++c)
    for (int k = 0; k < 8; ++k) {
      const double xi = (c + g.x[k]) / 12.0, a = kPi * xi * xi;
      alpha.push_back(a);
      wA.push_back(g.w[k] / 12.0 * 2.0 * kPi * xi * std::sin(a));
    }
  const int nBeta = 64;
  // The geometry of a sample (the table coordinates of (S, v), cos θv) does not depend on the
  // slice: each (θS, α, β) is located once and read in every slice. Per slice, the sums run in
  // the same order as a slice-by-slice loop would.
  std::vector<double> rhos(nSlices), sigmas(nSlices);
  std::vector<float> wFracs(nSlices);
  for (int k = 0; k < nSlices; ++k) {
    rhos[k] = std::exp2(dAx.value(k));
    sigmas[k] = in.unitOpticalRadius * rhos[k];
    wFracs[k] = nSlices > 1 ? static_cast<float>(k) / static_cast<float>(nSlices - 1) : 0.0f;
  }
  const std::size_t nK = static_cast<std::size_t>(nSlices);
  std::vector<std::uint32_t> sliceCells(nK);
  std::vector<float> sliceFracs(nK);
  for (std::size_t k = 0; k < nK; ++k)
    cloudlut_reader::locateCell(wFracs[k], static_cast<std::uint32_t>(nSlices), sliceCells[k], sliceFracs[k]);
  std::vector<double> p1(thS.size() * nK, 0.0), pm(thS.size() * nK, 0.0);  // [i·nK + k]
  tbb::parallel_for(std::size_t(0), thS.size(), [&](std::size_t i) {
    const glm::vec3 S(static_cast<float>(std::sin(thS[i])), 0.0f, static_cast<float>(std::cos(thS[i])));
    const glm::vec3 l(0.0f, 0.0f, 1.0f);
    std::vector<double> a1(nK, 0.0), am(nK, 0.0), b1(nK), bm(nK);
    for (std::size_t j = 0; j < alpha.size(); ++j) {
      const double ca = std::cos(alpha[j]), sa = std::sin(alpha[j]);
      const double ph = static_cast<double>(phaseValue(in.firstPhase, static_cast<float>(ca)));
      std::fill(b1.begin(), b1.end(), 0.0);
      std::fill(bm.begin(), bm.end(), 0.0);
      for (int b = 0; b < nBeta; ++b) {
        const double beta = kPi * (b + 0.5) / nBeta;
        const glm::vec3 v(static_cast<float>(sa * std::cos(beta)), static_cast<float>(sa * std::sin(beta)),
                          static_cast<float>(ca));
        const float cosV = -glm::dot(v, S);
        if (!(cosV > 0.0f)) continue;
        const glm::vec4 x1 = single ? glsl::scatteringAxes(S, v, l, 1.0f, axes1, 2.0f) : glm::vec4(0.0f);
        const glm::vec4 xm = multiple ? (single && axesM == axes1 ? x1 : glsl::scatteringAxes(S, v, l, 1.0f, axesM, 2.0f))
                                      : glm::vec4(0.0f);
        // Table4D::sample at (x, slice k), its cell located once for every slice: the same
        // locateCell and interpolateCell calls, so the same values.
        CellOnSlices c1, cm;
        if (single) c1 = locateOnSlices(*single, x1);
        if (multiple) cm = locateOnSlices(*multiple, xm);
        for (std::size_t k = 0; k < nK; ++k) {
          const float tau = static_cast<float>(sigmas[k]) * 2.0f * cosV;
          float val = 0.0f;
          if (single) {
            val = c1.sample(*single, sliceCells[k], sliceFracs[k]);
            b1[k] += static_cast<double>(scatteringFromStored(storage1, val, tau)) * cosV;
          }
          if (multiple) {
            val = cm.sample(*multiple, sliceCells[k], sliceFracs[k]);
            bm[k] += static_cast<double>(scatteringFromStored(storageM, val, tau)) * cosV;
          }
        }
      }
      const double wb = kPi / nBeta * 2.0;
      for (std::size_t k = 0; k < nK; ++k) {
        a1[k] += wA[j] * ph * b1[k] * wb;
        am[k] += wA[j] * bm[k] * wb;
      }
    }
    for (std::size_t k = 0; k < nK; ++k) {
      p1[i * nK + k] = wS[i] * a1[k];
      pm[i * nK + k] = wS[i] * am[k];
    }
  });
  EnergyBalance out;
  out.slices.resize(nSlices);
  for (int k = 0; k < nSlices; ++k) {
    EnergySlice e;
    e.rho = rhos[k];
    e.sigma = sigmas[k];
    e.unscattered = unscatteredShareExact(e.sigma);
    e.total = e.unscattered;
    double s1 = 0.0, sm = 0.0;
    for (std::size_t i = 0; i < thS.size(); ++i) {
      s1 += p1[i * nK + static_cast<std::size_t>(k)];
      sm += pm[i * nK + static_cast<std::size_t>(k)];
    }
    if (single) {
      e.single = s1 / kPi;
      e.total += e.single;
    }
    if (multiple) {
      e.multiple = sm / kPi;
      e.total += e.multiple;
    }
    out.slices[k] = e;
  }
  return out;
}

}  // namespace cloudlut::bake
