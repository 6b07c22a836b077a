// vtkLightRaySingleScattering: light rays against analytic single scattering, the gradient-based
// interpolation (Ren et al. 2008) against light rays, photons converging to light rays, dynamic
// sampling at density edges, surface shadows and bad input.
#include "PhotonTestUtilities.h"
#include "vtkCommand.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkIntArray.h"
#include "vtkLightRaySingleScattering.h"
#include "vtkMath.h"
#include "vtkPhotonTracer.h"
#include "vtkPlaneSource.h"
#include "vtkPolyData.h"
#include "vtkRefractaSurfaceMaterial.h"
#include "vtkRefractaSurfaceSet.h"
#include "vtkStringArray.h"
#include "vtkTestErrorObserver.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

using namespace photontest;

namespace
{
Voxel Homogeneous(double sigma, double albedo)
{
  Voxel v;
  v.Extinction = { sigma, sigma, sigma };
  v.Albedo = { albedo, albedo, albedo };
  return v;
}

// A heterogeneous cloud on n^3 voxels of unit spacing: a few Gaussian blobs, cut off sharply
// where their sum falls below 0.25 (hardEdge) or smooth everywhere.
vtkSmartPointer<vtkImageData> Cloud(int n, bool hardEdge = true)
{
  const double c = 0.5 * (n - 1);
  const double blobs[4][4] = { { 0.0, 0.0, 0.0, 0.30 }, { 0.2, 0.1, -0.1, 0.18 },
    { -0.2, -0.15, 0.1, 0.15 }, { 0.05, -0.2, -0.2, 0.12 } };
  return MakeMedium(
    n, n, n, 1.0,
    [&](double x, double y, double z)
    {
      double density = 0;
      for (const auto& b : blobs)
      {
        const double dx = x - c - b[0] * n, dy = y - c - b[1] * n, dz = z - c - b[2] * n;
        const double r = b[3] * n;
        density += std::exp(-(dx * dx + dy * dy + dz * dz) / (r * r));
      }
      if (hardEdge)
      {
        density = density > 0.25 ? density : 0.0;
      }
      return Homogeneous(0.12 * density, 0.9);
    },
    false);
}

// Lights around a cube of side n centred at c: count point lights on a sphere (and one
// directional light), total intensity fixed so the cases compare.
std::vector<vtkSmartPointer<vtkLight>> LightsAround(int n, int count)
{
  std::vector<vtkSmartPointer<vtkLight>> lights;
  const double c = 0.5 * (n - 1);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  for (int l = 0; l < count; ++l)
  {
    const double z = 2.0 * uniform(random) - 1.0, phi = 2.0 * vtkMath::Pi() * uniform(random);
    const double s = std::sqrt(1.0 - z * z), r = 0.9 * n;
    const std::array<double, 3> at = { c + r * s * std::cos(phi), c + r * s * std::sin(phi),
      c + r * z };
    lights.push_back(Positional(at, { c, c, c }, 180.0, 0.0, 1000.0 / count));
  }
  return lights;
}

double RelativeRms(const float* a, const float* b, size_t values)
{
  double diff = 0, ref = 0;
  for (size_t i = 0; i < values; ++i)
  {
    diff += (a[i] - b[i]) * double(a[i] - b[i]);
    ref += double(b[i]) * b[i];
  }
  return std::sqrt(diff / std::max(ref, 1e-300));
}

// A set holding one black plane (vtkPlaneSource: origin, point 1, point 2).
vtkSmartPointer<vtkRefractaSurfaceSet> BlackPlane(
  std::array<double, 3> origin, std::array<double, 3> p1, std::array<double, 3> p2)
{
  vtkNew<vtkRefractaSurfaceMaterial> black;
  black->SetAlbedo(0, 0, 0);
  auto set = vtkSmartPointer<vtkRefractaSurfaceSet>::New();
  set->AddSurface(Rectangle(origin, p1, p2), black);
  return set;
}

vtkSmartPointer<vtkImageData> RunPass(vtkLightRaySingleScattering* pass, vtkImageData* medium)
{
  pass->SetInputData(medium);
  pass->Update();
  auto out = vtkSmartPointer<vtkImageData>::New();
  out->DeepCopy(pass->GetOutput());
  return out;
}
}

