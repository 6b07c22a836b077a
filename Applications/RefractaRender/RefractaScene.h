// A whole refracta-render scene read, checked and handed to a renderer, short of rendering it:
// the settings, the medium, the lights, the camera and the background. refracta-render renders
// what this sets up; the scene fuzzer (Testing/Fuzz) runs it on hostile scene files.
#ifndef RefractaScene_h
#define RefractaScene_h

#include "RefractaSceneMedium.h"
#include "RefractaSceneSettings.h"
#include "RefractaSceneSurfaces.h"

#include "vtkSmartPointer.h"

#include <string>
#include <vector>

class vtkCamera;
class vtkRefractaImageRenderer;
class vtkRefractaSurfaceSet;

namespace RefractaRender
{
/// What ReadScene read (and the report uses).
struct Scene
{
  RenderSettings Settings;
  SceneMedium Medium;
  std::vector<SceneSurface> Surfaces;
  vtkSmartPointer<vtkRefractaSurfaceSet> SurfaceSet;
  int LightCount = 0;
  vtkSmartPointer<vtkCamera> Camera;
  bool EnvironmentLight = false; ///< background.illuminates
  double SurfacesSeconds = 0.0;
  double MediumSeconds = 0.0;
};

/// refracta-render's default scene (--print-default-scene): a glass sphere (n = 1.5) in a light
/// fog above a checkered floor, lit by a spot light from above, before a checkerboard background.
extern const char* const DefaultSceneJson;

/// Reads `scene` (file names relative to `base`) and configures `renderer` with it: settings,
/// surfaces, medium as its input, lights, camera, background. Prints the medium stage unless
/// `quiet`. Throws SceneError for a bad scene, FilterError where building the medium fails.
Scene ReadScene(
  const json& scene, const std::string& base, vtkRefractaImageRenderer* renderer, bool quiet);
}

#endif
