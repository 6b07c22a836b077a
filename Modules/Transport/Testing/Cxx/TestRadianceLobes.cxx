// S1's lobes (MaximumRadianceLobes of vtkLightRaySingleScattering and vtkPhotonTracer): each group
// of lights' S1 and mean direction kept apart, so that the view pass can shade lights from
// different sides each about its own direction. The light rays' lobes must sum to Radiance, hold
// exactly what their lights alone give, point along their own lights, group lights by direction
// when there are more lights than lobes, survive the interpolation and the box means, and appear
// only where the phase function looks at the direction; the photons' lobes must sum to their
// Radiance, point along their lights and agree with the light rays' lobes within their noise.
#include "PhotonTestUtilities.h"
#include "vtkLightRaySingleScattering.h"
#include "vtkOpenCLContext.h"
#include "vtkPhotonTracer.h"
#include "vtkRefractaLightingVolume.h"
#include "vtkRefractaMedium.h"
#include "vtkTypeInt64Array.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

using namespace photontest;

namespace
{
constexpr int N = 24;

// A homogeneous ball (sigma_t `sigma` per voxel, albedo 0.8) in an n^3 grid off the origin, with
// anisotropy g everywhere.
vtkSmartPointer<vtkImageData> Ball(double g, double sigma = 0.15)
{
  const double c = 0.5 * (N - 1), radius = 0.45 * N;
  auto medium = MakeMedium(
    N, N, N, 1.0,
    [&](double x, double y, double z)
    {
      Voxel v;
      if ((x - c) * (x - c) + (y - c) * (y - c) + (z - c) * (z - c) <= radius * radius)
      {
        v.Extinction = { sigma, sigma, sigma };
        v.Albedo = { 0.8, 0.8, 0.8 };
      }
      return v;
    },
    false);
  medium->SetOrigin(3.0, -2.0, 5.0); // grid-local directions do not depend on the origin
  vtkNew<vtkFloatArray> anisotropy;
  anisotropy->SetName(vtkRefractaMedium::AnisotropyName());
  anisotropy->SetNumberOfTuples(medium->GetNumberOfPoints());
  anisotropy->FillValue(static_cast<float>(g));
  medium->GetPointData()->AddArray(anisotropy);
  return medium;
}

// World position of the grid's centre.
std::array<double, 3> Centre(vtkImageData* medium)
{
  const double* o = medium->GetOrigin();
  const double c = 0.5 * (N - 1);
  return { o[0] + c, o[1] + c, o[2] + c };
}

std::array<double, 3> Offset(const std::array<double, 3>& p, double dx, double dy, double dz)
{
  return { p[0] + dx, p[1] + dy, p[2] + dz };
}

vtkSmartPointer<vtkImageData> RunLobes(vtkImageData* medium,
  const std::vector<vtkSmartPointer<vtkLight>>& lights, int maximumLobes = 2,
  int method = vtkLightRaySingleScattering::LIGHT_RAYS, int* lobes = nullptr)
{
  vtkNew<vtkLightRaySingleScattering> pass;
  for (const auto& light : lights)
  {
    pass->AddLight(light);
  }
  pass->SetMaximumRadianceLobes(maximumLobes);
  pass->SetMethod(method);
  pass->SetInputData(medium);
  pass->Update();
  if (lobes)
  {
    *lobes = pass->GetLastNumberOfLobes();
  }
  auto out = vtkSmartPointer<vtkImageData>::New();
  out->DeepCopy(pass->GetOutput());
  return out;
}

const float* Lobe(vtkImageData* out, int k, bool direction = false)
{
  return FloatPointer(out,
    direction ? vtkRefractaLightingVolume::RadianceLobeDirectionName(k)
              : vtkRefractaLightingVolume::RadianceLobeName(k));
}

// sqrt(sum (a - b)^2 / sum b^2) over 3 floats per voxel.
double RelativeRms(const float* a, const float* b)
{
  double diff = 0, ref = 0;
  for (size_t i = 0; i < 3 * static_cast<size_t>(N) * N * N; ++i)
  {
    diff += (a[i] - b[i]) * static_cast<double>(a[i] - b[i]);
    ref += static_cast<double>(b[i]) * b[i];
  }
  return std::sqrt(diff / std::max(ref, 1e-300));
}

// Largest |a - b| over the largest |b|, over 3 floats per voxel.
double RelativeDifference(const float* a, const float* b)
{
  double worst = 0, scale = 0;
  for (size_t i = 0; i < 3 * static_cast<size_t>(N) * N * N; ++i)
  {
    worst = std::max(worst, std::fabs(static_cast<double>(a[i]) - b[i]));
    scale = std::max(scale, std::fabs(static_cast<double>(b[i])));
  }
  return scale > 0 ? worst / scale : worst;
}

// The lobes' sum, 3 floats per voxel.
std::vector<float> LobeSum(vtkImageData* out)
{
  std::vector<float> sum(3 * static_cast<size_t>(N) * N * N);
  for (size_t i = 0; i < sum.size(); ++i)
  {
    sum[i] = Lobe(out, 0)[i] + Lobe(out, 1)[i];
  }
  return sum;
}

// The sun from +x (a little above) and a lamp at -x, -z, 2000 / 625 = 3.2 at the centre: light 0
// and light 1.
struct SunAndLamp
{
  std::array<double, 3> Lamp;
  double SunTravel[3] = { -30.0, -5.0, 0.0 };
  vtkSmartPointer<vtkLight> Sun, Point;
  explicit SunAndLamp(vtkImageData* medium)
  {
    const auto c = Centre(medium);
    this->Lamp = Offset(c, -20.0, 0.0, -15.0);
    this->Sun = Directional(Offset(c, 30.0, 5.0, 0.0), c, 1.0);
    this->Point = Positional(this->Lamp, c, 180.0, 0.0, 2000.0);
    vtkMath::Normalize(this->SunTravel);
  }
};

// Over the voxels where the sun's lobe (0) holds light and the lamp's (1) at least `floor` of its
// peak: the largest 1 - cos between lobe 0's direction and the sun's travel direction, and
// between lobe 1's and the direction away from the lamp; the smallest cosine between
// RadianceDirection and lobe 0's direction; the voxels compared.
struct DirectionErrors
{
  double Sun = 0, Lamp = 0, Mixed = 1;
  int Compared = 0;
};
DirectionErrors CheckDirections(
  vtkImageData* medium, vtkImageData* out, const SunAndLamp& lights, double floor)
{
  double peak = 0;
  for (size_t i = 0; i < 3 * static_cast<size_t>(N) * N * N; ++i)
  {
    peak = std::max(peak, static_cast<double>(Lobe(out, 1)[i]));
  }
  const double* o = medium->GetOrigin();
  const double* sun = lights.SunTravel;
  DirectionErrors e;
  for (int k = 0; k < N; ++k)
    for (int j = 0; j < N; ++j)
      for (int i = 0; i < N; ++i)
      {
        const size_t v = i + N * (j + static_cast<size_t>(N) * k);
        if (Lobe(out, 0)[3 * v] <= 0 || !(Lobe(out, 1)[3 * v] > floor * peak))
        {
          continue;
        }
        ++e.Compared;
        double away[3] = { o[0] + i - lights.Lamp[0], o[1] + j - lights.Lamp[1],
          o[2] + k - lights.Lamp[2] };
        vtkMath::Normalize(away);
        const float* dSun = Lobe(out, 0, true) + 3 * v;
        const float* dLamp = Lobe(out, 1, true) + 3 * v;
        const float* dMean = Direction(out) + 3 * v;
        e.Sun = std::max(e.Sun, 1.0 - (sun[0] * dSun[0] + sun[1] * dSun[1] + sun[2] * dSun[2]));
        e.Lamp =
          std::max(e.Lamp, 1.0 - (away[0] * dLamp[0] + away[1] * dLamp[1] + away[2] * dLamp[2]));
        e.Mixed = std::min(e.Mixed,
          static_cast<double>(dMean[0] * dSun[0] + dMean[1] * dSun[1] + dMean[2] * dSun[2]));
      }
  return e;
}
}

