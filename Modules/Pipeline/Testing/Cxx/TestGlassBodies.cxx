// Glass bodies (Documentation/Physics.md "Glass bodies"): the medium inside a mesh voxelized with
// exact interfaces is recorded per interface triangle (vtkRefractaMedium::InterfaceMaterialsName)
// and the photon pass uses it, not the grid, while a photon is inside.
// - The voxelizer records each mesh's own material (a density-scaled one: flagged "use the grid");
//   AddMediumInterfaces turns it into the surfaces' inside medium; bad arrays are errors naming it.
// - A clear glass ball in fog: the grid mixes the fog into the voxels the surface cuts; without the
//   record photons scatter in that shell inside the glass and circle there by total internal
//   reflection. With it nothing is scattered in the ball's interior and no photon is trapped.
// - A milky (absorbing or scattering) ball in a vacuum grid: a beam loses exactly the analytic
//   mean of 1 - exp(-sigma_t L) over the ball's chords; a point light at the centre of an
//   absorbing glass ball (which must start inside the body) loses 1 - escaped, escaped the
//   Fresnel series of the radial paths.
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkMediumMaterial.h"
#include "vtkMeshVoxelizer.h"
#include "vtkNew.h"
#include "vtkPhotonTracer.h"
#include "vtkPointData.h"
#include "vtkRefractaLightingVolume.h"
#include "vtkRefractaMedium.h"
#include "vtkRefractaSurfaceMaterial.h"
#include "vtkRefractaSurfaceSet.h"
#include "vtkSmartPointer.h"
#include "vtkSphere.h"
#include "vtkSphereSource.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <iostream>
#include <limits>
#include <string>

namespace
{
const double Pi = 3.14159265358979323846;

vtkSmartPointer<vtkPolyData> Sphere(double radius, int resolution)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(radius);
  sphere->SetThetaResolution(resolution);
  sphere->SetPhiResolution(resolution / 2);
  sphere->Update();
  return sphere->GetOutput();
}

// A ball of `material` (radius r at the origin) in `surrounding`, on n^3 voxels over [-h, h]^3,
// voxelized with exact interfaces (the default; an index-matched ball is no interface).
vtkSmartPointer<vtkImageData> Voxelize(vtkMediumMaterial* material, vtkMediumMaterial* surrounding,
  double r, int n, double h, int resolution = 96)
{
  vtkNew<vtkMeshVoxelizer> voxelizer;
  voxelizer->AddInputData(Sphere(r, resolution));
  voxelizer->SetMaterial(0, material);
  voxelizer->SetSurroundingMaterial(surrounding);
  voxelizer->SetDimensions(n, n, n);
  voxelizer->SetBounds(-h, h, -h, h, -h, h);
  voxelizer->Update();
  EXPECT_EQ(voxelizer->GetWroteInterfaces(),
    material->GetRefractiveIndex() != surrounding->GetRefractiveIndex());
  auto medium = vtkSmartPointer<vtkImageData>::New();
  medium->DeepCopy(voxelizer->GetOutput());
  return medium;
}

vtkSmartPointer<vtkMediumMaterial> Material(double n, double sigma, double albedo, double g = 0)
{
  auto m = vtkSmartPointer<vtkMediumMaterial>::New();
  m->SetRefractiveIndex(n);
  m->SetExtinction(sigma, sigma, sigma);
  m->SetAlbedo(albedo, albedo, albedo);
  m->SetAnisotropy(g);
  return m;
}

double Field(vtkImageData* image, const char* name, int component = 0)
{
  vtkDataArray* a = image->GetFieldData()->GetArray(name);
  return a ? a->GetComponent(0, component) : std::numeric_limits<double>::quiet_NaN();
}

// Every book closes to 1e-6 of the emitted power.
void ExpectExactBooks(vtkImageData* out)
{
  for (int c = 0; c < 3; ++c)
  {
    const double emitted = Field(out, "EnergyEmitted", c);
    const double ended = Field(out, "EnergySurface", c) + Field(out, "EnergyEscaped", c) +
      Field(out, "EnergyAbsorbed", c) + Field(out, "EnergyRemaining", c) +
      Field(out, "EnergyScattered", c) + Field(out, "EnergyRouletteKilled", c) -
      Field(out, "EnergyRouletteGained", c);
    EXPECT_NEAR(ended, emitted, 1e-6 * emitted) << "channel " << c;
  }
}

