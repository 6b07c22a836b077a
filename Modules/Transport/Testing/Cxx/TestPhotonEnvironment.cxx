// Environment light of the photon pass (vtkPhotonTracer::BackgroundIlluminates): a uniform sky of
// radiance L lights each side of an unoccluded black plane with E = pi L; an upper-hemisphere sky
// lights the upper side only (E = pi L there, 0 below); one bright texel of an equirectangular map
// gives the directional answer E = L x integral over the texel of cos(theta) d omega; the books
// (with the environment's emitted power) close; bad maps are reported.
#include "PhotonTestUtilities.h"

#include "vtkExecutive.h"
#include "vtkPhotonTracer.h"
#include "vtkPlaneSource.h"
#include "vtkRefractaSurfaceMaterial.h"
#include "vtkRefractaSurfaceSet.h"
#include "vtkTestErrorObserver.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <vector>

namespace
{
constexpr double Pi = 3.14159265358979323846;

// A black horizontal (normal +y, the default environment Up) square plane of side `size` at
// height y = 0, centred on the y axis.
vtkSmartPointer<vtkRefractaSurfaceSet> BlackFloor(double size)
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-size / 2, 0, -size / 2);
  plane->SetPoint1(size / 2, 0, -size / 2);
  plane->SetPoint2(-size / 2, 0, size / 2);
  plane->Update();
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->DeepCopy(plane->GetOutput());
  vtkNew<vtkRefractaSurfaceMaterial> black;
  black->SetAlbedo(0, 0, 0);
  auto set = vtkSmartPointer<vtkRefractaSurfaceSet>::New();
  set->AddSurface(mesh, black);
  return set;
}

// A linear-radiance equirectangular map, W x H, all black but for texel (i, j) = rgb.
vtkSmartPointer<vtkImageData> Map(int width, int height)
{
  auto map = vtkSmartPointer<vtkImageData>::New();
  map->SetDimensions(width, height, 1);
  map->AllocateScalars(VTK_FLOAT, 3);
  float* p = static_cast<float*>(map->GetScalarPointer());
  std::fill(p, p + 3 * width * height, 0.0f);
  return map;
}

void SetTexel(vtkImageData* map, int i, int j, const double rgb[3])
{
  for (int c = 0; c < 3; ++c)
  {
    map->GetPointData()->GetScalars()->SetComponent(i + map->GetDimensions()[0] * j, c, rgb[c]);
  }
}

// A small vacuum medium above the plane, inside its bounds.
vtkSmartPointer<vtkImageData> Vacuum()
{
  auto medium = photontest::MakeMedium(
    8, 8, 8, 0.25, [](double, double, double) { return photontest::Voxel{}; });
  medium->SetOrigin(-0.875, 0.25, -0.875);
  return medium;
}

// The floor's sides: its winding normal points down (-y), so the sky above lights its back.
constexpr int Upper = vtkRefractaLightingVolume::BACK_SIDE;
constexpr int Lower = vtkRefractaLightingVolume::FRONT_SIDE;

// The area-weighted mean irradiance (RGB) over the whole atlas on one side.
std::array<double, 3> MeanIrradiance(vtkRefractaSurfaceSet* set, vtkImageData* out, int side)
{
  std::array<double, 3> mean = { 0, 0, 0 };
  vtkDataArray* e =
    out->GetFieldData()->GetArray(vtkRefractaLightingVolume::SurfaceIrradianceName());
  EXPECT_NE(e, nullptr);
  if (!e)
  {
    return mean;
  }
  double area = 0;
  for (vtkIdType t = 0; t < e->GetNumberOfTuples(); ++t)
  {
    const double a = set->GetTexelAreas()[t];
    area += a;
    for (int c = 0; c < 3; ++c)
    {
      mean[c] += a * photontest::SideIrradiance(e, t, side, c);
    }
  }
  for (int c = 0; c < 3; ++c)
  {
    mean[c] /= area;
  }
  return mean;
}