// A light travelling all but parallel to the voxels' node planes (a component of 1e-16 to 1e-5
// along x, as a frame turned by 90 degrees gives) lights a ball as one exactly parallel to
// them. Rays from the voxels' centres then run along a node plane; their march took the cell
// behind the plane, whose exit was the plane itself, and stopped at its step cap: the fluence up
// to 4x too high (session 31).
TEST(LightRays, RaysAlongANodePlaneAreNotCutShort)
{
  // A ball of optical diameter 6 (radius 8.4 voxels, soft edge) on 24^3 voxels of unit spacing.
  const int n = 24;
  const double c = 0.5 * (n - 1), sy = std::sin(0.6), cz = std::cos(0.6);
  auto medium = MakeMedium(n, n, n, 1.0,
    [&](double x, double y, double z)
    {
      const double r = std::sqrt((x - c) * (x - c) + (y - c) * (y - c) + (z - c) * (z - c));
      return Homogeneous(0.357 * std::min(1.0, std::max(0.0, (8.4 - r) / 1.2)), 0.99);
    });
  auto lit = [&](double ex)
  {
    vtkNew<vtkLightRaySingleScattering> pass;
    pass->AddLight(Directional({ c - 30 * ex, c + 30 * sy, c - 30 * cz }, { c, c, c }, 2.0));
    return RunPass(pass, medium);
  };
  auto parallel = lit(0.0);
  const size_t values = 3 * static_cast<size_t>(n) * n * n;
  for (const double ex : { 1e-16, -1e-16, 1e-9, 1e-6, -1e-5 })
  {
    auto tilted = lit(ex);
    EXPECT_LT(RelativeRms(Radiance(tilted), Radiance(parallel), values), 1e-4) << "x " << ex;
  }
}

// A homogeneous slab (the whole grid) under a directional light along +z:
// S1(z) = sigma_s E exp(-sigma_t (z - z_entry)), z_entry the face of the box.
TEST(LightRays, SlabUnderDirectionalLightIsAnalytic)
{
  const double sigma = 0.15, albedo = 0.7, e = 3.0;
  auto medium =
    MakeMedium(8, 8, 40, 0.5, [&](double, double, double) { return Homogeneous(sigma, albedo); });
  vtkNew<vtkLightRaySingleScattering> pass;
  pass->AddLight(Directional({ 2, 2, -10 }, { 2, 2, 0 }, e));
  auto out = RunPass(pass, medium);
  const float* s = Radiance(out);
  const float* d = Direction(out);
  double worst = 0;
  for (int k = 0; k < 40; ++k)
  {
    const size_t v = 3 + 8 * (4 + 8 * static_cast<size_t>(k));
    const double z = 0.5 * k, entry = -0.25;
    const double expected = sigma * albedo * e * std::exp(-sigma * (z - entry));
    worst = std::max(worst, std::fabs(s[3 * v] / expected - 1.0));
    EXPECT_NEAR(d[3 * v + 2], 1.0, 1e-5);
  }
  EXPECT_LT(worst, 0.005) << "largest relative error of the slab";
  EXPECT_EQ(
    out->GetFieldData()->GetAbstractArray("SingleScatteringMethod")->GetVariantValue(0).ToString(),
    "light_rays");
}

