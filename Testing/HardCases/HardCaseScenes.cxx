// The hard-case scenes without surfaces (see HardCaseScenes.h).
#include "HardCaseScenes.h"

#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"

#include <cmath>

namespace refracta_hard_cases
{
vtkSmartPointer<vtkImageData> MakeMedium(std::array<int, 3> dims, std::array<double, 3> spacing,
  const Field& f, std::array<double, 3> origin, bool withGradient)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(dims.data());
  image->SetSpacing(spacing.data());
  image->SetOrigin(origin.data());
  auto add = [&](const char* name, int comps)
  {
    vtkNew<vtkFloatArray> a;
    a->SetName(name);
    a->SetNumberOfComponents(comps);
    a->SetNumberOfTuples(image->GetNumberOfPoints());
    a->Fill(0.0);
    image->GetPointData()->AddArray(a);
    return a.GetPointer();
  };
  vtkFloatArray* n = add("RefractiveIndex", 1);
  vtkFloatArray* ext = add("Extinction", 3);
  vtkFloatArray* alb = add("Albedo", 3);
  vtkFloatArray* g = add("Anisotropy", 1);
  for (int k = 0; k < dims[2]; ++k)
  {
    for (int j = 0; j < dims[1]; ++j)
    {
      for (int i = 0; i < dims[0]; ++i)
      {
        const vtkIdType id =
          i + static_cast<vtkIdType>(dims[0]) * (j + static_cast<vtkIdType>(dims[1]) * k);
        const Voxel v = f(i * spacing[0], j * spacing[1], k * spacing[2]);
        n->SetValue(id, static_cast<float>(v.N));
        g->SetValue(id, static_cast<float>(v.G));
        for (int c = 0; c < 3; ++c)
        {
          ext->SetComponent(id, c, v.SigmaT);
          alb->SetComponent(id, c, v.Albedo);
        }
      }
    }
  }
  if (withGradient)
  {
    add("RefractiveIndexGradient", 3); // deliberately zero: a sharp step with no smoothing at all
  }
  return image;
}

vtkSmartPointer<vtkLight> Light(bool positional, std::array<double, 3> at, std::array<double, 3> to,
  double intensity, double coneAngle)
{
  auto light = vtkSmartPointer<vtkLight>::New();
  light->SetPositional(positional);
  light->SetPosition(at.data());
  light->SetFocalPoint(to.data());
  light->SetIntensity(intensity);
  light->SetConeAngle(coneAngle);
  return light;
}

vtkSmartPointer<vtkCamera> Camera(std::array<double, 3> at, std::array<double, 3> to)
{
  auto camera = vtkSmartPointer<vtkCamera>::New();
  camera->SetPosition(at.data());
  camera->SetFocalPoint(to.data());
  camera->SetViewUp(0, 1, 0);
  if (std::abs(at[0] - to[0]) < 1e-9 && std::abs(at[2] - to[2]) < 1e-9)
  {
    camera->SetViewUp(0, 0, 1);
  }
  return camera;
}

double Smooth(double d, double width)
{
  return 0.5 * (1.0 - std::tanh(d / width));
}

HardCase& Add(std::vector<HardCase>& cases, std::string name, vtkSmartPointer<vtkImageData> medium,
  std::vector<vtkSmartPointer<vtkLight>> lights, vtkSmartPointer<vtkCamera> camera)
{
  cases.push_back({ std::move(name), medium, std::move(lights), camera });
  return cases.back();
}

