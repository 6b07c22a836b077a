// The render settings of a refracta-render scene: "image" (size, exposure, tone mapping),
// "quality" (an optional preset, then the light and view pass settings) and "effects" (the
// effect plan's per-effect overrides).
#ifndef RefractaSceneSettings_h
#define RefractaSceneSettings_h

#include "RefractaSceneJson.h"

#include <string>

class vtkRefractaImageRenderer;
class vtkRefractaRenderPipeline;

namespace RefractaRender
{
/// The settings of one render, as read (and reported).
struct RenderSettings
{
  int Width = 256;
  int Height = 256;
  double Exposure = 1.0;
  std::string ToneMappingName;
  int ToneMapping = 0;
  std::string Preset;
  int Photons = 1 << 18;
  int Seed = 1;
  double ViewStep = 1.0;
  std::string RayModeName;
  std::string SingleScatteringMethodName; // quality.single_scattering_method
  std::string DirectSurfaceLightName;     // quality.direct_surface_light
  int RayMode = 0;
  double TransmittanceCutoff = 1e-4;
  double PhotonMinStep = 1.0;
  double OctreeTolerance = 0.005;
  bool PhotonSmoothing = true;
  bool MultipleScattering = true;
  double LatticeTolerance = 1e-4;
  int LatticeBlockSize = 4;
  std::string MultipleScatteringMethodName = "auto"; // quality.multiple_scattering_method
  int Lattice = 0;                                   // 0 (the plan's choice), 6 or 18
  int ScatteringOrders = 0; // quality.scattering_orders: the split's k (0: the plan's choice)
  int VolumeCaustic = 4;    // quality.volume_caustic: vtkPhotonTracer::VolumeCausticSubdivision
  int RadianceLobes = 2;    // quality.radiance_lobes: vtkPhotonTracer::MaximumRadianceLobes
  int GlassSupersampling = 3; // quality.glass_supersampling: DielectricSupersampling of the view
  double GlassGrazingCosine = 0.5; // quality.glass_grazing_cosine: DielectricGrazingCosine
};

/// Reads "scene.image", "scene.quality" and "scene.effects". A quality preset is set on the
/// pipeline first: it supplies the defaults of the pass settings and of the plan's tolerance
/// (keys given explicitly win). The plan's tolerance and effect modes are set here.
RenderSettings ReadSettings(const json& scene, vtkRefractaRenderPipeline* pipeline);

/// The photons a "quality" block asks for: its "photons", else its preset's recommendation,
/// else 2^18 (what ReadSettings would read; a malformed block gives 2^18, ReadSettings reports it).
int RequestedPhotons(const json& quality);

/// Hands the settings to the renderer, its pipeline and their passes.
void ApplySettings(const RenderSettings& settings, vtkRefractaImageRenderer* renderer);

/// The report's "image" and "quality" sections.
json ImageReport(const RenderSettings& settings);
json QualityReport(const RenderSettings& settings);
}

#endif