// A dense slab's face under a directional light along +z (sigma_t = S from the centre plane
// z = 6 on, 0 below; unit spacing): the trilinear medium ramps from 0 to S between the centres
// z = 5 and z = 6, where most of the light scatters when S is large. The two voxels whose box
// holds the ramp (k = 5, 6) get the box mean (1 / h) integral over the box of
// a sigma(z) E exp(-tau(z)) dz, tau(z) = S (z - 5)^2 / 2 in the ramp and S / 2 + S (z - 6) past it
// (integrated here in double), to float precision (light along an axis: the lines' rule is
// exact); the voxels beyond keep their centre values. Without the box means the empty voxel
// k = 5 holds nothing and the face voxel the light at its centre: at S = 10 that is 6.7% of what
// the two voxels' boxes scatter.
TEST(LightRays, BoxMeansAtADenseFaceMatchTheTrilinearMedium)
{
  const double albedo = 0.8, e = 2.0;
  for (double S : { 2.0, 10.0 })
  {
    auto medium = MakeMedium(4, 4, 12, 1.0,
      [&](double, double, double z) { return Homogeneous(z >= 6 ? S : 0.0, albedo); });
    auto sigmaAt = [&](double z) { return z <= 5 ? 0.0 : (z >= 6 ? S : S * (z - 5)); };
    auto tauAt = [&](double z)
    { return z <= 5 ? 0.0 : (z >= 6 ? S / 2 + S * (z - 6) : S * (z - 5) * (z - 5) / 2); };
    auto boxMean = [&](int k)
    {
      const int steps = 200000;
      double sum = 0;
      for (int i = 0; i < steps; ++i)
      {
        const double z = k - 0.5 + (i + 0.5) / steps;
        sum += albedo * sigmaAt(z) * e * std::exp(-tauAt(z));
      }
      return sum / steps;
    };
    for (bool boxMeans : { true, false })
    {
      vtkNew<vtkLightRaySingleScattering> pass;
      pass->AddLight(Directional({ 1.5, 1.5, -10 }, { 1.5, 1.5, 0 }, e));
      pass->SetSharpVoxelBoxMeans(boxMeans);
      auto out = RunPass(pass, medium);
      const float* s1 = Radiance(out);
      const size_t column = 1 + 4 * 2; // (i, j) = (1, 2)
      const double centre7 = albedo * S * e * std::exp(-tauAt(7));
      const double at5 = s1[3 * (column + 16 * 5)], at6 = s1[3 * (column + 16 * 6)];
      const double at7 = s1[3 * (column + 16 * 7)];
      std::cout << "S " << S << (boxMeans ? ", box means: " : ", centres: ") << at5 << " " << at6
                << " " << at7 << " (box means " << boxMean(5) << " " << boxMean(6) << ")\n";
      EXPECT_NEAR(at7 / centre7, 1.0, 1e-4) << "beyond the face: the centre value";
      if (boxMeans)
      {
        // The layers k = 5 and 6, and the dense voxels on the grid's faces (k = 7..10: 12 per
        // layer; k = 11: all 16), which reach a face with no medium beyond.
        EXPECT_EQ(pass->GetNumberOfBoxMeanVoxels(), 16 + 16 + 4 * 12 + 16);
        EXPECT_NEAR(at5 / boxMean(5), 1.0, 1e-3);
        EXPECT_NEAR(at6 / boxMean(6), 1.0, 1e-3);
        EXPECT_NEAR(Direction(out)[3 * (column + 16 * 5) + 2], 1.0, 1e-5);
      }
      else
      {
        EXPECT_EQ(pass->GetNumberOfBoxMeanVoxels(), 0);
        EXPECT_EQ(at5, 0.0);
        EXPECT_NEAR(at6 / (albedo * S * e * std::exp(-S / 2)), 1.0, 1e-4);
      }
    }
  }
}

// A black wall two voxels in front of a dense face (sigma_t 2 from z = 6 on, light along +z, the
// wall at z = 3.5 over x < 6): the face's sharp voxels behind the wall get no light, those beside
// it their box means, although the plane their lines start from (4 voxels upstream) lies in
// front of the wall.
TEST(LightRays, BoxMeansBehindAWallAreDark)
{
  auto medium = MakeMedium(
    12, 4, 12, 1.0, [&](double, double, double z) { return Homogeneous(z >= 6 ? 2.0 : 0.0, 0.8); });
  auto set = BlackPlane({ -2, -2, 3.5 }, { 5.5, -2, 3.5 }, { -2, 6, 3.5 });
  vtkNew<vtkLightRaySingleScattering> pass;
  pass->AddLight(Directional({ 5.5, 1.5, -10 }, { 5.5, 1.5, 0 }, 1.0));
  pass->SetSurfaces(set);
  auto out = RunPass(pass, medium);
  const float* s1 = Radiance(out);
  for (int k : { 5, 6 })
  {
    const size_t shaded = 2 + 12 * (1 + 4 * static_cast<size_t>(k));
    const size_t lit = 9 + 12 * (1 + 4 * static_cast<size_t>(k));
    EXPECT_EQ(s1[3 * shaded], 0.0f) << "voxel (2, 1, " << k << ") lies behind the wall";
    EXPECT_GT(s1[3 * lit], 0.1f) << "voxel (9, 1, " << k << ") is lit";
  }
  EXPECT_GT(pass->GetNumberOfBoxMeanVoxels(), 0);
}

