#include "RefractaSceneSettings.h"

#include "vtkEffectPlan.h"
#include "vtkLatticeBoltzmannSolver.h"
#include "vtkNew.h"
#include "vtkPhotonTracer.h"
#include "vtkRefractaImageRenderer.h"
#include "vtkRefractaLightingVolume.h"
#include "vtkRefractaRenderPipeline.h"
#include "vtkRefractaViewPass.h"

#include <iterator>
#include <stdexcept>
#include <tuple>

namespace RefractaRender
{
namespace
{
const int NoPreset = -1;
const int DefaultPhotons = 1 << 18; // without a preset

const ChoiceTable<int> Presets = { { "none", NoPreset }, { "draft", vtkEffectPlan::DRAFT },
  { "interactive", vtkEffectPlan::INTERACTIVE }, { "production", vtkEffectPlan::PRODUCTION } };

const ChoiceTable<int> ToneMappings = { { "clamp", vtkRefractaImageRenderer::CLAMP },
  { "reinhard", vtkRefractaImageRenderer::REINHARD },
  { "exponential", vtkRefractaImageRenderer::EXPONENTIAL } };

const ChoiceTable<int> RayModes = { { "auto", vtkRefractaViewPass::AUTO },
  { "straight", vtkRefractaViewPass::STRAIGHT }, { "curved", vtkRefractaViewPass::CURVED } };

const ChoiceTable<int> SingleScatteringMethods = { { "auto", vtkEffectPlan::AUTOMATIC_METHOD },
  { "photons", vtkEffectPlan::PHOTONS }, { "light_rays", vtkEffectPlan::LIGHT_RAYS },
  { "interpolated", vtkEffectPlan::INTERPOLATED } };

// quality.direct_surface_light: vtkRefractaRenderPipeline::DirectSurfaceLightByRays.
const ChoiceTable<int> DirectSurfaceLights = { { "light_rays", 1 }, { "photons", 0 } };

const ChoiceTable<int> EffectModes = { { "auto", vtkEffectPlan::AUTOMATIC },
  { "on", vtkEffectPlan::FORCE_ON }, { "off", vtkEffectPlan::FORCE_OFF } };

// quality.multiple_scattering_method: the plan's method (vtkEffectPlan::MultipleScatteringMethod)
// and the Lattice-Boltzmann lattice it runs on (vtkEffectPlan::LatticeDirections: 0 lets the plan
// choose).
struct MultipleScatteringChoice
{
  int Method;
  int Lattice;
};
const ChoiceTable<MultipleScatteringChoice> MultipleScatteringMethods = {
  { "auto", { vtkEffectPlan::AUTOMATIC_MULTIPLE_METHOD, vtkEffectPlan::AUTOMATIC_LATTICE } },
  { "lbl", { vtkEffectPlan::LATTICE_ONLY, vtkEffectPlan::AUTOMATIC_LATTICE } },
  { "lbl_d3q6", { vtkEffectPlan::LATTICE_ONLY, vtkLatticeBoltzmannSolver::D3Q6 } },
  { "lbl_d3q18", { vtkEffectPlan::LATTICE_ONLY, vtkLatticeBoltzmannSolver::D3Q18 } },
  { "split", { vtkEffectPlan::FIRST_COLLISION_SPLIT, vtkEffectPlan::AUTOMATIC_LATTICE } },
  { "split_d3q6", { vtkEffectPlan::FIRST_COLLISION_SPLIT, vtkLatticeBoltzmannSolver::D3Q6 } },
  { "split_d3q18", { vtkEffectPlan::FIRST_COLLISION_SPLIT, vtkLatticeBoltzmannSolver::D3Q18 } },
  { "photons", { vtkEffectPlan::PHOTONS_EVERY_ORDER, vtkEffectPlan::AUTOMATIC_LATTICE } }
};

// The keys of "scene.effects", in vtkEffectPlan's effect order.
const char* const EffectKeys[] = { "refraction", "absorption", "single_scattering",
  "multiple_scattering", "emission", "surface_lighting" };
static_assert(sizeof(EffectKeys) / sizeof(EffectKeys[0]) == vtkEffectPlan::NUMBER_OF_EFFECTS,
  "one scene key per effect of vtkEffectPlan");

void ReadImage(const json& scene, RenderSettings& s)
{
  const json image = scene.value("image", json::object());
  CheckKeys(image, "scene.image", { "width", "height", "exposure", "tone_mapping" });
  s.Width = Integer(image, "width", "scene.image", 256, 1, 16384);
  s.Height = Integer(image, "height", "scene.image", 256, 1, 16384);
  s.Exposure = Number(image, "exposure", "scene.image", 1.0, 0.0, 1e30);
  std::tie(s.ToneMappingName, s.ToneMapping) =
    Choice(image, "tone_mapping", "scene.image", "clamp", ToneMappings);
}

void ReadQuality(const json& scene, vtkRefractaRenderPipeline* pipeline, RenderSettings& s)
{
  const json quality = scene.value("quality", json::object());
  const std::string q = "scene.quality";
  CheckKeys(quality, q,
    { "preset", "photons", "seed", "view_step", "ray_mode", "transmittance_cutoff",
      "photon_min_step", "octree_tolerance", "photon_smoothing", "multiple_scattering",
      "multiple_scattering_tolerance", "multiple_scattering_block_size",
      "multiple_scattering_method", "scattering_orders", "tolerance", "single_scattering_method",
      "volume_caustic", "glass_supersampling", "glass_grazing_cosine", "direct_surface_light",
      "radiance_lobes" });
  int preset;
  std::tie(s.Preset, preset) = Choice(quality, "preset", q, "none", Presets);
  const bool hasPreset = preset != NoPreset;
  if (hasPreset)
  {
    pipeline->SetQuality(preset);
  }
  vtkEffectPlan* plan = pipeline->GetEffectPlan();
  s.Photons = Integer(quality, "photons", q,
    hasPreset ? plan->GetRecommendedNumberOfPhotons() : DefaultPhotons, 1, 1 << 28);
  s.Seed = Integer(quality, "seed", q, 1, 0, 2147483647);
  s.ViewStep =
    Number(quality, "view_step", q, hasPreset ? plan->GetRecommendedViewStep() : 1.0, 0.01, 16.0);
  std::tie(s.RayModeName, s.RayMode) = Choice(quality, "ray_mode", q, "auto", RayModes);
  s.TransmittanceCutoff = Number(quality, "transmittance_cutoff", q, 1e-4, 0.0, 0.5);
  s.PhotonMinStep = Number(quality, "photon_min_step", q,
    hasPreset ? plan->GetRecommendedPhotonMinimumStep() : 1.0, 1e-3, 1e6);
  s.OctreeTolerance = Number(quality, "octree_tolerance", q,
    hasPreset ? plan->GetRecommendedOctreeTolerance() : 0.005, 0.0, 1.0);
  s.PhotonSmoothing = Boolean(quality, "photon_smoothing", q, true);
  s.VolumeCaustic = Integer(quality, "volume_caustic", q, 4, 1, 8);
  s.RadianceLobes =
    Integer(quality, "radiance_lobes", q, 2, 1, vtkRefractaLightingVolume::MAXIMUM_RADIANCE_LOBES);
  s.GlassSupersampling = Integer(quality, "glass_supersampling", q, 3, 1, 8);
  s.GlassGrazingCosine = Number(quality, "glass_grazing_cosine", q, 0.5, 0.0, 1.0);
  s.MultipleScattering = Boolean(quality, "multiple_scattering", q, true);
  s.LatticeTolerance = Number(quality, "multiple_scattering_tolerance", q,
    hasPreset ? plan->GetRecommendedLatticeTolerance() : 1e-4, 1e-8, 1.0);
  s.LatticeBlockSize = Integer(quality, "multiple_scattering_block_size", q,
    hasPreset ? plan->GetRecommendedLatticeBlockSize() : 4, 0, 8);
  // The lattice alone, the first-collision split (photons carry k orders) or photons alone
  // (vtkEffectPlan::SetMultipleScatteringMethod; k 0: the plan's choice by the tolerance).
  MultipleScatteringChoice multiple;
  std::tie(s.MultipleScatteringMethodName, multiple) =
    Choice(quality, "multiple_scattering_method", q, "auto", MultipleScatteringMethods);
  s.Lattice = multiple.Lattice;
  pipeline->SetMultipleScatteringMethod(multiple.Method);
  s.ScatteringOrders = Integer(quality, "scattering_orders", q, 0, 0, 1000);
  pipeline->SetScatteringOrders(s.ScatteringOrders);
  // Photons, light rays or the interpolation (vtkEffectPlan::SetSingleScatteringMethod).
  int method;
  std::tie(s.SingleScatteringMethodName, method) =
    Choice(quality, "single_scattering_method", q, "auto", SingleScatteringMethods);
  pipeline->SetSingleScatteringMethod(method);
  // The lit surfaces' direct light: light rays (noise-free, where photons fly straight) or photons.
  int rays;
  std::tie(s.DirectSurfaceLightName, rays) =
    Choice(quality, "direct_surface_light", q, "light_rays", DirectSurfaceLights);
  pipeline->SetDirectSurfaceLightByRays(rays != 0);
  // The relative image change an effect may cause and still be skipped.
  plan->SetTolerance(
    Number(quality, "tolerance", q, hasPreset ? plan->GetTolerance() : 0.01, 0.0, 1.0));
}

// Per-effect overrides of the plan ("auto", "on", "off").
void ReadEffects(const json& scene, const RenderSettings& s, vtkEffectPlan* plan)
{
  const json effects = scene.value("effects", json::object());
  CheckKeys(effects, "scene.effects", { std::begin(EffectKeys), std::end(EffectKeys) });
  for (int e = 0; e < vtkEffectPlan::NUMBER_OF_EFFECTS; ++e)
  {
    plan->SetEffectMode(
      e, Choice(effects, EffectKeys[e], "scene.effects", "auto", EffectModes).second);
  }
  if (!s.MultipleScattering)
  {
    plan->SetEffectMode(vtkEffectPlan::MULTIPLE_SCATTERING, vtkEffectPlan::FORCE_OFF);
  }
}
}

int RequestedPhotons(const json& quality)
{
  // ReadQuality's own reading, without its errors: ReadSettings reports those.
  try
  {
    const int preset = Choice(quality, "preset", "scene.quality", "none", Presets).second;
    vtkNew<vtkEffectPlan> plan;
    if (preset != NoPreset)
    {
      plan->SetQuality(preset);
    }
    return Integer(quality, "photons", "scene.quality",
      preset != NoPreset ? plan->GetRecommendedNumberOfPhotons() : DefaultPhotons, 1, 1 << 28);
  }
  catch (const std::exception&)
  {
    return DefaultPhotons;
  }
}

RenderSettings ReadSettings(const json& scene, vtkRefractaRenderPipeline* pipeline)
{
  RenderSettings settings;
  ReadImage(scene, settings);
  ReadQuality(scene, pipeline, settings);
  ReadEffects(scene, settings, pipeline->GetEffectPlan());
  return settings;
}

void ApplySettings(const RenderSettings& s, vtkRefractaImageRenderer* renderer)
{
  vtkRefractaRenderPipeline* pipeline = renderer->GetPipeline();
  vtkPhotonTracer* tracer = pipeline->GetPhotonTracer();
  tracer->SetNumberOfPhotons(s.Photons);
  tracer->SetSeed(static_cast<unsigned int>(s.Seed));
  tracer->SetMinimumStep(s.PhotonMinStep);
  pipeline->SetOctreeTolerance(s.OctreeTolerance);
  tracer->SetSmoothing(s.PhotonSmoothing);
  tracer->SetVolumeCausticSubdivision(s.VolumeCaustic);
  tracer->SetMaximumRadianceLobes(s.RadianceLobes); // the light rays take the tracer's

  pipeline->GetLatticeSolver()->SetTolerance(s.LatticeTolerance);
  pipeline->GetLatticeSolver()->SetBlockSize(s.LatticeBlockSize);
  pipeline->SetLattice(s.Lattice);
  renderer->SetImageSize(s.Width, s.Height);
  renderer->SetExposure(s.Exposure);
  renderer->SetToneMapping(s.ToneMapping);
  renderer->SetStepSize(s.ViewStep);
  renderer->SetRayMode(s.RayMode);
  renderer->SetTransmittanceCutoff(s.TransmittanceCutoff);
  renderer->GetViewPass()->SetDielectricSupersampling(s.GlassSupersampling);
  renderer->GetViewPass()->SetDielectricGrazingCosine(s.GlassGrazingCosine);
}

json ImageReport(const RenderSettings& s)
{
  return { { "width", s.Width }, { "height", s.Height }, { "exposure", s.Exposure },
    { "tone_mapping", s.ToneMappingName } };
}

json QualityReport(const RenderSettings& s)
{
  return { { "photons", s.Photons }, { "seed", s.Seed }, { "view_step", s.ViewStep },
    { "ray_mode", s.RayModeName }, { "transmittance_cutoff", s.TransmittanceCutoff },
    { "photon_min_step", s.PhotonMinStep }, { "photon_smoothing", s.PhotonSmoothing },
    { "volume_caustic", s.VolumeCaustic }, { "radiance_lobes", s.RadianceLobes },
    { "glass_supersampling", s.GlassSupersampling },
    { "glass_grazing_cosine", s.GlassGrazingCosine },
    { "multiple_scattering", s.MultipleScattering },
    { "single_scattering_method", s.SingleScatteringMethodName },
    { "direct_surface_light", s.DirectSurfaceLightName },
    { "multiple_scattering_tolerance", s.LatticeTolerance },
    { "multiple_scattering_block_size", s.LatticeBlockSize },
    { "multiple_scattering_method", s.MultipleScatteringMethodName },
    { "scattering_orders", s.ScatteringOrders }, { "preset", s.Preset },
    { "octree_tolerance", s.OctreeTolerance } };
}
}
