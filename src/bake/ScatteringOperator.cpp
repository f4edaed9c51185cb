#include "bake/ScatteringOperator.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Core>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include "bake/PhaseProduct.h"
#include "bake/Quadrature.h"

namespace cloudlut::bake {

namespace {
constexpr double kPi = 3.14159265358979323846;
}  // namespace

void convolvePhase(const std::vector<float>& in, int inDirs, const std::vector<float>& Mt, int outDirs,
                   const SphereField& field, std::vector<float>& out) {
  // Per radial node one matrix product out_r = M · in_r (M = Mt read column-major, outDirs ×
  // inDirs; in_r inDirs × nt and out_r outDirs × nt row-major), by Eigen's blocked kernel: the
  // products do not depend on the thread count, so neither does any sum's order.
  using RowMajor = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  const Eigen::Map<const Eigen::MatrixXf> m(Mt.data(), outDirs, inDirs);
  const int nt = field.zenithCount();
  // The same floats eight zenith nodes at a time where the processor has AVX2 (PhaseProduct.h).
  const bool avx2 = phaseProductAvx2Applies(outDirs, inDirs, nt);
  tbb::parallel_for(
      tbb::blocked_range<int>(0, field.radialCount(), 1),
      [&](const tbb::blocked_range<int>& r) {
        for (int ir = r.begin(); ir != r.end(); ++ir) {
          if (avx2) {
            phaseProductAvx2(Mt.data(), outDirs, inDirs, &in[static_cast<std::size_t>(ir) * inDirs * nt], nt,
                             &out[static_cast<std::size_t>(ir) * outDirs * nt]);
            continue;
          }
          const Eigen::Map<const RowMajor> a(&in[static_cast<std::size_t>(ir) * inDirs * nt], inDirs, nt);
          Eigen::Map<RowMajor> o(&out[static_cast<std::size_t>(ir) * outDirs * nt], outDirs, nt);
          o.noalias() = m * a;
        }
      },
      tbb::simple_partitioner());
}

int TransportStencil::pointsPerRay(double sigma, int points) {
  // The rule's panels may round the total up (at least 2 points each).
  std::vector<double> probeS, probeW;
  attenuatedRayRule(sigma, 2.0, points, probeS, probeW);
  return static_cast<int>(probeS.size());
}

TransportStencil::TransportStencil(const SphereField& field, double sigma, int points, Storage& storage)
    : field_(&field) {
  K_ = pointsPerRay(sigma, points);
  const DirectionGrid& dirs = field.directions();
  const int D = dirs.count(), nb = dirs.phiCount();
  entries_ = storage.acquire(field.size() * static_cast<std::size_t>(K_));
  counts_.assign(field.size(), 0);
  tbb::parallel_for(0, field.nodeCount(), [&](int s) {
    std::vector<double> ss, ww;
    const glm::dvec3 x = field.node(s);
    for (int d = 0; d < D; ++d) {
      const int ia = d / nb;
      const glm::dvec3& w = dirs.direction(d);
      attenuatedRayRule(sigma, distanceToSphere(x, -w), points, ss, ww);
      const double wh = std::hypot(w.x, w.y);
      const std::size_t cell = field.index(s, d);
      Entry* e = &entries_.data()[cell * K_];
      // Points of zero weight (the far panel of a ray shorter than its near optical depth)
      // contribute exactly nothing: they are left out, the rest packed at the cell's start.
      int nonzero = 0;
      for (int k = 0; k < K_; ++k)
        if (ww[k] != 0.0) {
          ss[nonzero] = ss[k];
          ww[nonzero++] = ww[k];
        }
      FieldPoint located[8];
      for (int k = 0; k < nonzero; ++k) {
        if (k % 8 == 0) field.locateRay8(x, w, wh, &ss[k], std::min(8, nonzero - k), located);
        const FieldPoint& p = located[k % 8];
        Entry& q = e[k];
        q.base = static_cast<std::uint32_t>(p.offset + static_cast<std::size_t>(ia) * nb * field.directionStride());
        for (int c = 0; c < 4; ++c) {
          q.wr[c] = static_cast<float>(ww[k]) * p.wr[c];
          q.wt[c] = p.wt[c];
        }
        q.fb = p.fb;
      }
      counts_[cell] = static_cast<std::uint8_t>(nonzero);
    }
  });
}

void TransportStencil::apply(const std::vector<float>& in, std::vector<float>& out) const {
  // Cells in the field's own order: out[cell] = Σ_k (in interpolated at point k), the four
  // zenith terms of every point summed as one vector, added up at the end.
  const std::size_t strideR = field_->radialStride(), strideB = field_->directionStride();
  const float* src = in.data();
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, field_->size(), 512), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t cell = r.begin(); cell != r.end(); ++cell) {
      const Entry* e = &entries_.data()[cell * K_];
      Float4 acc = {0.0f, 0.0f, 0.0f, 0.0f};
      for (int k = 0, n = counts_[cell]; k < n; ++k)
        acc += interpolateFieldTerms(src + e[k].base, strideR, strideB, e[k].wr, e[k].wt, e[k].fb);
      out[cell] = sumFloat4(acc);
    }
  });
}

std::vector<double> TransportStencil::isotropicCoarseOperator() const {
  const int NS = field_->nodeCount(), D = field_->directionCount(), nt = field_->zenithCount();
  const std::size_t strideR = field_->radialStride();
  const std::vector<double>& q = field_->directions().nodeWeights();
  const double inv4pi = 1.0 / (4.0 * kPi);
  std::vector<double> Kc(static_cast<std::size_t>(NS) * NS, 0.0);
  tbb::parallel_for(0, NS, [&](int sIdx) {
    double* row = &Kc[static_cast<std::size_t>(sIdx) * NS];
    for (int dd = 0; dd < D; ++dd) {
      const std::size_t cell = field_->index(sIdx, dd);
      const Entry* e = &entries_.data()[cell * K_];
      const double qd = q[dd] * inv4pi;
      for (int k = 0, n = counts_[cell]; k < n; ++k) {
        const std::size_t base = e[k].base;
        const int ir0 = static_cast<int>(base / strideR), it0 = static_cast<int>(base % static_cast<std::size_t>(nt));
        for (int c = 0; c < 4; ++c)
          for (int t = 0; t < 4; ++t) row[(ir0 + c) * nt + it0 + t] += qd * e[k].wr[c] * e[k].wt[t];
      }
    }
  });
  return Kc;
}

ScatteringOperator::ScatteringOperator(const TransportStencil& transport, const std::vector<float>& Mt,
                                       const SphereField& field)
    : transport_(&transport), Mt_(&Mt), field_(&field), scratch_(field.size()) {}

void ScatteringOperator::apply(const std::vector<float>& in, std::vector<float>& out) {
  transport_->apply(in, scratch_);
  const int D = field_->directionCount();
  convolvePhase(scratch_, D, *Mt_, D, *field_, out);
}

}  // namespace cloudlut::bake