// A point light at the centre of a homogeneous sphere: S1(d) = sigma_s I exp(-sigma_t d) / d^2,
// and the direction points away from the light.
TEST(LightRays, PointLightInHomogeneousSphereIsAnalytic)
{
  const int n = 33;
  const double c = 16.0, radius = 14.0, sigma = 0.2, albedo = 0.8, intensity = 50.0;
  auto medium = MakeMedium(n, n, n, 1.0,
    [&](double x, double y, double z)
    {
      const double r = std::sqrt((x - c) * (x - c) + (y - c) * (y - c) + (z - c) * (z - c));
      return r <= radius ? Homogeneous(sigma, albedo) : Voxel{};
    });
  vtkNew<vtkLightRaySingleScattering> pass;
  pass->AddLight(Positional({ c, c, c }, { c, c, c + 1 }, 180.0, 0.0, intensity));
  auto out = RunPass(pass, medium);
  const float* s = Radiance(out);
  const float* dir = Direction(out);
  double worst = 0;
  int compared = 0;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
      {
        const double r[3] = { i - c, j - c, k - c };
        const double d = std::sqrt(vtkMath::Dot(r, r));
        const size_t v = i + n * (j + static_cast<size_t>(n) * k);
        if (d > radius)
        {
          EXPECT_EQ(s[3 * v], 0.0f);
          continue;
        }
        if (d < 2.0 || d > radius - 2.0)
        {
          continue;
        }
        const double expected = sigma * albedo * intensity * std::exp(-sigma * d) / (d * d);
        worst = std::max(worst, std::fabs(s[3 * v] / expected - 1.0));
        EXPECT_NEAR(vtkMath::Dot(r,
                      std::array<double, 3>{ dir[3 * v], dir[3 * v + 1], dir[3 * v + 2] }.data()) /
            d,
          1.0, 1e-4);
        ++compared;
      }
  EXPECT_GT(compared, 5000);
  EXPECT_LT(worst, 0.005) << "largest relative error in the sphere";
}

// A spot light's cone and a sphere light's soft edge: the spot lights only inside its cone; a
// sphere light far away gives the point light's answer.
TEST(LightRays, SpotConeAndExtendedLights)
{
  const double sigma = 0.05;
  auto medium =
    MakeMedium(21, 21, 21, 1.0, [&](double, double, double) { return Homogeneous(sigma, 1.0); });
  vtkNew<vtkLightRaySingleScattering> spot;
  spot->AddLight(Positional({ 10, 10, -20 }, { 10, 10, 0 }, 10.0, 2.0, 100.0));
  auto out = RunPass(spot, medium);
  const float* s = Radiance(out);
  for (int i = 0; i < 21; ++i)
  {
    const size_t v = i + 21 * (10 + 21 * static_cast<size_t>(10));
    const double r[3] = { i - 10.0, 0.0, 30.0 };
    const double c = r[2] / std::sqrt(vtkMath::Dot(r, r));
    const double inside = c >= std::cos(vtkMath::RadiansFromDegrees(10.0));
    const double d2 = vtkMath::Dot(r, r);
    const double expected =
      inside ? sigma * 100.0 * c * c * std::exp(-sigma * (std::sqrt(d2) * (10.5 / 30.0))) / d2 : 0;
    EXPECT_NEAR(s[3 * v], expected, 0.005 * sigma * 100.0 / 900.0) << "voxel " << i;
  }
  // Sphere light of radius 2 at 40 voxels: within 0.2% of the point light (the cap is tiny).
  vtkNew<vtkLightRaySingleScattering> point, sphere;
  point->AddLight(Positional({ 10, 10, -30 }, { 10, 10, 0 }, 180.0, 0.0, 100.0));
  sphere->AddLight(Positional({ 10, 10, -30 }, { 10, 10, 0 }, 180.0, 0.0, 100.0));
  sphere->SetLightRadius(2.0);
  auto a = RunPass(point, medium);
  auto b = RunPass(sphere, medium);
  EXPECT_LT(RelativeRms(Radiance(b), Radiance(a), 3 * 21 * 21 * 21), 0.002);
  // A directional disc of 5 degrees: fluence E 2 / (1 + cos delta) in vacuum-like thin media.
  vtkNew<vtkLightRaySingleScattering> disc;
  disc->AddLight(Directional({ 10, 10, -30 }, { 10, 10, 0 }, 1.0));
  disc->SetDirectionalLightAngularRadius(5.0);
  auto thin =
    MakeMedium(4, 4, 4, 1.0, [&](double, double, double) { return Homogeneous(1e-6, 1.0); });
  auto c = RunPass(disc, thin);
  const double delta = vtkMath::RadiansFromDegrees(5.0);
  EXPECT_NEAR(Radiance(c)[0] / 1e-6, 2.0 / (1.0 + std::cos(delta)), 1e-4);
}

