#include "RefractaScene.h"

#include "RefractaRenderReport.h"
#include "RefractaSceneView.h"

#include "vtkCamera.h"
#include "vtkRefractaImageRenderer.h"
#include "vtkRefractaRenderPipeline.h"

#include <iostream>

namespace RefractaRender
{
Scene ReadScene(
  const json& scene, const std::string& base, vtkRefractaImageRenderer* renderer, bool quiet)
{
  CheckKeys(
    scene, "scene", { "image", "camera", "background", "medium", "lights", "quality", "effects" });
  Scene out;
  // A quality preset in the settings configures the pipeline first.
  out.Settings = ReadSettings(scene, renderer->GetPipeline());

  // The medium, then what surrounds it.
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
  ReadBackground(scene, base, renderer);

  ApplySettings(out.Settings, renderer);
  renderer->SetInputData(out.Medium.Image);
  renderer->SetCamera(out.Camera);
  return out;
}
}
