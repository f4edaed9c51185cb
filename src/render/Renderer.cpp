#include "render/Renderer.h"

#include <algorithm>
#include <numeric>
#include <functional>
#include <limits>
#include <string>

#include <glm/geometric.hpp>

#include "core/Errors.h"
#include "render/CloudscapeGeneration.h"
#include "render/DiffusionVolume.h"
#include "render/GlFunctions.h"
#include "render/GlResources.h"
#include "render/GpuParticleRecord.h"
#include "render/GpuStorage.h"
#include "render/HiddenFragments.h"
#include "render/LightOcclusion.h"
#include "render/LightSpaceInputs.h"
#include "render/ParticlePass.h"
#include "render/ParticleUpload.h"
#include "render/SkyPass.h"
#include "render/Stopwatch.h"
#include "render/SunVolume.h"
#include "render/SunVolumeGrid.h"
#include "render/Upscale.h"
#include "scene/CloudscapeGrid.h"
#include "scene/PixelFootprint.h"
#include "render/VolumeResolve.h"

namespace cloudlut::render {

std::vector<std::size_t> backToFrontOrder(const std::vector<scene::Particle>& particles, const glm::vec3& eye) {
  std::vector<float> distance(particles.size());
  for (std::size_t i = 0; i < particles.size(); ++i) distance[i] = glm::length(particles[i].center - eye);
  std::vector<std::size_t> order(particles.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return distance[a] > distance[b]; });
  return order;
}

// The passes, in the order a frame runs them. Members are destroyed in reverse order, the
// context current (the destructor makes it so).
struct Renderer::Impl {
  GlContext& context;
  GlFunctions gl;
  StorageBudget budget;
  ParticleBuffers buffers;
  ParticleUpload upload;
  CloudscapeGeneration generation;
  LightOcclusion occlusion;
  SunVolume sunVolume;
  SunVolume zenithVolume;  // the same structure, columns toward the zenith: the ambient's sky visibility
  SunVolume diffusionColumns;  // again toward the zenith, finer: the diffusion volume's extinction
  DiffusionVolume diffusion;
  ParticlePass particles;
  VolumeResolve volume;
  Upscale upscale;
  std::unique_ptr<SkyPass> sky;  // issue 13: made when a frame first uses the atmosphere
  // The particle buffer, kept from frame to frame while its size holds: a new one costs the GL a
  // fresh allocation, and llvmpipe its page faults inside the draw.
  std::unique_ptr<FloatRenderTarget> target;
  // VolumeTilePlan::Auto: count a frame's fragments before it draws (VolumeResolve::planBands)
  // rather than at its first overflow. Each count sets it to whether the expected tile plan was
  // too small for the load; it starts true, so that a single frame (one `render`) of a load that
  // overflows is planned before anything is drawn, and a load that fits stops counting after one.
  // A frame whose particles' screen rectangles fit one tile's pool is not counted at all.
  bool countFirst = true;
  // The inputs of the light-space volumes as they stand (LightSpaceInputs.h), when a frame of
  // explicit particles built them; null when they match nothing a frame could reuse (a
  // cloudscape's, or a single volume's build for the tests). And the footprints their sun
  // volume's build skipped.
  std::unique_ptr<LightSpaceInputs> lightSpace;
  std::size_t lightSpaceSkipped = 0;

  Impl(GlContext& c, const io::LutSet& luts)
      : context(c),
        gl(makeCurrentAndLoadGlFunctions(c)),
        budget(gl, c),
        buffers(gl),
        upload(budget, buffers),
        generation(gl, budget, buffers),
        occlusion(gl, budget, buffers),
        sunVolume(gl, c, budget, buffers),
        zenithVolume(gl, c, budget, buffers),
        diffusionColumns(gl, c, budget, buffers),
        diffusion(gl, c),
        particles(gl, c, luts, buffers),
        volume(gl, budget),
        upscale(gl, budget) {
    checkGlError(gl, "creating the renderer");
  }

  ~Impl() {
    try {
      context.makeCurrent();
    } catch (const GlError&) {
      // the context is gone; the members' deletions go nowhere
    }
  }

  void validateContext() { context.makeCurrent(); }

