#pragma once
// A renderer ready for a test: a scratch directory, a LUT set written into it and read back
// through io::readLutSet (as the CLI reads one), a fresh OSMesa context and a Renderer on both.
// Members are declared in construction order: the Renderer keeps references to the context
// and the tables.
#include <memory>
#include <stdexcept>
#include <string>

#include "bake/AngularClosureBaker.h"
#include "bake/OpticalDepthBaker.h"
#include "core/Medium.h"
#include "core/ReferenceParticle.h"
#include "io/LutIo.h"
#include "render/GlContext.h"
#include "render/Renderer.h"
#include "BakedFixtures.h"
#include "RenderLuts.h"
#include "TempDir.h"

namespace cloudlut::test {

struct RenderFixture {
  // The synthetic set of RenderLuts.h (an optical-depth table of `model`, smooth synthetic
  // scattering tables).
  static RenderFixture synthetic(DensityModel model = DensityModel::Radial) {
    return RenderFixture([model](const std::filesystem::path& dir) { writeSyntheticLutSet(dir, model); });
  }

  // The default medium's own tables, for comparisons with the path tracer: the optical depth of
  // the default noise particle at 32×16×32×16 and the default-resolution scattering tables of
  // `orders` (0 = converged; BakedFixtures caches the bake across tests). With `closure`, the
  // multiple table carries its angular closure (bake/AngularClosureBaker.h) as `cloudlut bake`
  // attaches it, at `closurePhotons` photons per sun direction, for the own term with its core
  // shadow or, with `coreShadow` false, without it (the model before it).
  static RenderFixture defaultMedium(int orders = 0, bool closure = false, long long closurePhotons = 8000,
                                     bool coreShadow = true) {
    return RenderFixture([=](const std::filesystem::path& dir) {
      const Medium medium;
      bake::OpticalDepthSettings ods;
      ods.dims = {32, 16, 32, 16};
      const ReferenceParticle particle(medium.model, medium.seed);
      const Table4D od = bake::bakeOpticalDepth(particle, ods);
      const bake::ScatteringResult& sc = defaultScattering(orders);
      if (!sc.single || !sc.multiple) throw std::runtime_error("the default scattering bake returned no table");
      Table4D multiple = *sc.multiple;
      if (closure) {
        bake::AngularClosureSettings s;
        s.photonsPerDirection = closurePhotons;
        s.ownCoreShadow = coreShadow;
        const auto k = bake::computeAngularClosure(od, multiple, particle, medium.first, medium.later, s);
        if (!k) throw std::runtime_error("the default medium has no angular closure");
        multiple.parameters()["angular_closure"] = angularClosureToJson(*k);
      }
      writeLutSet(dir, {&od, &*sc.single, &multiple});
    });
  }

  TempDir tmp;
  io::LutSet luts;
  std::unique_ptr<render::GlContext> context;
  render::Renderer renderer;

 private:
  // tmp() listed: clang's -Wuninitialized does not see a member constructed by default before
  // another member's initialiser reads it
  template <typename Write>
  explicit RenderFixture(Write write)
      : tmp(), luts(readWritten(tmp / "luts", write)), context(render::createHeadlessContext()), renderer(*context, luts) {}

  template <typename Write>
  static io::LutSet readWritten(const std::filesystem::path& dir, Write write) {
    write(dir);
    return io::readLutSet(dir);
  }
};

}  // namespace cloudlut::test
