// The hard cases with opaque surfaces (see HardCaseScenes.h): surfaces inside the medium, touching
// its box, closed around the light, and met edge-on by grazing light.
#include "HardCaseScenes.h"

#include "vtkCubeSource.h"
#include "vtkNew.h"
#include "vtkPlaneSource.h"
#include "vtkPolyData.h"
#include "vtkRefractaSurfaceMaterial.h"

namespace refracta_hard_cases
{
namespace
{
Voxel Fog(double sigmaT, double albedo)
{
  Voxel v;
  v.SigmaT = sigmaT;
  v.Albedo = albedo;
  return v;
}

// A square of side `size` centred at `centre` with unit `normal`.
vtkSmartPointer<vtkPolyData> Square(
  std::array<double, 3> centre, std::array<double, 3> normal, double size)
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetCenter(centre.data());
  plane->SetNormal(normal.data());
  plane->SetResolution(3, 3);
  plane->Update();
  // vtkPlaneSource makes a unit square: scale it about its centre.
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->DeepCopy(plane->GetOutput());
  vtkPoints* points = mesh->GetPoints();
  for (vtkIdType p = 0; p < points->GetNumberOfPoints(); ++p)
  {
    double x[3];
    points->GetPoint(p, x);
    for (int a = 0; a < 3; ++a)
    {
      x[a] = centre[a] + size * (x[a] - centre[a]);
    }
    points->SetPoint(p, x);
  }
  return mesh;
}

vtkSmartPointer<vtkPolyData> Cube(std::array<double, 3> centre, double side)
{
  vtkNew<vtkCubeSource> cube;
  cube->SetCenter(centre.data());
  cube->SetXLength(side);
  cube->SetYLength(side);
  cube->SetZLength(side);
  cube->Update();
  return cube->GetOutput();
}

vtkSmartPointer<vtkRefractaSurfaceSet> Surfaces(
  std::vector<vtkSmartPointer<vtkPolyData>> meshes, double albedo)
{
  auto set = vtkSmartPointer<vtkRefractaSurfaceSet>::New();
  for (const auto& mesh : meshes)
  {
    vtkNew<vtkRefractaSurfaceMaterial> material;
    material->SetAlbedo(albedo, albedo, albedo);
    set->AddSurface(mesh, material);
  }
  return set;
}
}

void AddSurfaceCases(std::vector<HardCase>& cases, int n)
{
  const double h = 1.0 / n;
  const double c = 0.5 - 0.5 * h; // the box's centre; the box spans [-h/2, 1 - h/2]
  const double lo = -0.5 * h;
  auto fog = [](double sigmaT, double albedo)
  { return [=](double, double, double) { return Fog(sigmaT, albedo); }; };
  auto fromAbove = [&] { return Light(false, { c, 3, c }, { c, c, c }, 1.0); };
  const auto front = Camera({ c, c + 0.2, 3.0 }, { c, c - 0.1, c });

  // A floor through the middle of a scattering fog, wider than the medium: photons reach it inside
  // the medium and outside it, reflect, and scatter again.
  Add(cases, "floor inside the fog", MakeMedium({ n, n, n }, { h, h, h }, fog(2.0, 0.8)),
    { fromAbove() }, front)
    .Surfaces = Surfaces({ Square({ c, c, c }, { 0, 1, 0 }, 2.0) }, 0.7);
  cases.back().SurfaceLit = true;

  // A floor exactly on the medium's bottom face: every photon that crosses the fog meets it where
  // the grid ends (the surface and the box's face coincide to the last bit).
  Add(cases, "floor touching the medium's face",
    MakeMedium({ n, n, n }, { h, h, h }, fog(1.0, 0.9)), { fromAbove() }, front)
    .Surfaces = Surfaces({ Square({ c, lo, c }, { 0, 1, 0 }, 1.0) }, 0.9);
  cases.back().SurfaceLit = true;

  // A point light inside a closed box (its faces on voxel faces) in a fog: no photon may leave
  // the box, so nothing escapes and no voxel more than one voxel outside the box (the reach of
  // the 3^3 smoothing) is lit.
  Add(cases, "light enclosed by a closed surface",
    MakeMedium({ n, n, n }, { h, h, h }, fog(1.5, 0.7)),
    { Light(true, { c, c, c }, { 1, c, c }, 1.0) }, front)
    .Surfaces = Surfaces({ Cube({ c, c, c }, 6 * h) }, 0.5);
  cases.back().LightEnclosed = true;
  cases.back().SurfaceLit = true;

  // Light grazing a plane that lies on a layer of voxel centres: photons travel in the plane of
  // the triangles (edge-on hits, the watertight test's degenerate case) through a dense fog.
  const double y = 8 * h;
  Add(cases, "light grazing a surface edge-on",
    MakeMedium({ n, n, n }, { h, h, h }, fog(3.0, 0.95)),
    { Light(false, { -3, y, c }, { 1, y, c }, 1.0) }, front)
    .Surfaces = Surfaces({ Square({ c, y, c }, { 0, 1, 0 }, 0.8) }, 0.8);
}
}