  void validate(const RenderSettings& s) {
    checkImageSize(s.width, s.height);
    if (s.downscale != 1 && s.downscale != 2 && s.downscale != 4)
      throw UsageError("--downscale: expected 1, 2 or 4, got " + std::to_string(s.downscale));
    if (s.fragmentsPerPixel < 1 || s.fragmentsPerPixel > 1024)
      throw UsageError("fragments per pixel: expected 1 to 1024, got " + std::to_string(s.fragmentsPerPixel));
    if (s.volumeShortList < 0 || s.volumeShortList > kShortListCapacity)
      throw UsageError("volume short list: expected 0 to " + std::to_string(kShortListCapacity) + " segments, got " +
                       std::to_string(s.volumeShortList));
    context.makeCurrent();
  }

  // UsageError when a w × h float target exceeds this OpenGL's limits.
  void requireTargetSize(int w, int h, const RenderSettings& s) const {
    GLint maxTexture = 0, viewport[2] = {0, 0};
    gl.GetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTexture);
    gl.GetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
    if (w > std::min(maxTexture, viewport[0]) || h > std::min(maxTexture, viewport[1]))
      throw UsageError("image size " + std::to_string(s.width) + "x" + std::to_string(s.height) +
                       " exceeds this OpenGL's limit of " + std::to_string(std::min(maxTexture, viewport[0])) +
                       " pixels per side");
  }

  // The diffusion volume's grid (one cascade; none: no cascade), how many nodes inside its
  // horizontal sides the shader fades its field out (0: none, the grid holds the whole scene),
  // and how far beside each node the weight of the cloud beside it looks (world units,
  // kBesideRadii particle radii).
  struct DiffusionGrid {
    SunVolumeGrid grid;
    float fadeNodes = 0.0f;
    float besideOffset = 0.0f;
  };
  // Which light-space volumes a frame built (illuminate).
  struct Built {
    bool sun = false, zenith = false;
  };

  // The sunlight of the frame: the seed's per-particle occlusion when the settings take the
  // sunlight per particle, the sun optical-depth volume over `grid` when the lighting or the
  // sunlight needs it; and the zenith volume over `zenithGrid` when the ambient needs it
  // (needsZenithVolume); the diffusion volume over diffusionGrid. With `keepable` (a frame of
  // explicit particles, their records in upload.records()) and s.keepLighting, the volumes of the
  // last build stand when they were built from the same inputs (LightSpaceInputs.h). Returns which
  // volumes the frame has.
  Built illuminate(std::size_t count, const SunVolumeGrid& grid, const SunVolumeGrid& zenithGrid, const RenderSettings& s,
                   RenderStats* stats, const DiffusionGrid& diffusionGrid = noDiffusionGrid(), bool keepable = false) {
    const Stopwatch clock;
    std::size_t dropped = 0;
    if (s.sunlight == SunlightModel::Particle)
      dropped = occlusion.run(count, s, particles.tables().unitOpticalRadius(), stats != nullptr);
    LightSpaceInputs inputs;
    inputs.sun = needsSunVolume(s) && count > 0;
    inputs.zenith = needsZenithVolume(s) && count > 0;
    inputs.diffusion = inputs.sun && diffusionGrid.grid.cascades == 1 && s.diffusionShare > 0.0f &&
                       (s.terms & kTermMultiple) != 0;
    if (inputs.sun) inputs.sunGrid = grid;
    if (inputs.zenith) inputs.zenithGrid = zenithGrid;
    if (inputs.diffusion) {
      inputs.diffusionGrid = diffusionGrid.grid;
      inputs.diffusionSweeps = s.diffusionSweeps;
      inputs.diffusionCycles = s.diffusionCycles;
      inputs.diffusionBeside = diffusionGrid.besideOffset;
      inputs.diffusionFade = diffusionGrid.fadeNodes;
    }
    inputs.sunChordMap = s.sunChordMap;
    inputs.countsOverflow = stats != nullptr;
    if (keepable) inputs.records = upload.records();
    const bool sun = inputs.sun, zenith = inputs.zenith;  // a frame that reuses had the same to build
    const bool kept = keepable && s.keepLighting && lightSpace && reusable(*lightSpace, inputs);
    SunIndependentReuse reuse;  // the same particles under a moved sun: what stands (LightSpaceInputs.h)
    if (!kept) {
      if (keepable && s.keepLighting && lightSpace) reuse = reusableUnderMovedSun(*lightSpace, inputs);
      lightSpace.reset();  // the volumes below are rebuilt: until they are, they match nothing
      lightSpaceSkipped = 0;
      if (inputs.sun)
        lightSpaceSkipped =
            sunVolume.build(grid, count, particles.tables().splatTable(), inputs.countsOverflow, s.sunChordMap);
      if (inputs.zenith && !reuse.zenith)
        zenithVolume.build(zenithGrid, count, particles.tables().splatTable(), false);
      diffusion.clear();
      if (inputs.diffusion) {
        if (!reuse.diffusionColumns)
          diffusionColumns.build(diffusionGrid.grid, count, particles.tables().splatTable(), false);
        diffusion.build(diffusionColumns, sunVolume, 1, particles.tables().laterPhaseAsymmetry(), s.diffusionSweeps,
                        s.diffusionCycles, diffusionGrid.besideOffset, diffusionGrid.fadeNodes,
                        reuse.diffusionWarmStart ? s.diffusionWarmCycles : 0);
      }
      if (keepable) lightSpace = std::make_unique<LightSpaceInputs>(std::move(inputs));
    }
    gl.Finish();
    if (stats) {
      stats->occlusionSeconds = clock.seconds();
      stats->lightSpaceKept = kept;
      stats->lightSpaceSunOnly = !kept && (reuse.zenith || reuse.diffusionColumns);
      stats->diffusionWarm = !kept && inputs.diffusion && diffusion.warmStarted();
      if (s.occlusion && count > 0) stats->tileOverflow = dropped;
      stats->sunFootprintOverflow = lightSpaceSkipped;
      stats->sunChordsNeeded = sun ? sunVolume.chordsNeeded() : 0;
      stats->sunChordMap = sun && sunVolume.chordMapComplete();
    }
    return {sun, zenith};
  }

  static bool needsSunVolume(const RenderSettings& s) {
    return s.lighting == LightingModel::Cloud || (s.occlusion && s.sunlight == SunlightModel::Volume);
  }

  // The cloud lighting's ambient needs the cloud above and below each point only when the sky is
  // darker (or brighter) below the horizon than above it (under a uniform sky it is exact without).
  static bool needsZenithVolume(const RenderSettings& s) {
    return s.lighting == LightingModel::Cloud && (s.terms & kTermAmbient) != 0 && s.view.lighting.skyBelow != glm::vec3(1.0f);
  }

  // Shading and blending at 1/downscale resolution, the volume resolve, the upscale, read-back.
  // `cloudscape`: generated (VolumeTilePlan::Auto counts its fragments for the tiles' plan).
  // `fragmentBound`: at least the fragments the particle pass can store (scene::
  // pixelFootprintBound; the largest size_t when unknown): under Auto, a frame that fits one tile of the
  // expected plan is not counted.
  Image draw(std::size_t count, bool useOrder, float farPlane, const RenderSettings& s, Built built, bool cloudscape,
             RenderStats* stats, std::size_t fragmentBound = std::numeric_limits<std::size_t>::max()) {
    const bool sun = built.sun;
    const int w = s.particleWidth(), h = s.particleHeight();
    requireTargetSize(w, h, s);
    const bool blendVolume = s.blend == BlendMode::Volume;
    const bool cullsHidden = ParticlePass::cullsHidden(s, count);  // the only user of the depth buffer
    if (blendVolume) {
      volume.prepare(w, h, s.fragmentsPerPixel, s.volumePoolBytes, s.volumeShortList);
      if (cullsHidden) particles.clearHiddenFragments(w, h);
    } else {
      volume.bindUnused();
    }

    // Float framebuffer: radiance + transmittance (a texture, for the resolve), and distance.
    if (!target || target->width() != w || target->height() != h) {
      target.reset();
      target = std::make_unique<FloatRenderTarget>(gl, context, w, h);
    }
    target->bind();
    const float clearColour[4] = {0.0f, 0.0f, 0.0f, 1.0f};
    const float clearDistance[4] = {kNoDistance, 0.0f, 0.0f, 0.0f};
    gl.ClearBufferfv(GL_COLOR, 0, clearColour);
    gl.ClearBufferfv(GL_COLOR, 1, clearDistance);
    if (cullsHidden) {
      const float clearDepth = 1.0f;
      gl.ClearBufferfv(GL_DEPTH, 0, &clearDepth);
    }

    const Stopwatch drawClock;
    const bool counted =
        s.tilePlan == VolumeTilePlan::Counted ||
        (s.tilePlan == VolumeTilePlan::Auto && (cloudscape || (countFirst && fragmentBound > volume.expectedTileNodes())));
    if (blendVolume && counted && volume.tiling().count() > 1) {
      // More than one tile: plan them from the fragments themselves (VolumeResolve::planBands).
      particles.countFragments(count, useOrder, farPlane, w, h, s);
      volume.planBands(target->colourTexture());
      gl.ClearBufferfv(GL_COLOR, 0, clearColour);
    }
    if (blendVolume) {
      // an explicit scene under Auto counts only once a tile overflows (VolumeResolve::run)
      const bool countOnOverflow = s.tilePlan == VolumeTilePlan::Auto && !cloudscape;
      std::function<void()> countTile;
      if (countOnOverflow) countTile = [&] { particles.countFragments(count, useOrder, farPlane, w, h, s); };
      volume.run(
          target->colourTexture(),
          [&] { particles.draw(count, useOrder, true, farPlane, w, h, s, sunVolume, sun, zenithVolume, built.zenith, diffusion); },
          countTile);
      // Auto: the next frame counts first while this one's fragments overflow the expected plan
      // (a frame's load is much like the last's; a count that finds no overflow stops it)
      if (s.tilePlan == VolumeTilePlan::Auto && volume.counts().countedPlan)
        countFirst = volume.counts().expectedPlanOverflows;
      if (stats) {
        const VolumeResolve::Counts c = volume.counts();
        stats->fragments = c.fragments;
        stats->fragmentOverflow = c.overflow;
        stats->truncatedPixels = c.truncatedPixels;
        stats->midListPixels = c.midLists;
        stats->longListPixels = c.longLists;
        stats->resolveCutPixels = c.cutPixels;
        stats->resolveSeconds = volume.resolveSeconds();
        stats->volumeTiles = c.tiles;
        stats->volumeRedrawnTiles = c.redrawnTiles;
        stats->countedFragments = c.countedFragments;
        stats->volumeTilesCounted = c.countedPlan;
        stats->volumePoolBytes = volume.poolBytes();
      }
    } else {
      particles.draw(count, useOrder, false, farPlane, w, h, s, sunVolume, sun, zenithVolume, built.zenith, diffusion);
    }
    if (stats) {
      stats->renderSeconds = drawClock.seconds();
      stats->particles = count;
    }

    if (s.downscale > 1) {
      const Stopwatch upscaleClock;
      upscale.run(*target, s.width, s.height);
      if (stats) stats->upscaleSeconds = upscaleClock.seconds();
    }
    const Stopwatch readClock;
    Image image = s.downscale > 1 ? upscale.readBack() : target->readBack();
    if (stats) stats->readbackSeconds = readClock.seconds();
    // --- atmosphere (issue 13, render/SkyPass.h): the sky, the ground, aerial perspective
    if (s.view.lighting.atmosphere) {
      const Stopwatch skyClock;
      skyPass().composite(image, s, sunVolume, sun, particles.tables().laterPhaseAsymmetry());
      if (stats) stats->skySeconds = skyClock.seconds();
    }
    return image;
  }

  Image render(const std::vector<scene::Particle>& list, const RenderSettings& settings, RenderStats* stats) {
    validate(settings);
    // hidden-fragment culling where the particles' screen rectangles add up to more than the
    // screen: below one fragment a pixel on average it finds little to cull (HiddenFragments.h)
    const int w = settings.particleWidth(), h = settings.particleHeight();
    const std::size_t bound = scene::pixelFootprintBound(list, scene::CameraFrame(settings.view.camera, w, h));
    RenderSettings s = settings;
    s.hiddenCulling = settings.hiddenCulling && hiddenCullingPays(bound, static_cast<std::size_t>(w) * h);
    const glm::vec3 eye = s.view.camera.eye;
    const Stopwatch clock;
    // drawn back to front for alpha blending, and for volume blending's hidden-fragment culling,
    // which draws them reversed (ParticlePass::draw); volume blending without it takes them as given
    const float farPlane = upload.upload(list, eye, glm::normalize(s.view.lighting.sunDirection));
    const bool sorted = s.blend == BlendMode::Alpha || ParticlePass::cullsHidden(s, list.size());
    if (sorted) upload.uploadDrawOrder(backToFrontOrder(list, eye));
    if (stats) stats->uploadSeconds = clock.seconds();
    float altitude = 0.0f;  // of the particles' mean centre, for the atmosphere's cloud lighting
    for (const scene::Particle& p : list) altitude += p.center.y / static_cast<float>(list.size());
    const RenderSettings lit = litByAtmosphere(s, altitude);
    const Built built = illuminate(list.size(), needsSunVolume(lit) ? sunGridFor(list, lit) : SunVolumeGrid{},
                                   needsZenithVolume(lit) ? zenithGridFor(list, lit) : SunVolumeGrid{}, lit, stats,
                                   diffusionGridFor(list, lit), true);
    if (stats) stats->fragmentBound = bound;
    return draw(list.size(), sorted, farPlane, lit, built, false, stats, bound);
  }

  Image renderCloudscape(const scene::CloudType& cloud, const scene::QualityPreset& q, const RenderSettings& s,
                         RenderStats* stats) {
    validate(s);
    const Stopwatch clock;
    // sorted for alpha blending, and for volume blending's hidden-fragment culling (drawn reversed)
    const bool sortKeys = s.blend == BlendMode::Alpha || s.hiddenCulling;
    const CloudscapeGeneration::Result g = generation.run(cloud, q, s, sortKeys, particles.tables().referenceRadius());
    gl.Finish();
    if (stats) {
      stats->generateSeconds = clock.seconds();
      stats->validCells = g.cells;
      stats->litParticles = g.count;
    }
    const RenderSettings lit = litByAtmosphere(s, 0.5f * (cloud.cloudBase + cloud.cloudTop));
    const Built built = illuminate(g.count, needsSunVolume(lit) ? sunGridFor(cloud, q, lit) : SunVolumeGrid{},
                                   needsZenithVolume(lit) ? zenithGridFor(cloud, q, lit) : SunVolumeGrid{}, lit, stats,
                                   diffusionGridFor(cloud, q, lit));
    return draw(g.visible, true, g.farPlane, lit, built, true, stats);  // the keys index the particles in view
  }

  // --- atmosphere (issue 13): the sky pass, and the settings whose sun colour and ambient the
  // atmosphere sets for clouds at `altitude` (SkyPass::cloudLighting); unchanged without it.
  SkyPass& skyPass() {
    if (!sky) sky = std::make_unique<SkyPass>(gl, context);
    return *sky;
  }
  RenderSettings litByAtmosphere(const RenderSettings& s, float altitude) {
    if (!s.view.lighting.atmosphere) return s;
    RenderSettings lit = s;
    if (!sky || !sky->hasTables()) {  // no tables given: the uniform sky (Renderer.h)
      lit.view.lighting.atmosphere = false;
      return lit;
    }
    lit.view.lighting = sky->cloudLighting(s.view.lighting, altitude);
    return lit;
  }

  // A column volume's grid around explicit particles, columns toward `toward`, spacingPerRadius
  // times the smallest particle radius apart: one grid over their bounds where `columns` per side
  // reach that spacing; otherwise (a wide scene, e.g. a dumped cloudscape) nested cascades around
  // the camera over the particles' heights, as a cloudscape's, so that the columns near the eye
  // keep the spacing.
  static SunVolumeGrid columnGridFor(const std::vector<scene::Particle>& list, const RenderSettings& s,
                                     const glm::vec3& toward, float spacingPerRadius, int columns, int slices) {
    glm::vec3 lo(0.0f), hi(0.0f);
    float smallest = 1.0f;
    for (std::size_t i = 0; i < list.size(); ++i) {
      const scene::Particle& p = list[i];
      const float reach = std::max({p.radii.x, p.radii.y, p.radii.z});
      const float least = std::min({p.radii.x, p.radii.y, p.radii.z});
      lo = i == 0 ? p.center - reach : glm::min(lo, p.center - reach);
      hi = i == 0 ? p.center + reach : glm::max(hi, p.center + reach);
      smallest = i == 0 ? least : std::min(smallest, least);
    }
    const float spacing = spacingPerRadius * smallest;
    const float width = std::max(hi.x - lo.x, hi.z - lo.z);
    if (width > spacing * static_cast<float>(columns - 3) && width > hi.y - lo.y)
      return sunVolumeGridForLayer(s.view.camera.eye, lo.y, hi.y, toward, spacing, kSunCascadesMax, columns);
    return sunVolumeGridForBounds(lo, hi, toward, spacing, columns, slices);
  }
  static SunVolumeGrid sunGridFor(const std::vector<scene::Particle>& list, const RenderSettings& s) {
    return columnGridFor(list, s, s.view.lighting.sunDirection, kSunColumnsPerRadius, 256, 128);
  }

  // Around the camera for a cloud layer: the layer's heights widened by the largest particle
  // radius, cascades from a quarter of the ring-0 cell.
  static SunVolumeGrid sunGridFor(const scene::CloudType& cloud, const scene::QualityPreset& q, const RenderSettings& s) {
    const scene::GridParameters g = scene::gridParameters(cloud, q);
    const glm::vec2 r = scene::grid::cgMaxRadii(q.rings - 1, g.g0, g.g1, g.g2);
    return sunVolumeGridForLayer(s.view.camera.eye, cloud.cloudBase - r.y, cloud.cloudTop + r.y,
                                 s.view.lighting.sunDirection, kSunColumnsPerRadius * cloud.cellSize, kSunCascadesMax);
  }
  static constexpr float kSunColumnsPerRadius = 0.25f;  // column spacing in units of the particle radius

  // The zenith volume's grids: the sun volume's with vertical columns, twice as far apart and half
  // as many per side (the ambient varies over a particle's size, not over its rim).
  static SunVolumeGrid zenithGridFor(const std::vector<scene::Particle>& list, const RenderSettings& s) {
    return columnGridFor(list, s, kZenith, kZenithColumnsPerRadius, kZenithColumns, kZenithSlices);
  }
  static SunVolumeGrid zenithGridFor(const scene::CloudType& cloud, const scene::QualityPreset& q,
                                     const RenderSettings& s) {
    const scene::GridParameters g = scene::gridParameters(cloud, q);
    const glm::vec2 r = scene::grid::cgMaxRadii(q.rings - 1, g.g0, g.g1, g.g2);
    return sunVolumeGridForLayer(s.view.camera.eye, cloud.cloudBase - r.y, cloud.cloudTop + r.y, kZenith,
                                 kZenithColumnsPerRadius * cloud.cellSize, kSunCascadesMax, kZenithColumns);
  }
  static DiffusionGrid noDiffusionGrid() {
    DiffusionGrid none;
    none.grid.cascades = 0;
    return none;
  }
  // The diffusion volume's nodes: vertical columns over the particles' bounds and three spacings
  // beyond (clear air, where the light leaves), the spacing s.diffusionSpacing times the median
  // particle radius (its least semi-axis) or what kDiffusionNodes per side need, up to twice that;
  // for a scene wider than that (a dumped cloudscape), a box ahead of the camera over the
  // particles' heights (diffusionGridAhead).
  static DiffusionGrid diffusionGridFor(const std::vector<scene::Particle>& list, const RenderSettings& s) {
    if (list.empty() || s.diffusionShare <= 0.0f) return noDiffusionGrid();
    glm::vec3 lo = list[0].center, hi = list[0].center;
    std::vector<float> radii;
    for (const scene::Particle& p : list) {
      const float reach = std::max({p.radii.x, p.radii.y, p.radii.z});
      lo = glm::min(lo, p.center - reach);
      hi = glm::max(hi, p.center + reach);
      radii.push_back(std::min({p.radii.x, p.radii.y, p.radii.z}));
    }
    std::nth_element(radii.begin(), radii.begin() + static_cast<std::ptrdiff_t>(radii.size() / 2), radii.end());
    const float radius = radii[radii.size() / 2], wanted = s.diffusionSpacing * radius;
    const float spacing =
        std::max(wanted, std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z}) / static_cast<float>(kDiffusionNodes - 9));
    if (spacing > 2.0f * wanted) return diffusionGridAhead(s, lo.y, hi.y, radius);
    return {sunVolumeGridForBounds(lo - 3.0f * spacing, hi + 3.0f * spacing, kZenith, spacing, kDiffusionNodes,
                                   kDiffusionNodes),
            0.0f, kBesideRadii * radius};
  }
  // A cloudscape's: the box ahead of the camera over the layer widened by the largest vertical
  // radius, for a wanted spacing of s.diffusionSpacing times a ring-0 particle's middle radius
  // (its least semi-axis: the middle of the cloud type's relative sizes times the cell, times the
  // vertical aspect when that is below 1).
  static DiffusionGrid diffusionGridFor(const scene::CloudType& cloud, const scene::QualityPreset& q,
                                        const RenderSettings& s) {
    if (s.diffusionShare <= 0.0f) return noDiffusionGrid();
    const scene::GridParameters g = scene::gridParameters(cloud, q);
    const glm::vec2 r = scene::grid::cgMaxRadii(q.rings - 1, g.g0, g.g1, g.g2);
    const float radius = cloud.cellSize * 0.5f * (cloud.particleSize.x + cloud.particleSize.y) *
                         std::min(cloud.verticalAspect, 1.0f);
    return diffusionGridAhead(s, cloud.cloudBase - r.y, cloud.cloudTop + r.y, radius);
  }
  // A box of kDiffusionNodes − 9 spacings a side over heights [yLo, yHi] and three spacings
  // beyond, the spacing kDiffusionAheadSpacing times the wanted one (s.diffusionSpacing times the
  // particle radius `radius`), its back face kDiffusionBehind of its side behind the eye along the
  // view's horizontal direction (centred on the eye when the view is vertical). The shader fades
  // the field out over kDiffusionFadeNodes inside its sides, where it cuts clouds.
  static DiffusionGrid diffusionGridAhead(const RenderSettings& s, float yLo, float yHi, float radius) {
    const float spacing = kDiffusionAheadSpacing * s.diffusionSpacing * radius;
    const float side = static_cast<float>(kDiffusionNodes - 9) * spacing;
    glm::vec3 ahead = s.view.camera.target - s.view.camera.eye;
    ahead.y = 0.0f;
    const float length = glm::length(ahead);
    glm::vec3 centre = s.view.camera.eye;
    if (length > 1e-6f * glm::length(s.view.camera.target - s.view.camera.eye))
      centre += ahead / length * ((0.5f - kDiffusionBehind) * side);
    const glm::vec3 lo(centre.x - 0.5f * side, yLo, centre.z - 0.5f * side);
    const glm::vec3 hi(centre.x + 0.5f * side, yHi, centre.z + 0.5f * side);
    return {sunVolumeGridForBounds(lo - 3.0f * spacing, hi + 3.0f * spacing, kZenith, spacing, kDiffusionNodes,
                                   kDiffusionNodes),
            kDiffusionFadeNodes, kBesideRadii * radius};
  }
  // Twice the wanted spacing: one particle radius at the default, a box 16.7 km a side for
  // fair_weather_cumulus (docs/LIGHTING.md, "The diffusion box ahead of the camera").
  static constexpr float kDiffusionAheadSpacing = 2.0f;
  static constexpr float kDiffusionBehind = 0.2f;
  static constexpr float kDiffusionFadeNodes = 12.0f;
  // The cloud beside a node is looked for two particle radii away: from a particle's edge, past
  // its own chords; within its neighbours' (docs/LIGHTING.md, "The cloud beside a particle").
  static constexpr float kBesideRadii = 2.0f;
  static constexpr int kDiffusionNodes = 128;
  static constexpr glm::vec3 kZenith{0.0f, 1.0f, 0.0f};
  static constexpr float kZenithColumnsPerRadius = 0.5f;
  static constexpr int kZenithColumns = 128, kZenithSlices = 64;

  scene::CpuGeneration generateOnGpu(const scene::CloudType& cloud, const scene::QualityPreset& q,
                                     const RenderSettings& s) {
    validate(s);
    return generation.readBack(generation.run(cloud, q, s, false, particles.tables().referenceRadius()), cloud, q, s);
  }

  // Uploads `list`, for the light-space passes alone (no draw follows).
  void uploadAsGiven(const std::vector<scene::Particle>& list, const RenderSettings& s) {
    upload.upload(list, s.view.camera.eye, glm::normalize(s.view.lighting.sunDirection));
  }

  Renderer::SunVolumeSnapshot sunVolumeOf(const std::vector<scene::Particle>& list, const RenderSettings& s,
                                          const SunVolumeGrid* given) {
    validate(s);
    uploadAsGiven(list, s);
    const SunVolumeGrid grid = given ? *given : sunGridFor(list, s);
    lightSpace.reset();  // the frame's volumes are overwritten
    if (list.empty()) return {grid, {}, 0};
    const std::size_t skipped =
        sunVolume.build(grid, list.size(), particles.tables().splatTable(), true);
    return {grid, sunVolume.readBack(), skipped};
  }

  Renderer::DiffusionSnapshot diffusionOf(const std::vector<scene::Particle>& list, const RenderSettings& s) {
    validate(s);
    uploadAsGiven(list, s);
    const DiffusionGrid grid = diffusionGridFor(list, s);
    illuminate(list.size(), needsSunVolume(s) ? sunGridFor(list, s) : SunVolumeGrid{}, SunVolumeGrid{}, s, nullptr,
               grid);
    if (!diffusion.built()) return {grid.grid, {}, {}};
    return {grid.grid, diffusion.readBack(), diffusion.readSolve()};
  }

  std::vector<float> sunlight(const std::vector<scene::Particle>& list, const RenderSettings& s) {
    validate(s);
    uploadAsGiven(list, s);
    occlusion.run(list.size(), s, particles.tables().unitOpticalRadius(), false);
    std::vector<float> out;
    for (const GpuParticleRecord& r : buffers.readRecords(list.size())) out.push_back(r.toParticle[2][3]);
    checkGlError(gl, "reading the particles back");
    return out;
  }
};