// A sun from +x and a point light at -x, -z: two lobes (lobe k: light k, no more lights than
// lobes), summing to Radiance, each what its light alone gives, pointing along that light's travel
// direction.
TEST(LightRayLobes, LobesSumToRadianceAndFollowTheirLight)
{
  auto medium = Ball(0.5);
  const SunAndLamp lights(medium);
  int lobes = 0;
  auto both = RunLobes(
    medium, { lights.Sun, lights.Point }, 2, vtkLightRaySingleScattering::LIGHT_RAYS, &lobes);
  ASSERT_EQ(lobes, 2);
  ASSERT_EQ(vtkRefractaLightingVolume::GetNumberOfRadianceLobes(both), 2);
  auto sunAlone = RunLobes(medium, { lights.Sun });
  EXPECT_EQ(vtkRefractaLightingVolume::GetNumberOfRadianceLobes(sunAlone), 0) << "one light";
  EXPECT_LT(RelativeDifference(Lobe(both, 0), Radiance(sunAlone)), 1e-6);
  EXPECT_LT(RelativeDifference(Lobe(both, 1), Radiance(RunLobes(medium, { lights.Point }))), 1e-6);
  EXPECT_LT(RelativeDifference(LobeSum(both).data(), Radiance(both)), 1e-6);
  // Directions: the sun's is constant, the lamp's points away from it; Radiance's is between.
  const DirectionErrors e = CheckDirections(medium, both, lights, 0.0);
  EXPECT_GT(e.Compared, 4000);
  EXPECT_LT(e.Sun, 1e-6) << "the sun's lobe points along the sun";
  EXPECT_LT(e.Lamp, 1e-5) << "the lamp's lobe points away from the lamp";
  EXPECT_LT(e.Mixed, 0.5) << "Radiance's mean direction is far from either light's somewhere";
}