void ExpectBooksClose(vtkImageData* out, double tolerance)
{
  using photontest::Energy;
  const auto emitted = Energy(out, "EnergyEmitted");
  const auto absorbed = Energy(out, "EnergyAbsorbed");
  const auto surface = Energy(out, "EnergySurface");
  const auto escaped = Energy(out, "EnergyEscaped");
  const auto scattered = Energy(out, "EnergyScattered");
  const auto remaining = Energy(out, "EnergyRemaining");
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_GT(emitted[c], 0) << "channel " << c;
    const double sum = absorbed[c] + surface[c] + escaped[c] + scattered[c] + remaining[c];
    EXPECT_NEAR(sum, emitted[c], tolerance * emitted[c]) << "channel " << c;
  }
}

vtkSmartPointer<vtkPhotonTracer> SkyTracer(vtkRefractaSurfaceSet* set, int photons)
{
  auto tracer = vtkSmartPointer<vtkPhotonTracer>::New();
  tracer->SetInputData(Vacuum());
  tracer->SetSurfaces(set);
  tracer->SetNumberOfPhotons(photons);
  tracer->BackgroundIlluminatesOn();
  return tracer;
}
}

TEST(PhotonEnvironment, UniformSkyLightsEachSideWithPiL)
{
  // 2^19 photons from a uniform sky L = (1, 0.5, 0.25) onto a 4 x 4 black plane: each side sees
  // the whole hemisphere, E = pi L on each side of the atlas.
  auto set = BlackFloor(4.0);
  auto tracer = SkyTracer(set, 1 << 19);
  const double L[3] = { 1.0, 0.5, 0.25 };
  tracer->SetBackgroundColor(L[0], L[1], L[2]);
  tracer->Update();
  vtkImageData* out = tracer->GetOutput();
  ASSERT_TRUE(tracer->GetUsedEnvironment());
  EXPECT_EQ(tracer->GetEnvironmentPhotons(), 1 << 19);
  ExpectBooksClose(out, 1e-4);
  double both = 0;
  for (int side : { Upper, Lower })
  {
    const auto E = MeanIrradiance(set, out, side);
    std::cout << "uniform sky, " << (side == Upper ? "upper" : "lower")
              << " side: E / (pi L) = " << E[0] / (Pi * L[0]) << ", " << E[1] / (Pi * L[1]) << ", "
              << E[2] / (Pi * L[2]) << "\n";
    for (int c = 0; c < 3; ++c)
    {
      EXPECT_NEAR(E[c], Pi * L[c], 0.02 * Pi * L[c]) << "channel " << c << " side " << side;
    }
    both += E[0];
  }
  // The plane absorbs it all: surface energy = E x area on both sides.
  EXPECT_NEAR(photontest::Energy(out, "EnergySurface")[0], both * 16.0, 1e-3 * both * 16.0);
  // Off: the sky does not light the scene (no lights either: darkness).
  tracer->BackgroundIlluminatesOff();
  tracer->Update();
  EXPECT_FALSE(tracer->GetUsedEnvironment());
}

TEST(PhotonEnvironment, UpperHemisphereSkyGivesPiLOnTheUpperSide)
{
  // A 1 x 2 map: the lower row (v in [0, 0.5], below the horizon) black, the upper row L: the
  // plane's upper side gets pi L, its lower side nothing.
  auto set = BlackFloor(4.0);
  auto tracer = SkyTracer(set, 1 << 19);
  auto map = Map(1, 2);
  const double L[3] = { 0.3, 0.6, 0.9 };
  SetTexel(map, 0, 1, L);
  tracer->SetEnvironmentMap(map);
  tracer->Update();
  vtkImageData* out = tracer->GetOutput();
  ASSERT_TRUE(tracer->GetUsedEnvironment());
  ExpectBooksClose(out, 1e-4);
  const auto E = MeanIrradiance(set, out, Upper);
  std::cout << "upper hemisphere: E / (pi L) = " << E[0] / (Pi * L[0]) << ", " << E[1] / (Pi * L[1])
            << ", " << E[2] / (Pi * L[2]) << "\n";
  const auto dark = MeanIrradiance(set, out, Lower);
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_NEAR(E[c], Pi * L[c], 0.02 * Pi * L[c]) << "channel " << c;
    EXPECT_EQ(dark[c], 0.0) << "channel " << c << ": no light comes from below";
  }
}