// A black square between a directional light and the medium shadows exactly its footprint.
TEST(LightRays, SurfacesCastShadows)
{
  auto medium =
    MakeMedium(20, 20, 10, 1.0, [&](double, double, double) { return Homogeneous(0.05, 1.0); });
  auto set = BlackPlane({ -1, -1, -3 }, { 9.5, -1, -3 }, { -1, 25, -3 });
  vtkNew<vtkLightRaySingleScattering> pass;
  pass->AddLight(Directional({ 10, 10, -20 }, { 10, 10, 0 }, 1.0));
  pass->SetSurfaces(set);
  auto out = RunPass(pass, medium);
  const float* s = Radiance(out);
  for (int i = 0; i < 20; ++i)
  {
    const size_t v = i + 20 * (10 + 20 * static_cast<size_t>(5));
    if (i <= 9)
    {
      EXPECT_EQ(s[3 * v], 0.0f) << "voxel " << i << " lies in the shadow";
    }
    else
    {
      EXPECT_NEAR(s[3 * v], 0.05 * std::exp(-0.05 * 5.5), 1e-6) << "voxel " << i;
    }
  }
}

// Eq. 4 with dynamic sampling against per-voxel light rays on a heterogeneous cloud, 1, 8 and
// 64 point lights: at the default ErrorTolerance the RMS error relative to the light rays' RMS is
// below 2% (1.6% to 1.8% measured on 32^3), with under a third as many samples as voxels that
// scatter. (Whether that is faster depends on the grid: Documentation/Benchmarks.md.)
TEST(LightRays, InterpolationMatchesLightRaysOnCloud)
{
  const int n = 32;
  auto medium = Cloud(n);
  for (int count : { 1, 8, 64 })
  {
    vtkNew<vtkLightRaySingleScattering> exact, interpolated;
    for (auto& light : LightsAround(n, count))
    {
      exact->AddLight(light);
      interpolated->AddLight(light);
    }
    interpolated->SetMethodToInterpolated();
    interpolated->SetCoarsestGridResolution(8);
    auto a = RunPass(exact, medium);
    auto b = RunPass(interpolated, medium);
    const double rms = RelativeRms(Radiance(b), Radiance(a), 3 * static_cast<size_t>(n) * n * n);
    std::cout << count << " lights: RMS " << rms << ", samples "
              << interpolated->GetNumberOfSamples() << ", points "
              << interpolated->GetNumberOfEvaluatedPoints() << " vs "
              << exact->GetNumberOfEvaluatedPoints() << " voxels\n";
    EXPECT_LT(rms, 0.02) << count << " lights";
    EXPECT_EQ(interpolated->GetNumberOfUncoveredVoxels(), 0);
    EXPECT_LT(3 * interpolated->GetNumberOfSamples(), exact->GetNumberOfEvaluatedPoints());
    EXPECT_EQ(
      b->GetFieldData()->GetAbstractArray("SingleScatteringMethod")->GetVariantValue(0).ToString(),
      "interpolated");
  }
}