// A dense ball (2 optical depths per voxel): its surface voxels get box means, per lobe too,
// each exactly what its light alone gives.
TEST(LightRayLobes, BoxMeansKeepTheLobes)
{
  auto medium = Ball(0.5, 2.0);
  const SunAndLamp lights(medium);
  int lobes = 0;
  auto both = RunLobes(
    medium, { lights.Sun, lights.Point }, 2, vtkLightRaySingleScattering::LIGHT_RAYS, &lobes);
  ASSERT_EQ(lobes, 2);
  auto boxes =
    vtkTypeInt64Array::SafeDownCast(both->GetFieldData()->GetAbstractArray("BoxMeanVoxels"));
  ASSERT_NE(boxes, nullptr);
  EXPECT_GT(boxes->GetValue(0), 1000);
  EXPECT_LT(RelativeDifference(Lobe(both, 0), Radiance(RunLobes(medium, { lights.Sun }))), 1e-6);
  EXPECT_LT(RelativeDifference(Lobe(both, 1), Radiance(RunLobes(medium, { lights.Point }))), 1e-6);
}

// Lobes only where the phase function looks at the direction: not over an isotropic medium, not
// with one light, not with MaximumRadianceLobes 1. Radiance is the same with and without them.
TEST(LightRayLobes, NoLobesWhereTheyChangeNothing)
{
  auto isotropic = Ball(0.0);
  const auto c = Centre(isotropic);
  const std::vector<vtkSmartPointer<vtkLight>> lights = { Directional(Offset(c, 30, 0, 0), c, 1.0),
    Directional(Offset(c, -30, 0, 0), c, 1.0) };
  int lobes = 0;
  auto out = RunLobes(isotropic, lights, 2, vtkLightRaySingleScattering::LIGHT_RAYS, &lobes);
  EXPECT_EQ(lobes, 1);
  EXPECT_EQ(vtkRefractaLightingVolume::GetNumberOfRadianceLobes(out), 0);
  EXPECT_EQ(out->GetPointData()->GetArray(vtkRefractaLightingVolume::RadianceLobeName(0)), nullptr);
  auto forward = Ball(0.7);
  auto one = RunLobes(forward, lights, 1, vtkLightRaySingleScattering::LIGHT_RAYS, &lobes);
  EXPECT_EQ(lobes, 1);
  EXPECT_EQ(vtkRefractaLightingVolume::GetNumberOfRadianceLobes(one), 0);
  auto two = RunLobes(forward, lights, 2, vtkLightRaySingleScattering::LIGHT_RAYS, &lobes);
  EXPECT_EQ(lobes, 2);
  EXPECT_EQ(RelativeDifference(Radiance(one), Radiance(two)), 0.0);
  EXPECT_EQ(RelativeDifference(Direction(one), Direction(two)), 0.0);
}

