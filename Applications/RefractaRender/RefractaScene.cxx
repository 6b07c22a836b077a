#include "RefractaScene.h"

#include "RefractaRenderReport.h"
#include "RefractaSceneView.h"

#include "vtkCamera.h"
#include "vtkRefractaImageRenderer.h"
#include "vtkRefractaRenderPipeline.h"
#include "vtkRefractaSurfaceSet.h"

#include <iostream>

namespace RefractaRender
{
// The embedded default scene: a glass sphere (n = 1.5) in a light fog above a checkered floor
// (an opaque Lambertian surface), lit by a spot light from above: the sphere focuses it into a
// caustic on the floor and in the fog, in front of a checkerboard environment that the sphere
// bends.
const char* const DefaultSceneJson = R"JSON({
  "image": { "width": 256, "height": 256, "exposure": 1.5, "tone_mapping": "reinhard" },
  "camera": { "position": [0.0, 0.55, 3.2], "focal_point": [0.0, -0.1, 0.0],
              "view_up": [0, 1, 0], "view_angle": 34 },
  "background": { "checker": { "squares": [24, 12],
                  "color1": [0.9, 0.85, 0.75], "color2": [0.08, 0.12, 0.3] } },
  "medium": {
    "grid": { "dimensions": [80, 76, 80], "bounds": [-1, 1, -0.9, 1, -1, 1] },
    "surrounding": { "extinction": [0.35, 0.35, 0.35], "albedo": [0.9, 0.9, 0.9],
                     "anisotropy": 0.3 },
    "meshes": [
      { "sphere": { "center": [0, 0.05, 0], "radius": 0.42, "resolution": 96 },
        "material": { "refractive_index": 1.5, "extinction": [0.02, 0.02, 0.02] } }
    ]
  },
  "surfaces": [
    { "plane": { "center": [0, -0.8, 0], "normal": [0, 1, 0], "size": [2.4, 2.4] },
      "material": { "checker": { "squares": [8, 8], "color1": [0.85, 0.8, 0.7],
                                 "color2": [0.45, 0.42, 0.38] } } }
  ],
  "lights": [
    { "type": "spot", "position": [0, 3, 0], "focal_point": [0, 0, 0], "cone_angle": 12,
      "exponent": 1, "color": [1.0, 0.95, 0.85], "intensity": 60 }
  ],
  "quality": { "photons": 262144, "view_step": 1.0, "seed": 1,
               "multiple_scattering": true, "multiple_scattering_tolerance": 0.001 }
})JSON";

Scene ReadScene(
  const json& scene, const std::string& base, vtkRefractaImageRenderer* renderer, bool quiet)
{
  CheckKeys(scene, "scene",
    { "image", "camera", "background", "medium", "surfaces", "lights", "quality", "effects" });
  Scene out;
  // A quality preset in the settings configures the pipeline first.
  out.Settings = ReadSettings(scene, renderer->GetPipeline());

  // The surfaces (read first: a bad entry fails before the voxelizer runs), the medium, then
  // what surrounds them.
  Timer surfacesTimer;
  out.Surfaces = ReadSurfaces(scene, base);
  out.SurfacesSeconds = surfacesTimer.Seconds();
  Timer mediumTimer;
  if (!quiet)
  {
    std::cout << "  medium ..." << std::endl;
  }
  out.Medium = ReadMedium(scene, base);
  out.MediumSeconds = mediumTimer.Seconds();
  if (!quiet)
  {
    std::cout << "  medium done, " << out.MediumSeconds << " s" << std::endl;
  }
  out.LightCount = AddLights(scene, renderer);
  out.Camera = ReadCamera(scene, out.Medium.Image);
  out.EnvironmentLight = ReadBackground(scene, base, renderer);

  ApplySettings(out.Settings, renderer);
  renderer->SetInputData(out.Medium.Image);
  out.SurfaceSet = MakeSurfaceSet(out.Surfaces);
  renderer->SetSurfaces(out.SurfaceSet);
  renderer->GetPipeline()->SetBackgroundIlluminates(out.EnvironmentLight);
  renderer->SetCamera(out.Camera);
  return out;
}
}