// The camera inside the medium: inside a fog, and at the centre of a glass ball.
void AddViewpointCases(std::vector<HardCase>& cases, int n)
{
  const double h = 1.0 / n;
  const double c = 0.5 - 0.5 * h; // the box's centre (a voxel corner)
  // A pure absorber, no light: looking along +x from the centre, the view crosses 0.5 of fog to
  // the box's face (at (n - 0.5) h), so the centre pixels are the background x exp(-0.5 sigma).
  const double sigma = 1.0;
  Add(cases, "camera inside the medium",
    MakeMedium({ n, n, n }, { h, h, h },
      [=](double, double, double)
      {
        Voxel v;
        v.SigmaT = sigma;
        return v;
      }),
    {}, Camera({ c, c, c }, { 1, c, c }))
    .CentreTransmittance = std::exp(-0.5 * sigma);
  // Clear glass (n = 1.5 in a ball of radius 0.3, vacuum around): from the ball's centre every
  // view ray is radial, meets the interface head-on and leaves unbent and unattenuated, so the
  // image is the background everywhere (basic radiance: the background is not divided by n^2).
  Add(cases, "camera inside glass",
    MakeMedium({ n, n, n }, { h, h, h },
      [=](double x, double y, double z)
      {
        Voxel v;
        const double r = std::sqrt((x - c) * (x - c) + (y - c) * (y - c) + (z - c) * (z - c));
        v.N = 1.0 + 0.5 * Smooth(r - 0.3, h);
        return v;
      }),
    { Light(false, { c, 3, c }, { c, c, c }, 1.0) }, Camera({ c, c, c }, { c, c, 1 }))
    .ImageIsBackground = true;
  cases.back().NothingInteracts = true;
}

// Point lights exactly on a voxel face inside a fog, and on a corner and a face of the box of an
// opaque absorber (what enters is absorbed at once, so the absorbed power is the light's
// intensity times the solid angle of the box seen from the light: pi / 2 from a corner, 2 pi
// from a face).
void AddLightPlacementCases(std::vector<HardCase>& cases)
{
  const int n = 8;
  const double h = 1.0 / n;
  const double c = 0.5 - 0.5 * h;
  auto fog = [](double sigmaT, double albedo)
  {
    return [=](double, double, double)
    {
      Voxel v;
      v.SigmaT = sigmaT;
      v.Albedo = albedo;
      return v;
    };
  };
  auto front = [=] { return Camera({ c, c, 3.0 }, { c, c, c }); };
  const double pi = 3.14159265358979323846;
  // x on the face between voxels 2 and 3, y and z at voxel centres: every photon starts inside.
  HardCase& face =
    Add(cases, "point light on a voxel face", MakeMedium({ n, n, n }, { h, h, h }, fog(2.0, 0.8)),
      { Light(true, { 2.5 * h, 3 * h, 4 * h }, { 1, 3 * h, 4 * h }, 1.0) }, front());
  face.NoneMissed = true;
  face.ExpectedEmitted = 4 * pi;
  HardCase& corner = Add(cases, "point light on the grid's corner",
    MakeMedium({ n, n, n }, { h, h, h }, fog(1e3 / h, 0.0)),
    { Light(true, { -0.5 * h, -0.5 * h, -0.5 * h }, { c, c, c }, 1.0) }, front());
  corner.ExpectedAbsorbed = pi / 2;
  HardCase& boxFace = Add(cases, "point light on the box's face",
    MakeMedium({ n, n, n }, { h, h, h }, fog(1e3 / h, 0.0)),
    { Light(true, { c, c, -0.5 * h }, { c, c, c }, 1.0) }, front());
  boxFace.ExpectedAbsorbed = 2 * pi;
}