// Three suns, two of them 10 degrees apart from +x and one from -x, into two lobes: the close pair
// shares a lobe (with the sum of their light; the stronger of them seeds lobe 0), the opposite sun
// has the other one.
TEST(LightRayLobes, MoreLightsThanLobesAreGroupedByDirection)
{
  auto medium = Ball(0.5);
  const auto c = Centre(medium);
  const double t = vtkMath::RadiansFromDegrees(10.0);
  auto a = Directional(Offset(c, 30, 0, 0), c, 1.0);
  auto b = Directional(Offset(c, 30 * std::cos(t), 30 * std::sin(t), 0), c, 0.8);
  auto opposite = Directional(Offset(c, -30, 0, 0), c, 0.5);
  int lobes = 0;
  auto out =
    RunLobes(medium, { a, opposite, b }, 2, vtkLightRaySingleScattering::LIGHT_RAYS, &lobes);
  ASSERT_EQ(lobes, 2);
  auto pair = RunLobes(medium, { a, b });
  auto alone = RunLobes(medium, { opposite });
  EXPECT_LT(RelativeDifference(Lobe(out, 0), Radiance(pair)), 1e-6) << "a and b: the first lobe";
  EXPECT_LT(RelativeDifference(Lobe(out, 1), Radiance(alone)), 1e-6) << "the opposite sun";
}

// The interpolation interpolates every lobe with the samples' weights: the lobes sum to its
// Radiance and each is about as close to the light rays' lobe as the sum is to theirs.
TEST(LightRayLobes, InterpolationKeepsTheLobes)
{
  auto medium = Ball(0.5);
  const auto c = Centre(medium);
  const std::vector<vtkSmartPointer<vtkLight>> lights = { Directional(Offset(c, 30, 8, 0), c, 1.0),
    Positional(Offset(c, -6, -20, 10), c, 180.0, 0.0, 900.0) };
  auto exact = RunLobes(medium, lights);
  int lobes = 0;
  auto interpolated =
    RunLobes(medium, lights, 2, vtkLightRaySingleScattering::INTERPOLATED, &lobes);
  ASSERT_EQ(lobes, 2);
  EXPECT_LT(RelativeDifference(LobeSum(interpolated).data(), Radiance(interpolated)), 1e-5);
  // The ball's sharp edge at 24^3 costs the interpolation a few percent (its finest grid has 2
  // voxels per cell): measured RMS 4.4% on Radiance, 4.7% and 5.7% on the lobes.
  const double total = RelativeRms(Radiance(interpolated), Radiance(exact));
  std::cout << "Radiance: RMS " << total << "\n";
  EXPECT_LT(total, 0.06);
  for (int k = 0; k < 2; ++k)
  {
    const double error = RelativeRms(Lobe(interpolated, k), Lobe(exact, k));
    std::cout << "lobe " << k << ": RMS " << error << "\n";
    EXPECT_LT(error, 1.5 * total) << "lobe " << k << " interpolated worse than the sum";
  }
}