// A medium that scatters up to its faces (a uniform 20 x 14 x 17 box, off the origin). The light
// field is discontinuous at the faces (a ray beside the box never crosses it); samples on or
// outside a face used to take central differences across it and carried the unattenuated light
// into the voxels along the faces (RMS 28%, one voxel 4.6x too bright under a light along -y,
// before the samples were clamped into the box of voxel centres). Under that light the field is a
// smooth exponential in y and the interpolation is within 1% of the light rays in every voxel
// (0.5% measured: faces, edges, corners); under oblique lights it has kinks inside the box (where
// the exit face of the ray to the light changes), which the finest grid (half the medium's
// resolution, 2 voxels) does not resolve: RMS 2.7% and at worst 14% measured (13% and 150%
// before), bounds 4% and 20%.
TEST(LightRays, InterpolationMatchesLightRaysAtTheMediumsFaces)
{
  const int dims[3] = { 20, 14, 17 };
  auto medium = MakeMedium(
    dims[0], dims[1], dims[2], 0.2, [&](double, double, double) { return Homogeneous(0.6, 0.8); });
  medium->SetOrigin(-3.0, 1.5, 0.25);
  const size_t values = 3 * static_cast<size_t>(dims[0]) * dims[1] * dims[2];
  for (bool oblique : { false, true })
  {
    vtkNew<vtkLightRaySingleScattering> exact, interpolated;
    for (auto* pass : { exact.Get(), interpolated.Get() })
    {
      if (oblique)
      {
        pass->AddLight(Directional({ -1.0, 9.0, 3.0 }, { -1.1, 2.8, 1.8 }, 1.0));
        pass->AddLight(Positional({ 1.5, 4.0, -1.0 }, { -1.1, 2.8, 1.8 }, 180.0, 0.0, 5.0));
      }
      else
      {
        pass->AddLight(Directional({ -1.1, 9.0, 1.8 }, { -1.1, 2.8, 1.8 }, 1.0));
      }
    }
    interpolated->SetMethodToInterpolated();
    auto a = RunPass(exact, medium);
    auto b = RunPass(interpolated, medium);
    const float* sa = Radiance(a);
    const float* sb = Radiance(b);
    double worst = 0;
    for (size_t i = 0; i < values; ++i)
    {
      ASSERT_GT(sa[i], 0.0f);
      worst = std::max(worst, std::fabs(sb[i] / sa[i] - 1.0));
    }
    const double rms = RelativeRms(sb, sa, values);
    std::cout << (oblique ? "oblique" : "along -y") << ": largest relative difference " << worst
              << ", RMS " << rms << ", " << interpolated->GetNumberOfSamples() << " samples\n";
    EXPECT_LT(rms, oblique ? 0.04 : 0.01);
    EXPECT_LT(worst, oblique ? 0.2 : 0.01);
    EXPECT_EQ(interpolated->GetNumberOfUncoveredVoxels(), 0);
  }
}

// Dynamic sampling refines where the shading changes fast: a density step across x = 24 under a
// directional light along +x gets more finest-level samples in the slab around the step than in
// an equal slab in the flat part.
TEST(LightRays, DynamicSamplingRefinesAtDensityEdges)
{
  const int n = 48;
  auto medium = MakeMedium(
    n, n, n, 1.0, [&](double x, double, double) { return Homogeneous(x < 24 ? 0.02 : 0.5, 0.9); });
  vtkNew<vtkLightRaySingleScattering> pass;
  pass->AddLight(Directional({ -10, 23.5, 23.5 }, { 0, 23.5, 23.5 }, 1.0));
  pass->SetMethodToInterpolated();
  pass->SetCoarsestGridResolution(6);
  pass->SetMaximumGridResolution(24);
  RunPass(pass, medium);
  vtkDoubleArray* positions = pass->GetSamplePositions();
  vtkIntArray* levels = pass->GetSampleLevels();
  const int finest = static_cast<int>(pass->GetSamplesPerLevel().size()) - 1;
  ASSERT_GE(finest, 2);
  int atEdge = 0, flat = 0;
  for (vtkIdType s = 0; s < positions->GetNumberOfTuples(); ++s)
  {
    if (levels->GetValue(s) != finest)
    {
      continue;
    }
    const double x = positions->GetComponent(s, 0);
    atEdge += (x >= 18 && x < 30);
    flat += (x >= 4 && x < 16);
  }
  std::cout << "finest-level samples: " << atEdge << " at the edge, " << flat << " flat\n";
  EXPECT_GT(atEdge, 4 * std::max(flat, 1));
}

