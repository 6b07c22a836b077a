// The hard-case scenes (Refracta.HardCases): media, lights, cameras and surfaces at the edges of
// what the physics and the numbers allow, each with what is known about its answer. The checks
// that run every pass on them are in TestHardCases.cxx.
#ifndef HardCaseScenes_h
#define HardCaseScenes_h

#include "vtkCamera.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkRefractaImageRenderer.h"
#include "vtkRefractaSurfaceSet.h"
#include "vtkSmartPointer.h"

#include <array>
#include <functional>
#include <string>
#include <vector>

namespace refracta_hard_cases
{
struct Voxel
{
  double N = 1.0;
  double SigmaT = 0.0;
  double Albedo = 0.0;
  double G = 0.0;
};

// A case: a medium, its lights, a camera, and what is known about the answer.
struct HardCase
{
  std::string Name;
  vtkSmartPointer<vtkImageData> Medium;
  std::vector<vtkSmartPointer<vtkLight>> Lights;
  vtkSmartPointer<vtkCamera> Camera;
  bool NothingInteracts = false; // vacuum-like: every emitted photon escapes, nothing scatters
  bool NoLightPower = false;     // nothing is emitted at all
  bool Opaque = false;           // nothing gets through: no photon escapes with power
  bool Conservative = false;     // albedo 1: nothing is absorbed
  // Known answers of the newer cases (negative: none).
  double ExpectedEmitted = -1;     // photon pass, per channel: I x the solid angle entering
  double ExpectedAbsorbed = -1;    // photon pass, per channel, within 3%
  bool NoneMissed = false;         // the light is inside: every photon starts in the medium
  double CentreTransmittance = -1; // pipeline image, centre pixels = background x this (3%)
  bool ImageIsBackground = false;  // pipeline image = background in every pixel (0.5%)
  double Exposure = 1.0;           // the pipeline image's tone mapping
  int ToneMapping = vtkRefractaImageRenderer::CLAMP;
  int ExpectedRGB = -1; // every tone-mapped channel (0..255) of the pipeline image
  // Opaque surfaces in the scene (none: nullptr), and what is known with them.
  vtkSmartPointer<vtkRefractaSurfaceSet> Surfaces;
  bool LightEnclosed = false; // a closed surface surrounds every light: nothing escapes
  bool SurfaceLit = false;    // some power reaches a surface (EnergySurface > 0)
};

using Field = std::function<Voxel(double, double, double)>; // at grid-local voxel centres

vtkSmartPointer<vtkImageData> MakeMedium(std::array<int, 3> dims, std::array<double, 3> spacing,
  const Field& f, std::array<double, 3> origin = { 0, 0, 0 }, bool withGradient = false);
vtkSmartPointer<vtkLight> Light(bool positional, std::array<double, 3> at, std::array<double, 3> to,
  double intensity, double coneAngle = 180);
vtkSmartPointer<vtkCamera> Camera(std::array<double, 3> at, std::array<double, 3> to);
// A profile falling from 1 to 0 across d = 0 over about `width`.
double Smooth(double d, double width);
HardCase& Add(std::vector<HardCase>& cases, std::string name, vtkSmartPointer<vtkImageData> medium,
  std::vector<vtkSmartPointer<vtkLight>> lights, vtkSmartPointer<vtkCamera> camera);

// Every case, in a fixed order (the test names follow it).
std::vector<HardCase> MakeCases();
// The cases with surfaces (HardCaseSurfaces.cxx), on an n^3 grid of the unit box.
void AddSurfaceCases(std::vector<HardCase>& cases, int n);
}

#endif