// Denormal and 1e30 coefficients, refraction on an anisotropic grid, and exposure extremes.
void AddExtremeValueCases(std::vector<HardCase>& cases)
{
  const int n = 8;
  const double h = 1.0 / n;
  const double c = 0.5 - 0.5 * h;
  auto fog = [](double sigmaT, double albedo)
  {
    return [=](double, double, double)
    {
      Voxel v;
      v.SigmaT = sigmaT;
      v.Albedo = albedo;
      return v;
    };
  };
  auto above = [=] { return Light(false, { c, 3, c }, { c, c, c }, 1.0); };
  auto front = [=] { return Camera({ c, c, 3.0 }, { c, c, c }); };
  // 1e-40 is below FLT_MIN (a denormal float): nothing may interact, nothing may turn NaN.
  Add(cases, "denormal extinction 1e-40", MakeMedium({ n, n, n }, { h, h, h }, fog(1e-40, 0.5)),
    { above() }, front())
    .NothingInteracts = true;
  Add(cases, "extinction 1e30", MakeMedium({ n, n, n }, { h, h, h }, fog(1e30, 0.5)), { above() },
    front())
    .Opaque = true;
  // A tilted index ramp (1 to 1.6 along x + z) on voxels of 0.01 x 0.04 x 0.02, clear: rays bend
  // but nothing is absorbed or scattered, so every photon escapes with all its power.
  Add(cases, "refraction on anisotropic spacing",
    MakeMedium({ 12, 12, 12 }, { 0.01, 0.04, 0.02 },
      [](double x, double, double z)
      {
        Voxel v;
        v.N = 1.0 + 0.6 * Smooth(0.17 - x - z, 0.03);
        return v;
      }),
    { Light(false, { -1, 2, 0.5 }, { 0.06, 0.22, 0.11 }, 1.0) },
    Camera({ 0.06, 0.22, 3.0 }, { 0.06, 0.22, 0.11 }))
    .NothingInteracts = true;
  // Exposure at the ends of its range: 1e30 saturates every channel that has any light (every
  // pixel sees the background through the fog), 1e-30 leaves every channel black.
  HardCase& bright = Add(cases, "exposure 1e30",
    MakeMedium({ n, n, n }, { h, h, h }, fog(2.0, 0.8)), { above() }, front());
  bright.Exposure = 1e30;
  bright.ToneMapping = vtkRefractaImageRenderer::REINHARD;
  bright.ExpectedRGB = 255;
  HardCase& dark = Add(cases, "exposure 1e-30", MakeMedium({ n, n, n }, { h, h, h }, fog(2.0, 0.8)),
    { above() }, front());
  dark.Exposure = 1e-30;
  dark.ToneMapping = vtkRefractaImageRenderer::EXPONENTIAL;
  dark.ExpectedRGB = 0;
}