// The photons' lobes: the sun and the point light of the first test, 2^18 photons (smoothed, as
// the pipeline runs them). Lobe k holds the photons of light k: the lobes sum to Radiance (the same
// deposits, resolved by the same linear steps), the sun's lobe points along the sun, the lamp's
// away from the lamp, and each lobe is as close to the light rays' lobe as the photons' Radiance is
// to theirs (measured RMS 18.4% and 20.4% against 19.9%: the ball's edge, where the photons give
// box means and the light rays centre values, and the smoothing; swapped, 95% and 355%).
TEST(PhotonLobes, LobesSumToRadianceFollowTheirLightAndMatchTheLightRays)
{
  auto medium = Ball(0.5);
  const SunAndLamp lights(medium);
  vtkNew<vtkPhotonTracer> tracer;
  tracer->AddLight(lights.Sun);
  tracer->AddLight(lights.Point);
  tracer->SetNumberOfPhotons(1 << 18);
  tracer->SetInputData(medium);
  tracer->Update();
  ASSERT_EQ(tracer->GetLastNumberOfLobes(), 2);
  vtkImageData* photons = tracer->GetOutput();
  ASSERT_EQ(vtkRefractaLightingVolume::GetNumberOfRadianceLobes(photons), 2);
  EXPECT_LT(RelativeDifference(LobeSum(photons).data(), Radiance(photons)), 1e-5);
  // Where the lamp's lobe holds at least 1% of its peak (the smoothing blends the directions of
  // neighbouring voxels, a few degrees apart near the lamp).
  const DirectionErrors e = CheckDirections(medium, photons, lights, 0.01);
  EXPECT_GT(e.Compared, 4000);
  EXPECT_LT(e.Sun, 1e-5) << "the sun's lobe points along the sun";
  EXPECT_LT(e.Lamp, 0.01) << "the lamp's lobe points away from the lamp (within 8 degrees)";
  auto rays = RunLobes(medium, { lights.Sun, lights.Point });
  const double total = RelativeRms(Radiance(photons), Radiance(rays));
  std::cout << "photon Radiance: RMS " << total << " of the light rays'\n";
  EXPECT_LT(total, 0.25);
  for (int k = 0; k < 2; ++k)
  {
    const double error = RelativeRms(Lobe(photons, k), Lobe(rays, k));
    const double swapped = RelativeRms(Lobe(photons, k), Lobe(rays, 1 - k));
    std::cout << "photon lobe " << k << ": RMS " << error << " of the light rays' lobe, " << swapped
              << " of the other\n";
    EXPECT_LT(error, 1.25 * total) << "lobe " << k;
    EXPECT_GT(swapped, 0.5) << "lobe " << k;
  }
  // The chunked march (the interleaved lattice's) resumes each photon with its lobe: its lobes sum
  // to its Radiance, and differ from the whole march's as little as its Radiance does (its
  // straight walks are cut into segments, so the pieces, and the roulette, differ).
  vtkNew<vtkImageData> whole;
  whole->DeepCopy(photons);
  tracer->SetStepsPerChunk(3);
  // What a chunk callback (the interleaved lattice) reads: all of S1, the lobes' sum.
  double lastSeen = -1;
  tracer->SetChunkCallback(
    [&](cl_mem deposits, double radianceFactor, double, int active)
    {
      std::vector<cl_long> first(6 * static_cast<size_t>(N) * N * N);
      if (active == 0 &&
        tracer->GetContext()->ReadBuffer(deposits, first.size() * sizeof(cl_long), first.data()))
      {
        lastSeen = 0;
        for (size_t v = 0; v < first.size(); v += 6)
        {
          lastSeen += radianceFactor * static_cast<double>(first[v]);
        }
      }
      return true;
    });
  tracer->Update();
  tracer->SetChunkCallback(nullptr);
  vtkImageData* chunked = tracer->GetOutput();
  double power = 0; // channel 0's sum; the smoothing keeps it
  for (size_t v = 0; v < 3 * static_cast<size_t>(N) * N * N; v += 3)
  {
    power += Radiance(chunked)[v];
  }
  EXPECT_NEAR(lastSeen, power, 1e-4 * power) << "the last chunk's deposits hold all of S1";
  ASSERT_EQ(vtkRefractaLightingVolume::GetNumberOfRadianceLobes(chunked), 2);
  const double moved = RelativeRms(Radiance(chunked), Radiance(whole));
  for (int k = 0; k < 2; ++k)
  {
    const double lobeMoved = RelativeRms(Lobe(chunked, k), Lobe(whole, k));
    std::cout << "chunked: Radiance RMS " << moved << ", lobe " << k << " " << lobeMoved << "\n";
    EXPECT_LT(lobeMoved, 2 * moved + 0.01) << "chunked lobe " << k;
  }
  EXPECT_LT(RelativeDifference(LobeSum(chunked).data(), Radiance(chunked)), 1e-5);
  tracer->SetStepsPerChunk(0);
  // An isotropic medium: no lobes.
  tracer->SetInputData(Ball(0.0));
  tracer->Update();
  EXPECT_EQ(tracer->GetLastNumberOfLobes(), 1);
  EXPECT_EQ(vtkRefractaLightingVolume::GetNumberOfRadianceLobes(tracer->GetOutput()), 0);
}
