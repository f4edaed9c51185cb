#include "bake/ScatteringBaker.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <mutex>
#include <stdexcept>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include "bake/EnergyBalance.h"
#include "bake/MultipleScattering.h"
#include "bake/ScatteringPaper.h"
#include "bake/SingleScattering.h"
#include "core/Glsl.h"
#include "core/TableLookup.h"

namespace cloudlut::bake {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kClosureThreshold = 0.002;

void validate(const ScatteringSettings& s) {
  for (int d : s.dims)
    if (d < 2 || d > 4096) throw std::invalid_argument("scattering table dimensions must lie in [2, 4096]");
  if (!(s.sMax > s.sMin) || !std::isfinite(s.sMin) || !std::isfinite(s.sMax) || s.sMin < -40 || s.sMax > 40)
    throw std::invalid_argument("the density range needs finite sMin < sMax within [-40, 40]");
  if (!(s.extinction > 0) || !(s.radius > 0) || !std::isfinite(s.extinction * s.radius))
    throw std::invalid_argument("extinction and radius must be positive");
  for (const Phase* p : {&s.firstPhase, &s.laterPhase}) {
    if (!phaseKindFromInt(glslKind(p->kind))) throw std::invalid_argument("phase kind must be 0 (iso), 1 (HG), 2 (CS) or 3 (JD)");
    if ((p->kind == PhaseKind::HenyeyGreenstein || p->kind == PhaseKind::CornetteShanks) &&
        !(p->param > -0.999f && p->param < 0.999f))
      throw std::invalid_argument("phase g must lie in (-0.999, 0.999)");
    if (p->kind == PhaseKind::JendersieDeon &&
        !(p->param >= defaults::kDropletDiameterMinUm && p->param <= defaults::kDropletDiameterMaxUm))
      throw std::invalid_argument("Jendersie-d'Eon droplet diameter must lie in [5, 50] um");
  }
  if (!s.single && !s.multiple) throw std::invalid_argument("nothing to bake: neither single nor multiple");
  if (s.method == ScatteringMethod::Paper && s.orders <= 0)
    throw std::invalid_argument("the paper method computes a fixed number of orders (orders >= 2)");
  checkTableFitsInMemory(s.dims, 1, (s.single ? 1 : 0) + (s.multiple ? 1 : 0));
}

Table4D makeTable(const ScatteringSettings& s, const char* name, const char* channel, const char* meaning) {
  const auto& d = s.dims;
  // φv over [0, π] (folded, mirroredAzimuth) or [0, 2π] (periodic); density interpolated
  // linearly in ρ between the slices (densityAxisLinearInRho, cloudlut_geometry.glsl).
  std::array<Axis, 4> axes{Axis{"theta_s", "rad", 0.0, kPi, d[0], false, sunZenithWarp(d[0])},
                           Axis{"phi_v", "rad", 0.0, s.foldPhiV ? kPi : 2.0 * kPi, d[1], !s.foldPhiV, 0.0, s.foldPhiV},
                           Axis{"theta_v", "rad", 0.0, 0.5 * kPi, d[2], false},
                           Axis{"log2_density", "log2", s.sMin, s.sMax, d[3], false, 0.0, false, s.densityLinearInRho}};
  Table4D t(name, axes, {{channel, meaning}});
  auto& p = t.parameters();
  p["extinction_per_m"] = s.extinction;
  p["radius_m"] = s.radius;
  p["unit_optical_radius"] = s.extinction * s.radius;
  p["first_phase"] = phaseToJson(s.firstPhase);
  p["later_phase"] = phaseToJson(s.laterPhase);
  p["method"] = toString(s.method);
  p["density_range_log2"] = {s.sMin, s.sMax};
  p["particle"] = "homogeneous unit sphere";
  return t;
}

}  // namespace