std::vector<HardCase> MakeCases()
{
  const int n = 16;
  const double h = 1.0 / n;
  const std::array<double, 3> centre = { 0.5 - 0.5 * h, 0.5 - 0.5 * h, 0.5 - 0.5 * h };
  auto fromAbove = [&] { return Light(false, { centre[0], 3, centre[2] }, centre, 1.0); };
  auto front = [&] { return Camera({ centre[0], centre[1], 3.0 }, centre); };
  auto fog = [](double sigmaT, double albedo, double g)
  {
    return [=](double, double, double)
    {
      Voxel v;
      v.SigmaT = sigmaT;
      v.Albedo = albedo;
      v.G = g;
      return v;
    };
  };
  auto sphere = [&](double index, double width)
  {
    return [=](double x, double y, double z)
    {
      Voxel v;
      const double r = std::sqrt(
        std::pow(x - centre[0], 2) + std::pow(y - centre[1], 2) + std::pow(z - centre[2], 2));
      v.N = 1.0 + (index - 1.0) * Smooth(r - 0.3, width);
      v.SigmaT = 0.05;
      v.Albedo = 0.5;
      return v;
    };
  };
  std::vector<HardCase> cases;
  auto add = [&](std::string name, vtkSmartPointer<vtkImageData> medium,
               std::vector<vtkSmartPointer<vtkLight>> lights) -> HardCase&
  {
    cases.push_back({ std::move(name), medium, std::move(lights), front() });
    return cases.back();
  };
  add("albedo 0.999", MakeMedium({ n, n, n }, { h, h, h }, fog(5.0, 0.999, 0.0)), { fromAbove() });
  add("albedo 1", MakeMedium({ n, n, n }, { h, h, h }, fog(5.0, 1.0, 0.0)), { fromAbove() })
    .Conservative = true;
  add("optical depth 1e4 per voxel", MakeMedium({ n, n, n }, { h, h, h }, fog(1e4 / h, 0.5, 0.0)),
    { fromAbove() })
    .Opaque = true;
  add("extinction 0 everywhere", MakeMedium({ n, n, n }, { h, h, h }, sphere(1.5, 2 * h)), {})
    .NothingInteracts = true;
  cases.back().Medium->GetPointData()->GetArray("Extinction")->Fill(0.0);
  cases.back().Lights = { fromAbove() };
  add("index jump 1 to 2.4, unsmoothed",
    MakeMedium({ n, n, n }, { h, h, h },
      [&](double, double y, double)
      {
        Voxel v;
        v.N = y < 0.5 ? 1.0 : 2.4;
        v.SigmaT = 0.1;
        v.Albedo = 0.5;
        return v;
      }),
    { Light(false, { 0, 3, 0.2 }, { 1, 0, 0.7 }, 1.0) });
  add("total internal reflection in n = 2.4 sphere",
    MakeMedium({ n, n, n }, { h, h, h }, sphere(2.4, h)),
    { Light(true, { centre[0] + 0.2, centre[1], centre[2] }, { 1, centre[1], centre[2] }, 1.0) });
  add("grazing rays on an interface",
    MakeMedium({ n, n, n }, { h, h, h },
      [&](double, double y, double)
      {
        Voxel v;
        v.N = 1.0 + 0.5 * Smooth(0.5 - y, h);
        v.SigmaT = 0.2;
        v.Albedo = 0.7;
        return v;
      }),
    { Light(false, { -3, 0.5 + 3e-3, 0.5 }, { 1, 0.5, 0.5 }, 1.0) });
  add("caustic focal point of a ball lens", MakeMedium({ n, n, n }, { h, h, h }, sphere(1.5, h)),
    { Light(false, { centre[0], centre[1], -3 }, centre, 1.0) });
  add("g = 0.999", MakeMedium({ n, n, n }, { h, h, h }, fog(3.0, 0.9, 0.999)), { fromAbove() });
  add("g = -0.999", MakeMedium({ n, n, n }, { h, h, h }, fog(3.0, 0.9, -0.999)), { fromAbove() });
  add("1x1x1 grid", MakeMedium({ 1, 1, 1 }, { 0.5, 0.5, 0.5 }, fog(2.0, 0.8, 0.3)),
    { Light(false, { 0, 3, 0 }, { 0, 0, 0 }, 1.0) });
  cases.back().Camera = Camera({ 0, 0, 3 }, { 0, 0, 0 });
  add("1x1x512 grid",
    MakeMedium({ 1, 1, 512 }, { 0.01, 0.01, 0.01 },
      [](double, double, double z)
      {
        Voxel v;
        v.SigmaT = 3.0;
        v.Albedo = 0.9;
        v.N = 1.0 + 0.3 * z;
        return v;
      }),
    { Light(false, { 0, 0, -3 }, { 0, 0, 1 }, 1.0) });
  cases.back().Camera = Camera({ 3, 0, 2.5 }, { 0, 0, 2.5 });
  add("strongly anisotropic spacing",
    MakeMedium({ 8, 8, 8 }, { 1.0, 0.01, 10.0 }, sphere(1.3, 0.02)),
    { Light(false, { 3.5, 3, 35 }, { 3.5, 0, 35 }, 1.0) });
  cases.back().Camera = Camera({ 3.5, 0.035, 150 }, { 3.5, 0.035, 35 });
  add("origin at 1e6", MakeMedium({ n, n, n }, { h, h, h }, sphere(1.5, 2 * h), { 1e6, 1e6, 1e6 }),
    { Light(false, { 1e6 + 0.5, 1e6 + 3, 1e6 + 0.5 }, { 1e6 + 0.5, 1e6, 1e6 + 0.5 }, 1.0) });
  cases.back().Camera =
    Camera({ 1e6 + 0.47, 1e6 + 0.47, 1e6 + 3 }, { 1e6 + 0.47, 1e6 + 0.47, 1e6 + 0.47 });
  add("light inside the medium", MakeMedium({ n, n, n }, { h, h, h }, fog(2.0, 0.8, 0.0)),
    { Light(true, centre, { 1, centre[1], centre[2] }, 1.0) });
  add("zero-intensity light", MakeMedium({ n, n, n }, { h, h, h }, fog(2.0, 0.8, 0.0)),
    { Light(false, { 0.5, 3, 0.5 }, centre, 0.0) })
    .NoLightPower = true;
  add("all vacuum", MakeMedium({ n, n, n }, { h, h, h }, fog(0.0, 0.0, 0.0)), { fromAbove() })
    .NothingInteracts = true;
  AddViewpointCases(cases, n);
  AddLightPlacementCases(cases);
  AddExtremeValueCases(cases);
  AddSurfaceCases(cases, n);
  return cases;
}
}