vtkSmartPointer<vtkLight> Sun(double intensity = 1.0)
{
  auto light = vtkSmartPointer<vtkLight>::New();
  light->SetPositional(false);
  light->SetPosition(0, 3, 0);
  light->SetFocalPoint(0, 0, 0);
  light->SetIntensity(intensity);
  return light;
}

vtkSmartPointer<vtkImageData> Trace(
  vtkImageData* medium, vtkRefractaSurfaceSet* set, vtkLight* light, int photons, bool analog)
{
  vtkNew<vtkPhotonTracer> tracer;
  tracer->SetInputData(medium);
  tracer->SetSurfaces(set);
  tracer->AddLight(light);
  tracer->SetNumberOfPhotons(photons);
  tracer->SetAnalogScattering(analog);
  tracer->SetSeed(5);
  tracer->SetSmoothing(false); // deposits stay in the voxel of their piece
  tracer->Update();
  auto out = vtkSmartPointer<vtkImageData>::New();
  out->ShallowCopy(tracer->GetOutput());
  return out;
}

// Sum (first channel) of the scattered deposits (Radiance and, with analog scattering,
// MultipleScattering) in the voxels whose centre lies within `radius` of the origin, and in all.
std::array<double, 2> ScatteredInside(vtkImageData* out, double radius)
{
  std::array<double, 2> sums{ 0, 0 };
  for (const char* name : { vtkRefractaLightingVolume::RadianceName(),
         vtkRefractaLightingVolume::MultipleScatteringName() })
  {
    vtkDataArray* a = out->GetPointData()->GetArray(name);
    for (vtkIdType p = 0; a && p < out->GetNumberOfPoints(); ++p)
    {
      double x[3];
      out->GetPoint(p, x);
      const double v = a->GetComponent(p, 0);
      sums[1] += v;
      sums[0] += (x[0] * x[0] + x[1] * x[1] + x[2] * x[2] < radius * radius) ? v : 0.0;
    }
  }
  return sums;
}

// The last error message `object` reports while `run` runs.
template <typename Run>
std::string ErrorOf(vtkObject* object, Run run)
{
  std::string message;
  vtkNew<vtkCallbackCommand> onError;
  onError->SetClientData(&message);
  onError->SetCallback([](vtkObject*, unsigned long, void* client, void* call)
    { *static_cast<std::string*>(client) = static_cast<const char*>(call); });
  const unsigned long tag = object->AddObserver(vtkCommand::ErrorEvent, onError);
  run();
  object->RemoveObserver(tag);
  return message;
}
}

TEST(GlassBodies, VoxelizerRecordsTheInsideMedium)
{
  auto milk = Material(1.4, 2.0, 0.7, 0.25);
  milk->SetEmission(0.1, 0.2, 0.3);
  auto medium = Voxelize(milk, Material(1.0, 0.35, 0.9), 0.3, 16, 0.5, 24);
  vtkDataArray* bodies =
    medium->GetFieldData()->GetArray(vtkRefractaMedium::InterfaceMaterialsName());
  ASSERT_NE(bodies, nullptr);
  ASSERT_EQ(bodies->GetNumberOfComponents(), vtkRefractaMedium::InterfaceMaterialComponents);
  ASSERT_EQ(bodies->GetNumberOfTuples(),
    medium->GetFieldData()
      ->GetArray(vtkRefractaMedium::InterfaceTrianglesName())
      ->GetNumberOfTuples());
  const double expected[11] = { 2, 2, 2, 0.7, 0.7, 0.7, 0.25, 0.1, 0.2, 0.3, 1 };
  for (int c = 0; c < 11; ++c)
  {
    EXPECT_DOUBLE_EQ(bodies->GetComponent(0, c), expected[c]) << "component " << c;
  }
  vtkNew<vtkRefractaSurfaceSet> set;
  ASSERT_EQ(set->AddMediumInterfaces(medium), 1);
  vtkRefractaSurfaceMaterial* m = set->GetMaterial(0);
  EXPECT_TRUE(m->GetUseInsideMedium());
  EXPECT_DOUBLE_EQ(m->GetInsideExtinction()[1], 2.0);
  EXPECT_DOUBLE_EQ(m->GetInsideAlbedo()[2], 0.7);
  EXPECT_DOUBLE_EQ(m->GetInsideAnisotropy(), 0.25);
  EXPECT_DOUBLE_EQ(m->GetInsideEmission()[2], 0.3);
  ASSERT_TRUE(set->Build());
  const auto& table = set->GetSurfaceBodies();
  ASSERT_EQ(table.size(), size_t(12));
  EXPECT_FLOAT_EQ(table[0], 2.0f);
  EXPECT_FLOAT_EQ(table[3], 1.0f);
  EXPECT_FLOAT_EQ(table[4], 0.7f);
  EXPECT_FLOAT_EQ(table[7], 0.25f);
  EXPECT_FLOAT_EQ(table[10], 0.3f);

  // A material with a density field is not one medium: flagged 0, the passes use the grid.
  auto cloud = Material(1.2, 2.0, 0.7);
  vtkNew<vtkSphere> density;
  density->SetRadius(1.0);
  cloud->SetDensityFunction(density);
  auto clouded = Voxelize(cloud, Material(1.0, 0.35, 0.9), 0.3, 16, 0.5, 24);
  vtkDataArray* flagged =
    clouded->GetFieldData()->GetArray(vtkRefractaMedium::InterfaceMaterialsName());
  ASSERT_NE(flagged, nullptr);
  EXPECT_EQ(flagged->GetComponent(0, 10), 0.0);
  vtkNew<vtkRefractaSurfaceSet> gridInside;
  ASSERT_EQ(gridInside->AddMediumInterfaces(clouded), 1);
  EXPECT_FALSE(gridInside->GetMaterial(0)->GetUseInsideMedium());
}