Renderer::Renderer(GlContext& context, const io::LutSet& luts) : impl_(std::make_unique<Impl>(context, luts)) {}

Renderer::~Renderer() = default;

void Renderer::setAtmosphereTables(const glsl::AtmosphereParameters& atmosphere, const Table4D& transmittance,
                                   const Table4D& multipleScattering, const Table4D& irradiance) {
  impl_->validateContext();
  impl_->skyPass().setTables(atmosphere, transmittance, multipleScattering, irradiance);
}

Image Renderer::render(const std::vector<scene::Particle>& particles, const RenderSettings& settings,
                       RenderStats* stats) {
  return impl_->render(particles, settings, stats);
}

Image Renderer::renderCloudscape(const scene::CloudType& cloud, const scene::QualityPreset& quality,
                                 const RenderSettings& settings, RenderStats* stats) {
  return impl_->renderCloudscape(cloud, quality, settings, stats);
}

scene::CpuGeneration Renderer::generateOnGpu(const scene::CloudType& cloud, const scene::QualityPreset& quality,
                                             const RenderSettings& settings) {
  return impl_->generateOnGpu(cloud, quality, settings);
}

std::vector<float> Renderer::sunlight(const std::vector<scene::Particle>& particles, const RenderSettings& settings) {
  return impl_->sunlight(particles, settings);
}

Renderer::SunVolumeSnapshot Renderer::sunVolume(const std::vector<scene::Particle>& particles,
                                                const RenderSettings& settings, const SunVolumeGrid* grid) {
  return impl_->sunVolumeOf(particles, settings, grid);
}

Renderer::DiffusionSnapshot Renderer::diffusionVolume(const std::vector<scene::Particle>& particles,
                                                      const RenderSettings& settings) {
  return impl_->diffusionOf(particles, settings);
}

}  // namespace cloudlut::render