double sunZenithWarp(int nodes) {
  constexpr double kMaxWarp = 7.0, kMaxPoleSpacing = 21.0 / 180.0 * kPi;
  const double uniform = kPi / std::max(1, nodes - 1);
  // pole spacing of warp w relative to uniform nodes: (w/2)·coth(w/2), increasing from 1 at w = 0
  const auto poleFactor = [](double w) { return w < 1e-9 ? 1.0 : 0.5 * w / std::tanh(0.5 * w); };
  if (poleFactor(kMaxWarp) * uniform <= kMaxPoleSpacing) return kMaxWarp;
  if (uniform >= kMaxPoleSpacing) return 0.0;
  double lo = 0.0, hi = kMaxWarp;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (poleFactor(mid) * uniform <= kMaxPoleSpacing ? lo : hi) = mid;
  }
  return std::floor(lo * 1000.0) / 1000.0;  // a short number in the files, rounded toward uniform
}

const char* toString(ScatteringMethod method) { return method == ScatteringMethod::Paper ? "paper" : "fast"; }

ScatteringResult bakeScattering(const ScatteringSettings& settings, const ProgressFn& progress) {
  validate(settings);
  ScatteringResult result;
  nlohmann::json& report = result.report;
  report["method"] = toString(settings.method);
  const double sigma1 = settings.extinction * settings.radius;
  const int nRho = settings.dims[3];
  const auto sigmaOf = [&](int k) {
    const double s = settings.sMin + (settings.sMax - settings.sMin) * k / (nRho - 1);
    return sigma1 * std::exp2(s);
  };
  const auto t0 = std::chrono::steady_clock::now();
  std::optional<Table4D> closureSingle;
  const double singleSpan = settings.single || (settings.multiple && settings.orders <= 0) ? (settings.multiple ? 0.05 : 1.0) : 0.0;

  // Converged multiple scattering closes its energy balance against the single table, which
  // is then baked even when not requested (it costs a few percent of the whole).
  const bool converged = settings.multiple && settings.orders <= 0 && settings.method == ScatteringMethod::Fast;
  if (settings.single || converged) {
    Table4D t = makeTable(settings, "single_scattering", kSingleScatteringChannel,
                          "log2 of the mean sun transmittance along the chord: single-scattered radiance per unit "
                          "sun irradiance WITHOUT the phase function = (1 - exp(-tau)) * 2^value (multiply by P1(v.l))");
    t.parameters()["orders"] = 1;
    t.parameters()["phase_included"] = false;
    if (settings.method == ScatteringMethod::Paper) {
      t.parameters()["method"] = "paper";
    }
    for (int k = 0; k < nRho; ++k) {
      bakeSingleScatteringSlice(sigmaOf(k), k, t);
      reportProgress(progress, "single scattering", singleSpan * (k + 1) / nRho);
    }
    if (settings.single) result.single = std::move(t);
    else closureSingle = std::move(t);
  }
  const double tSingle = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  const auto t1 = std::chrono::steady_clock::now();
  if (settings.multiple) {
    Table4D t = makeTable(settings, "multiple_scattering", kMultipleScatteringChannel,
                          settings.orders > 0
                              ? "mean source of orders 2..N along the chord: their radiance toward the camera per unit sun irradiance = (1 - exp(-tau)) * value, sr^-1"
                              : "mean source of every order from 2 on (converged) along the chord: radiance toward the camera per unit sun irradiance = (1 - exp(-tau)) * value, sr^-1");
    t.parameters()["orders"] = settings.orders > 0 ? nlohmann::json(settings.orders) : nlohmann::json("converged");
    t.parameters()["first_order"] = 2;
    t.parameters()["phase_included"] = true;
    nlohmann::json slices = nlohmann::json::array();
    if (settings.method == ScatteringMethod::Fast) {
      const FastResolution res;
      FastMultipleScattering fast(settings, res);
      std::optional<Table4D> tail;
      if (converged) tail = makeTable(settings, "multiple_scattering_tail", kMultipleScatteringChannel, "orders 19 and up");
      report["resolution"] = {{"radial", res.radial}, {"zenith", res.zenith}, {"dir_theta", res.dirTheta},
                              {"dir_phi", res.dirPhi}, {"fine_theta", res.fineTheta}, {"fine_phi", res.finePhi},
                              {"transport_points", res.transportPoints}, {"dense_transport_points", res.denseTransportPoints},
                              {"gather_points", res.gatherPoints},
                              {"thin", {{"max_sigma", res.thinSigma}, {"radial", res.thinRadial}, {"zenith", res.thinZenith}}}};
      // The density slices are independent (each writes its own slice of the tables), so they
      // run side by side as well as inside: the serial parts of one slice (the coarse
      // correction's factorisation, GMRES's small steps) overlap another slice's work.
      std::vector<nlohmann::json> sliceReports(static_cast<std::size_t>(nRho));
      std::mutex progressMutex;
      int slicesDone = 0;
      tbb::parallel_for(
          tbb::blocked_range<int>(0, nRho, 1),
          [&](const tbb::blocked_range<int>& range) {
            for (int k = range.begin(); k != range.end(); ++k) {
              fast.bakeSlice(sigmaOf(k), k, t, tail ? &*tail : nullptr, sliceReports[static_cast<std::size_t>(k)],
                             ProgressFn{}, 0.0, 1.0);
              const std::lock_guard<std::mutex> lock(progressMutex);
              ++slicesDone;
              reportProgress(progress, "multiple scattering",
                             singleSpan + (1.0 - singleSpan) * slicesDone / nRho);
            }
          },
          tbb::simple_partitioner());
      for (auto& r : sliceReports) slices.push_back(std::move(r));
      if (tail) {
        // Energy closure of the tail (orders 19 … ∞): a non-absorbing particle returns all the
        // light it receives, so the tail's share is 1 − unscattered − single − orders 2…18,
        // all of which are accurate; the discrete operator fixes the tail's shape, the balance
        // its amplitude. The scale factor measures the operator's conservation error.
        EnergyInputs ein;
        ein.unitOpticalRadius = sigma1;
        ein.firstPhase = settings.firstPhase;
        const Table4D& single = result.single ? *result.single : *closureSingle;
        const EnergyBalance head = computeEnergyBalance(&single, &t, ein);
        const EnergyBalance rest = computeEnergyBalance(nullptr, &*tail, ein);
        for (int k = 0; k < nRho; ++k) {
          const double want = 1.0 - head.slices[k].total;
          const double have = rest.slices[k].multiple;
          // Differences below the table integration's own accuracy (~0.002 of the incident
          // power, mostly the interpolated single table) are left alone: thin particles have
          // almost no tail, and scaling it would only move that error into it.
          double scale = std::abs(want - have) > kClosureThreshold && have > 1e-12 ? want / have : 1.0;
          const bool clamped = !(scale >= 0.5 && scale <= 2.0);
          scale = std::clamp(scale, 0.5, 2.0);
          for (int iV = 0; iV < settings.dims[2]; ++iV)
            for (int iP = 0; iP < settings.dims[1]; ++iP)
              for (int iS = 0; iS < settings.dims[0]; ++iS) {
                const std::size_t n = t.index(iS, iP, iV, k);  // mean sources add
                t.at(n, 0) += static_cast<float>(scale) * tail->at(n, 0);
              }
          slices[k]["tail_share_before_closure"] = have;
          slices[k]["tail_share"] = want;
          slices[k]["total_before_closure"] = head.slices[k].total + have;
          slices[k]["energy_closure_scale"] = scale;
          if (clamped) slices[k]["energy_closure_warning"] = "scale outside [0.5, 2]: clamped";
        }
      }
    } else {
      bakePaperMultipleScattering(settings, t, slices, progress, singleSpan, 1.0 - singleSpan);
    }
    report["multiple_slices"] = slices;
    result.multiple = std::move(t);
  }
  const double tMultiple = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();

  const auto t2 = std::chrono::steady_clock::now();
  const Table4D* s = result.single ? &*result.single : nullptr;
  const Table4D* m = result.multiple ? &*result.multiple : nullptr;
  EnergyInputs ein;
  ein.unitOpticalRadius = sigma1;
  ein.firstPhase = settings.firstPhase;
  report["energy"] = computeEnergyBalance(s, m, ein).toJson()["slices"];
  const double tEnergy = std::chrono::duration<double>(std::chrono::steady_clock::now() - t2).count();
  report["orders"] = settings.orders > 0 ? nlohmann::json(settings.orders) : nlohmann::json("converged");
  report["seconds"] = {{"single", tSingle}, {"multiple", tMultiple}, {"energy_check", tEnergy}};
  reportProgress(progress, "done", 1.0);
  return result;
}

}  // namespace cloudlut::bake