TEST(GlassBodies, BadInterfaceMaterialsAreAnErrorThatNamesThem)
{
  auto medium = Voxelize(Material(1.5, 0, 0), Material(1.0, 0.35, 0.9), 0.3, 12, 0.5, 16);
  vtkDataArray* good =
    medium->GetFieldData()->GetArray(vtkRefractaMedium::InterfaceMaterialsName());
  ASSERT_NE(good, nullptr);
  const vtkIdType triangles = good->GetNumberOfTuples();
  auto withArray = [&](int components, vtkIdType tuples, int badComponent, double badValue)
  {
    auto copy = vtkSmartPointer<vtkImageData>::New();
    copy->DeepCopy(medium);
    vtkNew<vtkDoubleArray> a;
    a->SetName(vtkRefractaMedium::InterfaceMaterialsName());
    a->SetNumberOfComponents(components);
    a->SetNumberOfTuples(tuples);
    for (vtkIdType t = 0; t < tuples; ++t)
    {
      for (int c = 0; c < components; ++c)
      {
        a->SetComponent(t, c, c == 10 ? 1.0 : 0.1);
      }
    }
    if (badComponent >= 0)
    {
      a->SetComponent(tuples / 2, badComponent, badValue);
    }
    copy->GetFieldData()->RemoveArray(vtkRefractaMedium::InterfaceMaterialsName());
    copy->GetFieldData()->AddArray(a);
    return copy;
  };
  struct Case
  {
    const char* what;
    int components;
    vtkIdType tuples;
    int component;
    double value;
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Case cases[] = { { "10 components", 10, triangles, -1, 0 },
    { "one tuple short", 11, triangles - 1, -1, 0 }, { "NaN extinction", 11, triangles, 1, nan },
    { "negative extinction", 11, triangles, 0, -1.0 }, { "albedo above 1", 11, triangles, 4, 1.5 },
    { "anisotropy 1", 11, triangles, 6, 1.0 }, { "infinite emission", 11, triangles, 8, INFINITY },
    { "flag 0.5", 11, triangles, 10, 0.5 } };
  for (const Case& c : cases)
  {
    auto bad = withArray(c.components, c.tuples, c.component, c.value);
    vtkNew<vtkRefractaSurfaceSet> set;
    int added = 0;
    const std::string message = ErrorOf(set, [&] { added = set->AddMediumInterfaces(bad); });
    EXPECT_EQ(added, -1) << c.what;
    EXPECT_EQ(set->GetNumberOfSurfaces(), 0) << c.what;
    EXPECT_NE(message.find(vtkRefractaMedium::InterfaceMaterialsName()), std::string::npos)
      << c.what << ": " << message;
    EXPECT_NE(message.find("valid"), std::string::npos) << c.what << ": " << message;
  }
  // The good array itself passes (the cases above fail for their one fault).
  vtkNew<vtkRefractaSurfaceSet> set;
  EXPECT_EQ(set->AddMediumInterfaces(withArray(11, triangles, -1, 0)), 1);
}

TEST(GlassBodies, FogNoLongerLeaksIntoGlass)
{
  // The default scene's ball (n = 1.5, radius 0.42, a little absorption) in its fog (sigma_t
  // 0.35, albedo 0.9, g 0.3), 40^3 voxels over [-0.6, 0.6]^3, photons with analog scattering as
  // the pipeline runs them with surfaces. Once with the voxelizer's record of the glass, once
  // without it (the array removed: the passes as before, the grid inside the glass too).
  const double radius = 0.42, h = 0.6;
  const int n = 40;
  auto fog = Material(1.0, 0.35, 0.9, 0.3);
  auto medium = Voxelize(Material(1.5, 0.02, 0.0), fog, radius, n, h);
  auto old = vtkSmartPointer<vtkImageData>::New();
  old->DeepCopy(medium);
  old->GetFieldData()->RemoveArray(vtkRefractaMedium::InterfaceMaterialsName());
  const double voxel = 2 * h / (n - 1);
  // Deposits go to the voxel of their piece: a voxel whose centre lies more than half its
  // diagonal (0.87 voxel) inside the sphere holds only light scattered inside the glass.
  const double glassOnly = radius - 0.9 * voxel, deep = radius - 1.5 * voxel;

  auto run = [&](vtkImageData* m, const char* label)
  {
    vtkNew<vtkRefractaSurfaceSet> set;
    EXPECT_EQ(set->AddMediumInterfaces(m), 1);
    auto out = Trace(m, set, Sun(20.0), 1 << 16, true);
    ExpectExactBooks(out);
    const auto inside = ScatteredInside(out, glassOnly);
    const auto deeper = ScatteredInside(out, deep);
    const double photons = Field(out, "PhotonsMarched");
    std::cout << label << ": scattered inside the glass (voxels > 0.9 voxel inside) "
              << inside[0] / inside[1] << " of all, deeper than 1.5 voxels "
              << deeper[0] / deeper[1] << "; " << Field(out, "TerminatedStepCap") << " of "
              << photons << " photons ended by the caps, " << Field(out, "TotalSteps") / photons
              << " steps per photon\n";
    return std::array<double, 4>{ inside[0] / inside[1], Field(out, "TerminatedStepCap"),
      Field(out, "TotalSteps"), deeper[0] / deeper[1] };
  };
  const auto before = run(old, "grid inside the glass");
  const auto after = run(medium, "glass body");
  // Without the record a shell of fog about a voxel thick lies inside the glass: light scatters
  // there and (some of it) deeper in the interior; with it the interior is clear glass.
  EXPECT_GT(before[0], 1e-4);
  EXPECT_GT(before[3], 0.0);
  EXPECT_EQ(after[0], 0.0);
  EXPECT_EQ(after[3], 0.0);
  // Trapped light: photons scattered inside the glass circle by total internal reflection
  // until the interface cap ends them; with the body none scatters there.
  EXPECT_GT(before[1], 20.0);
  EXPECT_LE(after[1], 0.05 * before[1]);
  EXPECT_LT(after[2], before[2]);
}

namespace
{
// Mean over a disc of radius R of exp(-sigma 2 sqrt(R^2 - r^2)) (the chords of a ball along one
// direction, weighted by area): (2 / R^2) int_0^R u exp(-2 sigma u) du.
double MeanBallTransmittance(double sigma, double R)
{
  const double a = 2 * sigma;
  return 2.0 / (R * R) * (1 - (1 + a * R) * std::exp(-a * R)) / (a * a);
}

// A vacuum grid over [-h, h]^3 holding a ball (radius R, a fine sphere) as a caller-made
// dielectric surface with inside index `index` and inside medium (sigma, albedo).
struct MilkyBall
{
  vtkSmartPointer<vtkImageData> Medium;
  vtkNew<vtkRefractaSurfaceSet> Set;
  MilkyBall(double R, double h, double index, double sigma, double albedo)
  {
    this->Medium = Voxelize(Material(1.0, 0, 0), Material(1.0, 0, 0), 0.1, 24, h, 16);
    for (const char* name :
      { vtkRefractaMedium::InterfacePointsName(), vtkRefractaMedium::InterfaceTrianglesName(),
        vtkRefractaMedium::InterfaceIndicesName(), vtkRefractaMedium::InterfaceMaterialsName() })
    {
      this->Medium->GetFieldData()->RemoveArray(name);
    }
    vtkNew<vtkRefractaSurfaceMaterial> glass;
    glass->SetKindToDielectric();
    glass->SetIndexInside(index);
    glass->SetIndexOutside(1.0);
    glass->SetUseInsideMedium(true);
    glass->SetInsideExtinction(sigma, sigma, sigma);
    glass->SetInsideAlbedo(albedo, albedo, albedo);
    this->Set->AddSurface(Sphere(R, 256), glass);
  }
};
}

TEST(GlassBodies, MilkyBallAttenuatesWithItsOwnExtinction)
{
  // A beam from +y over the whole box; the grid is vacuum, so everything lost is lost in the
  // body: the emitted power times (ball's cross-section / box face) times the mean of
  // 1 - exp(-sigma L) over the ball's chords (index 1 inside: straight chords, no reflection).
  const double R = 0.4, h = 0.5, sigma = 3.0;
  // Irradiance 1: the beam carries pi R^2 onto the ball.
  const double expected = Pi * R * R * (1 - MeanBallTransmittance(sigma, R));
  for (double albedo : { 0.0, 1.0 })
  {
    MilkyBall ball(R, h, 1.0, sigma, albedo);
    auto out = Trace(ball.Medium, ball.Set, Sun(), 1 << 17, false);
    ExpectExactBooks(out);
    const double lost = Field(out, "EnergyAbsorbed") + Field(out, "EnergyScattered");
    std::cout << "albedo " << albedo << ": lost " << lost << ", expected " << expected << "\n";
    // The 256 x 128 sphere's cross-section is 0.02% short of the disc's; the lattice of
    // photon starts is low-discrepancy: 0.3%.
    EXPECT_NEAR(lost, expected, 0.003 * expected);
    EXPECT_NEAR(Field(out, "EnergyScattered"), albedo * expected, 0.003 * expected);
    // Scattered deposits lie in the voxels of the pieces inside the ball: centres within
    // half a voxel diagonal (0.87 voxel) of it.
    const auto inside = ScatteredInside(out, R + 0.9 * (2 * h / 23));
    EXPECT_NEAR(inside[0], inside[1], 1e-9 * std::max(inside[1], 1.0));
    if (albedo > 0)
    {
      EXPECT_GT(inside[1], 0.0);
    }
  }
}

TEST(GlassBodies, PointLightInsideAGlassBodyStartsInIt)
{
  // A point light at the centre of an absorbing glass ball (n = 1.5, sigma 2, radius 0.4):
  // every path is radial, meets the surface at normal incidence (Fresnel F = 0.04) and crosses
  // R, then 2R after each reflection. Escaped: (1 - F) e^{-sigma R} / (1 - F e^{-2 sigma R}).
  // A photon that did not know it starts inside the body would cross the vacuum grid unharmed.
  const double R = 0.4, h = 0.5, sigma = 2.0, index = 1.5;
  MilkyBall ball(R, h, index, sigma, 0.0);
  vtkNew<vtkLight> bulb;
  bulb->SetPositional(true);
  bulb->SetPosition(0.013, -0.007, 0.011); // off the grid's planes of symmetry
  bulb->SetFocalPoint(0, -1, 0);
  bulb->SetConeAngle(180);
  bulb->SetIntensity(1.0);
  auto out = Trace(ball.Medium, ball.Set, bulb, 1 << 16, false);
  ExpectExactBooks(out);
  const double F = std::pow((index - 1) / (index + 1), 2);
  const double escaped = (1 - F) * std::exp(-sigma * R) / (1 - F * std::exp(-2 * sigma * R));
  const double emitted = Field(out, "EnergyEmitted");
  const double absorbed = Field(out, "EnergyAbsorbed") / emitted;
  std::cout << "light at the centre: absorbed " << absorbed << ", expected " << 1 - escaped << "\n";
  // The light sits 0.02 R off the centre: path lengths change by < 0.02 R at first order, which
  // averages out over the sphere; Fresnel sampling noise sqrt(F / N) on the 4% reflected.
  EXPECT_NEAR(absorbed, 1 - escaped, 0.004);
}
