#include "RefractaScenes.h"

#include "vtkCamera.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkRefractaParticleMedium.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>

namespace refracta
{
namespace scenes
{
namespace
{
struct Voxel
{
  double N = 1.0;
  double SigmaT[3] = { 0, 0, 0 };
  double Albedo[3] = { 0, 0, 0 };
  double G = 0.0;
  double Emission[3] = { 0, 0, 0 };
  double Occupancy = 0.0;
};

vtkFloatArray* AddArray(vtkImageData* image, const char* name, int components)
{
  vtkNew<vtkFloatArray> array;
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(image->GetNumberOfPoints());
  array->Fill(0.0);
  image->GetPointData()->AddArray(array);
  return array;
}

// Sample `field` at the voxel centres of the unit cube at resolution n.
vtkSmartPointer<vtkImageData> Build(
  int n, const std::function<Voxel(double, double, double)>& field)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(n, n, n);
  const double h = 1.0 / n;
  image->SetSpacing(h, h, h);
  image->SetOrigin(0.5 * h, 0.5 * h, 0.5 * h);
  vtkFloatArray* index = AddArray(image, "RefractiveIndex", 1);
  vtkFloatArray* extinction = AddArray(image, "Extinction", 3);
  vtkFloatArray* albedo = AddArray(image, "Albedo", 3);
  vtkFloatArray* anisotropy = AddArray(image, "Anisotropy", 1);
  vtkFloatArray* emission = AddArray(image, "Emission", 3);
  vtkFloatArray* occupancy = AddArray(image, "Occupancy", 1);
  AddArray(image, "RefractiveIndexGradient", 3);
  vtkSMPTools::For(0, n,
    [&](int k0, int k1)
    {
      for (int k = k0; k < k1; ++k)
      {
        for (int j = 0; j < n; ++j)
        {
          for (int i = 0; i < n; ++i)
          {
            const vtkIdType p = i + static_cast<vtkIdType>(n) * (j + static_cast<vtkIdType>(n) * k);
            const Voxel v = field((i + 0.5) * h, (j + 0.5) * h, (k + 0.5) * h);
            index->SetValue(p, static_cast<float>(v.N));
            anisotropy->SetValue(p, static_cast<float>(v.G));
            occupancy->SetValue(p, static_cast<float>(v.Occupancy));
            for (int c = 0; c < 3; ++c)
            {
              extinction->SetComponent(p, c, v.SigmaT[c]);
              albedo->SetComponent(p, c, v.Albedo[c]);
              emission->SetComponent(p, c, v.Emission[c]);
            }
          }
        }
      }
    });
  ComputeIndexGradient(image);
  return image;
}

// Smooth step from 0 (outside) to 1 (inside) across a boundary at signed distance d (d < 0
// inside), over about `width` world units.
double Inside(double d, double width)
{
  const double x = d / width;
  // Exactly 0 or 1 far from the boundary, so that empty space is empty (tanh never reaches 0).
  return x > 8.0 ? 0.0 : (x < -8.0 ? 1.0 : 0.5 * (1.0 - std::tanh(x)));
}

void SetRGB(double rgb[3], double r, double g, double b)
{
  rgb[0] = r;
  rgb[1] = g;
  rgb[2] = b;
}

void SetBox(double box[6], double x0, double x1, double y0, double y1, double z0, double z1)
{
  const double values[6] = { x0, x1, y0, y1, z0, z1 };
  std::copy(values, values + 6, box);
}

// A point light (cone 180 degrees) at `position`, its axis towards `focus`.
vtkSmartPointer<vtkLight> MakePointLight(
  const double position[3], const double focus[3], double intensity)
{
  auto light = vtkSmartPointer<vtkLight>::New();
  light->SetPositional(true);
  light->SetConeAngle(180);
  light->SetPosition(position[0], position[1], position[2]);
  light->SetFocalPoint(focus[0], focus[1], focus[2]);
  light->SetIntensity(intensity);
  return light;
}

vtkSmartPointer<vtkCamera> MakeCamera(double x, double y, double z)
{
  auto camera = vtkSmartPointer<vtkCamera>::New();
  camera->SetPosition(x, y, z);
  camera->SetFocalPoint(0.5, 0.5, 0.5);
  camera->SetViewUp(0, 1, 0);
  camera->SetViewAngle(30);
  return camera;
}
}

void ComputeIndexGradient(vtkImageData* medium)
{
  int dims[3];
  medium->GetDimensions(dims);
  const double* spacing = medium->GetSpacing();
  vtkDataArray* n = medium->GetPointData()->GetArray("RefractiveIndex");
  vtkDataArray* gradient = medium->GetPointData()->GetArray("RefractiveIndexGradient");
  if (!n || !gradient)
  {
    return;
  }
  auto id = [&](int i, int j, int k)
  { return i + static_cast<vtkIdType>(dims[0]) * (j + static_cast<vtkIdType>(dims[1]) * k); };
  vtkSMPTools::For(0, dims[2],
    [&](int k0, int k1)
    {
      for (int k = k0; k < k1; ++k)
      {
        for (int j = 0; j < dims[1]; ++j)
        {
          for (int i = 0; i < dims[0]; ++i)
          {
            const int ijk[3] = { i, j, k };
            for (int a = 0; a < 3; ++a)
            {
              double g = 0.0;
              if (dims[a] > 1)
              {
                int lo[3] = { i, j, k }, hi[3] = { i, j, k };
                lo[a] = std::max(ijk[a] - 1, 0);
                hi[a] = std::min(ijk[a] + 1, dims[a] - 1);
                g = (n->GetComponent(id(hi[0], hi[1], hi[2]), 0) -
                      n->GetComponent(id(lo[0], lo[1], lo[2]), 0)) /
                  ((hi[a] - lo[a]) * spacing[a]);
              }
              gradient->SetComponent(id(i, j, k), a, g);
            }
          }
        }
      }
    });
}

Scene GlassSphereInFog(int n)
{
  Scene scene;
  scene.Name = "glass-sphere-in-fog";
  const double width = 1.5 / n;
  scene.Medium = Build(n,
    [&](double x, double y, double z)
    {
      Voxel v;
      const double r =
        std::sqrt((x - 0.5) * (x - 0.5) + (y - 0.6) * (y - 0.6) + (z - 0.5) * (z - 0.5));
      const double glass = Inside(r - 0.25, width);
      v.N = 1.0 + 0.5 * glass;
      const double fog = 0.6, clear = 0.02;
      for (int c = 0; c < 3; ++c)
      {
        v.SigmaT[c] = glass * clear + (1.0 - glass) * fog;
        v.Albedo[c] = (1.0 - glass) * 0.9; // fog scatters, glass absorbs its little extinction
      }
      v.G = 0.2;
      v.Occupancy = glass;
      return v;
    });
  auto spot = vtkSmartPointer<vtkLight>::New();
  spot->SetPositional(true);
  spot->SetPosition(0.5, 1.6, 0.5);
  spot->SetFocalPoint(0.5, 0.0, 0.5);
  spot->SetConeAngle(20);
  spot->SetExponent(2);
  spot->SetIntensity(4.0);
  scene.Lights.push_back(spot);
  scene.Camera = MakeCamera(0.5, 0.55, 3.2);
  SetRGB(scene.Background, 0.05, 0.05, 0.08);
  SetBox(scene.RegionOfInterest, 0.4, 0.6, 0.1, 0.36, 0.4, 0.6);
  scene.LightRadius = 0.1;
  scene.RegionName = "caustic below the sphere";
  return scene;
}

Scene HeterogeneousCloud(int n)
{
  Scene scene;
  scene.Name = "heterogeneous-cloud";
  scene.Medium = Build(n,
    [](double x, double y, double z)
    {
      Voxel v;
      const double dx = x - 0.5, dy = y - 0.5, dz = z - 0.5;
      const double r = std::sqrt(dx * dx + dy * dy + dz * dz);
      // A smooth blob modulated by a few incommensurate waves: deterministic "noise".
      const double waves = 0.5 +
        0.25 * std::sin(11.0 * x + 2.0 * std::sin(7.0 * z)) * std::cos(9.0 * y + 1.3) +
        0.25 * std::sin(17.0 * z + 3.0 * x) * std::sin(13.0 * y);
      const double density = std::max(0.0, Inside(r - 0.38, 0.05) * waves);
      for (int c = 0; c < 3; ++c)
      {
        v.SigmaT[c] = 12.0 * density;
        v.Albedo[c] = 0.95;
      }
      v.G = 0.6;
      v.Occupancy = density > 0 ? 1.0 : 0.0;
      return v;
    });
  auto sun = vtkSmartPointer<vtkLight>::New();
  sun->SetPositional(false);
  sun->SetPosition(1.5, 2.0, 1.0);
  sun->SetFocalPoint(0.5, 0.5, 0.5);
  sun->SetIntensity(1.0);
  scene.Lights.push_back(sun);
  scene.Camera = MakeCamera(0.5, 0.5, 3.2);
  SetRGB(scene.Background, 0.3, 0.45, 0.7);
  SetBox(scene.RegionOfInterest, 0.25, 0.75, 0.25, 0.75, 0.25, 0.75);
  scene.RegionName = "cloud core";
  return scene;
}

Scene GrinLens(int n)
{
  Scene scene;
  scene.Name = "grin-lens";
  const double A = 2.0; // 1 / length^2: focuses within the unit cube
  scene.Medium = Build(n,
    [&](double x, double y, double z)
    {
      Voxel v;
      const double r2 = (x - 0.5) * (x - 0.5) + (y - 0.5) * (y - 0.5);
      const double rod =
        Inside(std::sqrt(r2) - 0.35, 2.0 / 128.0) * Inside(std::abs(z - 0.5) - 0.3, 2.0 / 128.0);
      v.N = 1.0 + rod * (0.6 - 0.8 * A * r2);
      for (int c = 0; c < 3; ++c)
      {
        v.SigmaT[c] = 0.3;
        v.Albedo[c] = 0.8;
      }
      v.Occupancy = rod;
      return v;
    });
  auto beam = vtkSmartPointer<vtkLight>::New();
  beam->SetPositional(false);
  beam->SetPosition(0.5, 0.5, 2.0);
  beam->SetFocalPoint(0.5, 0.5, 0.5);
  beam->SetIntensity(2.0);
  scene.Lights.push_back(beam);
  scene.Camera = MakeCamera(3.0, 0.9, 0.5);
  SetBox(scene.RegionOfInterest, 0.3, 0.7, 0.3, 0.7, 0.0, 0.25);
  scene.LightAngularRadius = 3.0;
  scene.RegionName = "beam converging out of the lens";
  return scene;
}

Scene DenseObject(int n)
{
  Scene scene;
  scene.Name = "dense-high-albedo";
  scene.Medium = Build(n,
    [&](double x, double y, double z)
    {
      Voxel v;
      const double d = std::max({ std::abs(x - 0.5), std::abs(y - 0.5), std::abs(z - 0.5) }) - 0.2;
      const double inside = Inside(d, 1.0 / n);
      for (int c = 0; c < 3; ++c)
      {
        v.SigmaT[c] = 60.0 * inside;
        v.Albedo[c] = 0.99;
      }
      v.Albedo[2] = 0.97; // a little colour
      v.Occupancy = inside;
      return v;
    });
  const double bulb[3] = { 0.9, 0.9, 0.9 }, centre[3] = { 0.5, 0.5, 0.5 };
  scene.Lights.push_back(MakePointLight(bulb, centre, 0.5));
  scene.Camera = MakeCamera(2.5, 1.5, 2.5);
  SetBox(scene.RegionOfInterest, 0.3, 0.7, 0.3, 0.7, 0.3, 0.7);
  scene.LightRadius = 0.02;
  scene.RegionName = "dense cube";
  return scene;
}

Scene LampInFog(int n)
{
  Scene scene;
  scene.Name = "lamp-in-fog";
  scene.Medium = Build(n,
    [&](double, double, double)
    {
      Voxel v;
      for (int c = 0; c < 3; ++c)
      {
        v.SigmaT[c] = 4.0;
        v.Albedo[c] = 0.95;
      }
      v.Albedo[2] = 0.9; // a little colour
      return v;
    });
  const double centre[3] = { 0.5, 0.5, 0.5 }, below[3] = { 0.5, 0.0, 0.5 };
  scene.Lights.push_back(MakePointLight(centre, below, 0.05));
  scene.Camera = MakeCamera(0.5, 0.5, 3.2);
  SetBox(scene.RegionOfInterest, 0.2, 0.8, 0.2, 0.8, 0.2, 0.8);
  scene.LightRadius = 0.02;
  scene.RegionName = "glow around the lamp";
  return scene;
}

std::vector<Scene> AllScenes(int n)
{
  return { GlassSphereInFog(n), HeterogeneousCloud(n), GrinLens(n), DenseObject(n) };
}

std::vector<Scene> ExtraScenes(int n)
{
  return { LampInFog(n) };
}

const double ParticleLightTravel[3] = { -0.4, -0.8, -0.45 };

Scene ParticleCloudView()
{
  Scene view;
  view.Name = "particle-cloud";
  auto sun = vtkSmartPointer<vtkLight>::New();
  sun->SetPositional(false);
  sun->SetPosition(
    -10 * ParticleLightTravel[0], -10 * ParticleLightTravel[1], -10 * ParticleLightTravel[2]);
  sun->SetFocalPoint(0, 0, 0);
  sun->SetIntensity(1.0);
  view.Lights.push_back(sun);
  view.LightAngularRadius = 0.0; // the illumination network's light is a delta light
  view.Camera = vtkSmartPointer<vtkCamera>::New();
  view.Camera->SetPosition(0.5, 0.6, 4.0);
  view.Camera->SetFocalPoint(0, 0, 0);
  view.Camera->SetViewUp(0, 1, 0);
  view.Camera->SetViewAngle(36);
  return view;
}

vtkSmartPointer<vtkPolyData> ParticleCloud(int n)
{
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  vtkNew<vtkPoints> points;
  while (points->GetNumberOfPoints() < n)
  {
    const double x = u(rng), y = u(rng), z = u(rng);
    if (x * x + y * y + z * z <= 1.0)
    {
      points->InsertNextPoint(x, y, z);
    }
  }
  // Particles of volume fraction 1 (n r^3 = 1): r = n^(-1/3); sigma so that the cloud's
  // extinction n V sigma = 10 per unit (20 collisions across the diameter).
  const double r = std::cbrt(1.0 / n);
  const double sigma = 10.0 / (n * 4.0 / 3.0 * vtkMath::Pi() * r * r * r);
  auto cloud = vtkSmartPointer<vtkPolyData>::New();
  cloud->SetPoints(points);
  auto add = [&](const char* name, int comps, double value)
  {
    vtkNew<vtkFloatArray> a;
    a->SetName(name);
    a->SetNumberOfComponents(comps);
    a->SetNumberOfTuples(n);
    a->Fill(value);
    cloud->GetPointData()->AddArray(a);
  };
  add(vtkRefractaParticleMedium::RadiusName(), 1, r);
  add(vtkRefractaParticleMedium::ExtinctionName(), 3, sigma);
  add(vtkRefractaParticleMedium::AlbedoName(), 3, 0.9);
  return cloud;
}
}
}