// The photon pass estimates the same S1 (averaged over each voxel, where the light rays give the
// value at its centre: the same on a smooth medium up to O(h^2)): its RMS distance to the light
// rays falls as photons grow (about 1 / sqrt(N)) and ends within 1.5%.
TEST(LightRays, PhotonsConvergeToLightRays)
{
  const int n = 24;
  const double c = 0.5 * (n - 1), r = 0.3 * n;
  auto medium = MakeMedium(
    n, n, n, 1.0,
    [&](double x, double y, double z)
    {
      const double d2 = (x - c) * (x - c) + (y - c) * (y - c) + (z - c) * (z - c);
      return Homogeneous(0.03 + 0.15 * std::exp(-d2 / (r * r)), 0.9);
    },
    false);
  vtkNew<vtkLightRaySingleScattering> exact;
  auto light = Directional({ 11.5, -10, 11.5 }, { 11.5, 0, 11.5 }, 1.0);
  exact->AddLight(light);
  auto reference = RunPass(exact, medium);
  std::vector<double> errors;
  for (int photons : { 1 << 14, 1 << 16, 1 << 18 })
  {
    vtkNew<vtkPhotonTracer> tracer;
    tracer->AddLight(light);
    tracer->SetNumberOfPhotons(photons);
    tracer->SmoothingOff();
    tracer->SetInputData(medium);
    tracer->Update();
    errors.push_back(RelativeRms(
      Radiance(tracer->GetOutput()), Radiance(reference), 3 * static_cast<size_t>(n) * n * n));
    std::cout << photons << " photons: RMS " << errors.back() << "\n";
  }
  EXPECT_LT(errors[1], 0.7 * errors[0]);
  EXPECT_LT(errors[2], 0.7 * errors[1]);
  EXPECT_LT(errors[2], 0.015);
}

