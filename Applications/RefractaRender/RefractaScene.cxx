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