TEST(PhotonEnvironment, OneBrightTexelIsADirectionalLight)
{
  // A 16 x 8 map, black but for texel (5, 6): latitudes 45 to 67.5 degrees, azimuth 1/16 of the
  // circle. E = L x integral of cos(theta) d omega over it = L (2 pi / W) (sin^2 lat1 -
  // sin^2 lat0) / 2, for every point of the unoccluded plane.
  auto set = BlackFloor(4.0);
  auto tracer = SkyTracer(set, 1 << 18);
  const int w = 16, h = 8;
  auto map = Map(w, h);
  const double L[3] = { 50.0, 40.0, 30.0 };
  SetTexel(map, 5, 6, L);
  tracer->SetEnvironmentMap(map);
  tracer->Update();
  vtkImageData* out = tracer->GetOutput();
  ASSERT_TRUE(tracer->GetUsedEnvironment());
  ExpectBooksClose(out, 1e-4);
  const double lat0 = Pi * (6.0 / h - 0.5), lat1 = Pi * (7.0 / h - 0.5);
  const double cosineSolidAngle =
    2 * Pi / w * 0.5 * (std::sin(lat1) * std::sin(lat1) - std::sin(lat0) * std::sin(lat0));
  const auto E = MeanIrradiance(set, out, Upper);
  std::cout << "bright texel: E / (L x cos-weighted solid angle) = "
            << E[0] / (L[0] * cosineSolidAngle) << "\n";
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_NEAR(E[c], L[c] * cosineSolidAngle, 0.02 * L[c] * cosineSolidAngle) << "channel " << c;
  }
  EXPECT_EQ(MeanIrradiance(set, out, Lower)[0], 0.0);
  // The same texel below the horizon (row 1) lights the lower side with the same irradiance.
  const double black[3] = { 0, 0, 0 };
  SetTexel(map, 5, 6, black);
  SetTexel(map, 5, 1, L);
  map->Modified();
  tracer->Update();
  const auto below = MeanIrradiance(set, tracer->GetOutput(), Lower);
  std::cout << "bright texel below: " << below[0] / (L[0] * cosineSolidAngle) << "\n";
  EXPECT_NEAR(below[0], L[0] * cosineSolidAngle, 0.02 * L[0] * cosineSolidAngle);
  EXPECT_EQ(MeanIrradiance(set, tracer->GetOutput(), Upper)[0], 0.0);
}

TEST(PhotonEnvironment, BadEnvironmentIsReported)
{
  auto set = BlackFloor(4.0);
  auto tracer = SkyTracer(set, 1 << 12);
  vtkNew<vtkTest::ErrorObserver> observer;
  tracer->AddObserver(vtkCommand::ErrorEvent, observer);
  tracer->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, observer);
  // A negative sky.
  tracer->SetBackgroundColor(1, -1, 0);
  tracer->Update();
  EXPECT_TRUE(observer->GetError());
  EXPECT_NE(observer->GetErrorMessage().find("BackgroundColor"), std::string::npos);
  EXPECT_EQ(tracer->GetOutput()->GetNumberOfPoints(), 0);
  observer->Clear();
  // A map with 5 components (1 to 4, grey to RGBA, are maps).
  vtkNew<vtkImageData> fiveComponents;
  fiveComponents->SetDimensions(4, 2, 1);
  fiveComponents->AllocateScalars(VTK_FLOAT, 5);
  tracer->SetEnvironmentMap(fiveComponents);
  tracer->Update();
  EXPECT_TRUE(observer->GetError());
  EXPECT_NE(observer->GetErrorMessage().find("EnvironmentMap"), std::string::npos);
  EXPECT_EQ(tracer->GetOutput()->GetNumberOfPoints(), 0);
  observer->Clear();
  // A NaN texel.
  auto map = Map(4, 2);
  const double nan[3] = { std::nan(""), 0, 0 };
  SetTexel(map, 1, 1, nan);
  tracer->SetEnvironmentMap(map);
  tracer->Update();
  EXPECT_TRUE(observer->GetError());
  EXPECT_NE(observer->GetErrorMessage().find("texel 5"), std::string::npos);
  observer->Clear();
  // Up parallel to Right.
  tracer->SetEnvironmentMap(nullptr);
  tracer->SetBackgroundColor(1, 1, 1);
  tracer->SetEnvironmentUp(1, 0, 0);
  tracer->Update();
  EXPECT_TRUE(observer->GetError());
  EXPECT_NE(observer->GetErrorMessage().find("EnvironmentUp"), std::string::npos);
}
