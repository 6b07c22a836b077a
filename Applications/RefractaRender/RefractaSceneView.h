// What surrounds the medium in a refracta-render scene: "lights", "camera" and "background"
// (a colour, an environment image or a checkerboard environment).
#ifndef RefractaSceneView_h
#define RefractaSceneView_h

#include "RefractaSceneJson.h"

#include "vtkSmartPointer.h"

#include <string>

class vtkCamera;
class vtkImageData;
class vtkRefractaImageRenderer;

namespace RefractaRender
{
/// Adds the lights of "scene.lights" to the renderer; returns how many there are.
int AddLights(const json& scene, vtkRefractaImageRenderer* renderer);

/// The camera of "scene.camera"; where unset it looks at the medium's centre from the front.
vtkSmartPointer<vtkCamera> ReadCamera(const json& scene, vtkImageData* medium);

/// Sets the background colour or environment map of "scene.background" (files relative to
/// `base`) and the environment's up and right directions; returns "illuminates" (default false:
/// whether the background also lights the scene; true is refused until the photon pass emits
/// from the environment).
bool ReadBackground(const json& scene, const std::string& base, vtkRefractaImageRenderer* renderer);
}

#endif
