// A whole refracta-render scene read, checked and handed to a renderer, short of rendering it:
// the settings, the medium, the lights, the camera and the background. refracta-render renders
// what this sets up; the scene fuzzer (Testing/Fuzz) runs it on hostile scene files.
#ifndef RefractaScene_h
#define RefractaScene_h

#include "RefractaSceneMedium.h"
#include "RefractaSceneSettings.h"

#include "vtkSmartPointer.h"

#include <string>

class vtkCamera;
class vtkRefractaImageRenderer;

namespace RefractaRender
{
/// What ReadScene read (and the report uses).
struct Scene
{
  RenderSettings Settings;
  SceneMedium Medium;
  int LightCount = 0;
  vtkSmartPointer<vtkCamera> Camera;
  double MediumSeconds = 0.0;
};

/// Reads `scene` (file names relative to `base`) and configures `renderer` with it: settings,
/// medium as its input, lights, camera, background. Prints the medium stage unless `quiet`.
/// Throws SceneError for a bad scene, std::runtime_error where building the medium fails.
Scene ReadScene(
  const json& scene, const std::string& base, vtkRefractaImageRenderer* renderer, bool quiet);
}

#endif
