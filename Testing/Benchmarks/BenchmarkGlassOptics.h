// BenchmarkGlassOptics.h: what the two files of BenchmarkGlassOptics share (the program's
// settings, scenes, render and view; BenchmarkGlassOptics.cxx holds the floor figures and main,
// BenchmarkGlassOpticsShaft.cxx the light shaft). See BenchmarkGlassOptics.cxx for what it
// measures.
#ifndef BenchmarkGlassOptics_h
#define BenchmarkGlassOptics_h

#include "vtkCamera.h"
#include "vtkMath.h"
#include "vtkNew.h"

#include "RefractaIdealGlass.h"
#include "RefractaShaftMeasures.h"

#include <cmath>
#include <vector>

namespace glass_optics
{
using namespace RefractaIdealGlass;
using namespace RefractaShaftMeasures;

// The spot light's intensity on its axis (the ideal optics uses 1).
constexpr double LightIntensity = 60;

struct Settings
{
  int Size = 256;
  int Photons = 1 << 18;
  int Grid[3] = { 80, 76, 80 };
  int Rays = 4000;
  int ShaftRays = 3000;                // light rays for the shaft's fluence planes (per cone axis)
  int ShaftImageRays = 1500;           // light rays for the shaft's ideal image
  bool ShaftMultipleScattering = true; // false: the shaft's renders without the lattice
  // vtkPhotonTracer::VolumeCausticSubdivision; also the factor of the shaft's S1 lattices.
  int VolumeCaustic = 4;
  double CausticPieces = -1; // vtkPhotonTracer::VolumeCausticPiecesPerFineVoxel (< 0: its default)
};

// Which scene to render. The shaft's renders (BlackFloor) take the default scene with its fog and
// a black floor, with the glass ball and with a black opaque ball in its place: their difference
// is the light through the glass (the floor behind the shaft, which would add the caustic and the
// light through the ball on the floor, adds nothing to either).
struct Scene
{
  bool Ball = true;        // the glass ball (false: none)
  bool Exact = true;       // exact interfaces (false: the paper's smoothed index)
  bool Fog = false;        // the default scene's fog
  bool OpaqueBall = false; // a black opaque sphere instead of the glass
  bool BlackFloor = false; // floor albedo 0 (else 0.8); single scattering by photons
  unsigned int Seed = 1;   // the photon pass's
  // One centre ray per pixel (DielectricSupersampling 1): the floor figures' renders, since the
  // apparent radius counts the pixels whose centre ray sees the ball, as the ideal silhouette.
  bool CentreRays = false;
};

// The default scene's camera.
void SetCamera(vtkCamera* camera);

struct Render
{
  std::vector<float> Image; // RGBA, row 0 at the bottom
  double Seconds = 0;
  double LightSeconds = 0;    // the photon pass's
  int VolumeCaustic = 1;      // the volume caustic's subdivision in the photon pass (1: none)
  ScatteringLattice Lighting; // the lighting volume's S1 = sigma_s phi (red)
};

// The scene through the render pipeline.
Render RenderScene(const Settings& s, const Scene& scene);

//------------------------------------------------------------------------------
// The camera's rays and the floor, in pixel coordinates (x, y in [0, size), pixel i covering
// [i, i + 1), row 0 at the bottom).
struct View : Pinhole
{
  explicit View(int size)
  {
    Size = size;
    vtkNew<vtkCamera> c;
    SetCamera(c);
    double p[3], f[3], u[3];
    c->GetPosition(p);
    c->GetFocalPoint(f);
    c->GetViewUp(u);
    Eye = { p[0], p[1], p[2] };
    Forward = Unit(Add({ f[0], f[1], f[2] }, Eye, -1.0));
    V3 up = { u[0], u[1], u[2] };
    Right = Unit({ Forward[1] * up[2] - Forward[2] * up[1], Forward[2] * up[0] - Forward[0] * up[2],
      Forward[0] * up[1] - Forward[1] * up[0] });
    Up = { Right[1] * Forward[2] - Right[2] * Forward[1],
      Right[2] * Forward[0] - Right[0] * Forward[2],
      Right[0] * Forward[1] - Right[1] * Forward[0] };
    Tan = std::tan(vtkMath::RadiansFromDegrees(c->GetViewAngle()) / 2);
  }

  // Floor point seen along the ray through (x, y); false when the ray misses the floor.
  bool Floor(double x, double y, V3& hit) const
  {
    const V3 d = Ray(x, y);
    if (d[1] >= 0)
    {
      return false;
    }
    hit = Add(Eye, d, (FloorY - Eye[1]) / d[1]);
    return std::abs(hit[0]) <= 1.2 && std::abs(hit[2]) <= 1.2;
  }

  // Whether the pixel's centre ray meets the ball.
  bool SeesBall(int i, int j) const
  {
    const V3 d = Ray(i + 0.5, j + 0.5);
    const V3 oc = Add(Eye, BallCentre, -1.0);
    const double b = Dot(oc, d), c = Dot(oc, oc) - BallRadius * BallRadius;
    return b * b - c > 0 && -b > 0;
  }
};

// Measures and prints the light shaft below the ball (BenchmarkGlassOpticsShaft.cxx); returns
// whether every render ran. `narrowMet[m]`, `lightMet[m]` (m = 0 exact, 1 smoothed): whether the
// shaft narrows as the optics say and holds the ideal light (the --check criteria).
bool MeasureShaft(const Settings& s, const View& view, bool lightMet[2], bool narrowMet[2]);
}

#endif