// Bad input: errors with an empty output for what cannot run; warnings and a right (zero or
// dark) answer for what is legal.
TEST(LightRays, BadInput)
{
  {
    vtkNew<vtkLightRaySingleScattering> pass;
    vtkNew<vtkTest::ErrorObserver> errors;
    pass->AddObserver(vtkCommand::ErrorEvent, errors);
    pass->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, errors);
    vtkNew<vtkImageData> notAMedium;
    notAMedium->SetDimensions(4, 4, 4);
    pass->AddLight(Directional({ 0, 0, -1 }, { 0, 0, 0 }, 1.0));
    pass->SetInputData(notAMedium);
    pass->Update();
    EXPECT_TRUE(errors->GetError());
    EXPECT_EQ(pass->GetOutput()->GetNumberOfPoints(), 0);
  }
  auto medium =
    MakeMedium(8, 8, 8, 1.0, [&](double, double, double) { return Homogeneous(0.1, 0.5); });
  {
    vtkNew<vtkLightRaySingleScattering> pass;
    vtkNew<vtkTest::ErrorObserver> errors;
    pass->AddObserver(vtkCommand::ErrorEvent, errors);
    pass->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, errors);
    pass->AddLight(Positional({ 1, 1, 1 }, { 1, 1, 1 }, 30.0, 1.0, 1.0)); // spot without axis
    pass->SetInputData(medium);
    pass->Update();
    EXPECT_NE(errors->GetErrorMessage().find("focal"), std::string::npos);
    EXPECT_EQ(pass->GetOutput()->GetNumberOfPoints(), 0);
  }
  for (int method :
    { vtkLightRaySingleScattering::LIGHT_RAYS, vtkLightRaySingleScattering::INTERPOLATED })
  {
    // No lights, and a medium with no density: a zero lighting volume and a warning.
    vtkNew<vtkLightRaySingleScattering> dark;
    vtkNew<vtkTest::ErrorObserver> warnings;
    dark->AddObserver(vtkCommand::WarningEvent, warnings);
    dark->SetMethod(method);
    auto out = RunPass(dark, medium);
    EXPECT_TRUE(warnings->GetWarning());
    ASSERT_EQ(out->GetNumberOfPoints(), 512);
    for (int i = 0; i < 3 * 512; ++i)
    {
      ASSERT_EQ(Radiance(out)[i], 0.0f);
    }
    auto empty = MakeMedium(8, 8, 8, 1.0, [&](double, double, double) { return Voxel{}; });
    vtkNew<vtkLightRaySingleScattering> vacuum;
    vtkNew<vtkTest::ErrorObserver> vacuumWarnings;
    vacuum->AddObserver(vtkCommand::WarningEvent, vacuumWarnings);
    vacuum->SetMethod(method);
    vacuum->AddLight(Directional({ 0, 0, -1 }, { 0, 0, 0 }, 1.0));
    auto zero = RunPass(vacuum, empty);
    EXPECT_TRUE(vacuumWarnings->GetWarning());
    EXPECT_EQ(zero->GetNumberOfPoints(), 512);
    EXPECT_EQ(Radiance(zero)[0], 0.0f);
  }
  {
    // A point light inside an opaque voxel: a warning, and darkness outside that voxel.
    auto walled = MakeMedium(9, 9, 9, 1.0,
      [&](double x, double y, double z)
      { return (x == 4 && y == 4 && z == 4) ? Homogeneous(1e4, 0.5) : Homogeneous(0.1, 0.5); });
    vtkNew<vtkLightRaySingleScattering> pass;
    vtkNew<vtkTest::ErrorObserver> warnings;
    pass->AddObserver(vtkCommand::WarningEvent, warnings);
    pass->AddLight(Positional({ 4, 4, 4 }, { 4, 4, 5 }, 180.0, 0.0, 1.0));
    auto out = RunPass(pass, walled);
    EXPECT_NE(warnings->GetWarningMessage().find("opaque"), std::string::npos);
    double sum = 0;
    for (int v = 0; v < 9 * 9 * 9; ++v)
    {
      ASSERT_TRUE(std::isfinite(Radiance(out)[3 * v]));
      sum += v == 4 + 9 * (4 + 9 * 4) ? 0.0 : Radiance(out)[3 * v];
    }
    EXPECT_LT(sum, 1e-12);
  }
}

// ComputeSurfaceIrradiance refuses what it cannot light, with the reason: no medium, an invalid
// one, no surfaces, a bad light; each leaves the result empty.
TEST(LightRays, SurfaceIrradianceBadInput)
{
  auto medium =
    MakeMedium(8, 8, 8, 1.0, [&](double, double, double) { return Homogeneous(0.1, 0.5); });
  vtkNew<vtkPlaneSource> plane;
  plane->Update();
  vtkNew<vtkRefractaSurfaceSet> floor;
  floor->AddSurface(plane->GetOutput());
  vtkNew<vtkImageData> notAMedium;
  notAMedium->SetDimensions(4, 4, 4);
  struct Case
  {
    vtkImageData* Medium;
    vtkRefractaSurfaceSet* Surfaces;
    bool SpotWithoutAxis;
    const char* Expected;
  };
  const Case cases[] = { { nullptr, floor, false, "none given" },
    { notAMedium, floor, false, "valid Refracta medium" }, { medium, nullptr, false, "surfaces" },
    { medium, floor, true, "focal" } };
  for (const Case& c : cases)
  {
    vtkNew<vtkLightRaySingleScattering> pass;
    vtkNew<vtkTest::ErrorObserver> errors;
    pass->AddObserver(vtkCommand::ErrorEvent, errors);
    pass->AddLight(c.SpotWithoutAxis ? Positional({ 1, 1, 1 }, { 1, 1, 1 }, 30.0, 1.0, 1.0)
                                     : Directional({ 0, 0, -1 }, { 0, 0, 0 }, 1.0));
    pass->SetSurfaces(c.Surfaces);
    std::vector<float> irradiance(3, 1.0f);
    EXPECT_FALSE(pass->ComputeSurfaceIrradiance(c.Medium, irradiance)) << c.Expected;
    EXPECT_NE(errors->GetErrorMessage().find(c.Expected), std::string::npos)
      << errors->GetErrorMessage();
    EXPECT_TRUE(irradiance.empty());
  }
}
