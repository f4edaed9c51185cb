#pragma once
// The suites `cloudlut bench` runs; each measures speed and accuracy against an independent
// reference and appends rows to the report.
#include <filesystem>
#include <string>
#include <vector>

#include "bench/BenchReport.h"
#include "core/Progress.h"
#include "io/LutIo.h"

namespace cloudlut::bench {

struct BenchOptions {
  bool quick = false;  // reduced resolutions, for a fast look
  int threads = 0;     // the machine's cores when 0
  std::vector<std::string> scenes;  // ground-truth: these scenes of data/bench_scenes only (empty: all)
  ProgressFn progress;
};

// Optical-depth table: default bake on all threads and on one; time against error for several
// samples-per-diameter values, against a 4096-sample integration of the same particle; every
// density model at its default.
void benchOpticalDepth(BenchReport& report, const BenchOptions& options);

// Scattering tables (ScatteringBench.cpp): each method and resolution against the Monte Carlo
// reference of the homogeneous sphere, with the energy balance of every bake.
void benchScattering(BenchReport& report, const BenchOptions& options, const std::filesystem::path& out);

// Scattering-table layout (TableLayoutBench.cpp): bytes against the single-scattering error on
// and between the density slices, for folded or full φv, slices per octave and the density
// interpolation; Monte Carlo reference. BenchRow::steps holds the bytes of one table (half).
void benchTableLayout(BenchReport& report, const BenchOptions& options);

// Renderer II: cloudscapes per quality preset and blend mode, ms per stage (generation,
// occlusion, shading + blending, upscale) and frame-to-frame stability (RenderBench.cpp).
void benchRender(BenchReport& report, const BenchOptions& options);
// Of those, only the rows of time against particle count (1e4, 1e5, 1e6 explicit particles).
void benchRenderParticleCount(BenchReport& report, const BenchOptions& options);

// Atmosphere (AtmosphereBench.cpp): the tables' bake time on 2 threads, and the transmittance,
// single-scattered and all-orders sky against the brute-force reference (AtmosphereComparison.h);
// then what the atmosphere adds to a cloudscape frame (benchAtmosphereFrame).
void benchAtmosphere(BenchReport& report, const BenchOptions& options);

// The default cloudscape at 1280 × 720 (640 × 360 quick), volume blending, particles at half
// resolution, under the uniform sky, the atmosphere without light shafts and with them, in turn
// twice: each one's faster frame, its stage times (AtmosphereFrameBench.cpp). `--suite
// atmosphere-frame` runs only these rows.
void benchAtmosphereFrame(BenchReport& report, const BenchOptions& options);

// The LUT set the render suites time with: a small baked optical-depth table and synthetic
// scattering tables (the timing does not depend on their values).
io::LutSet renderBenchLuts();

// Ground truth (GroundTruthBench.cpp): every rendering method on data/bench_scenes, time against
// error relative to the path-traced reference; references and LUTs cached under `out`. Throws
// UsageError for a name in options.scenes that is not one of its scenes.
void benchGroundTruth(BenchReport& report, const BenchOptions& options, const std::filesystem::path& out);

}  // namespace cloudlut::bench
