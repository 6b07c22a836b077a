// Tests of vtkPhotonTracer's bookkeeping: Beer-Lambert transmission and deposit profile, energy
// balance, emitted power of every light type, determinism, frames (origin at 1e6, rotated grid),
// the octree against a brute-force CPU build, the gradient default, and bad input.
#include "PhotonTestUtilities.h"

#include "vtkExecutive.h"
#include "vtkLightCollection.h"
#include "vtkMatrix3x3.h"
#include "vtkOpenCLContext.h"
#include "vtkPhotonTracer.h"
#include "vtkRefractaMedium.h"
#include "vtkTestErrorObserver.h"
#include "vtkUnsignedCharArray.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <vector>

using namespace photontest;

namespace
{
double Sum(const std::array<double, 3>& a)
{
  return a[0] + a[1] + a[2];
}

vtkSmartPointer<vtkImageData> Trace(vtkPhotonTracer* tracer, vtkImageData* medium)
{
  tracer->SetInputData(medium);
  tracer->Update();
  auto out = vtkSmartPointer<vtkImageData>::New();
  out->DeepCopy(tracer->GetOutput());
  return out;
}

// Uniform weakly absorbing medium (so that the proxy box is the whole grid).
vtkSmartPointer<vtkImageData> Haze(int nx, int ny, int nz, double s)
{
  return MakeMedium(nx, ny, nz, s,
    [](double, double, double)
    {
      Voxel v;
      v.Extinction = { 1e-3, 1e-3, 1e-3 };
      return v;
    });
}
}

// Straight photons through a homogeneous slab: transmission exp(-sigma_t L) per channel, and the
// deposit profile sigma_s E exp(-sigma_t z) averaged over each voxel slice. Parallel rays
// perpendicular to the slab all travel exactly L, so the only error is float rounding and the
// lateral sampling density: 1% is the tolerance and is ~100x the expected error.
TEST(PhotonTracer, BeerLambertSlab)
{
  const double s = 0.1;
  const int nz = 40;
  const std::array<double, 3> sigma{ 0.1, 0.4, 0.8 };
  auto medium = MakeMedium(8, 8, nz, s,
    [&](double, double, double)
    {
      Voxel v;
      v.Extinction = sigma;
      v.Albedo = { 0.5, 0.5, 0.5 };
      return v;
    });
  vtkNew<vtkPhotonTracer> tracer;
  const double E = 2.0;
  tracer->AddLight(Directional({ 0.35, 0.35, -10 }, { 0.35, 0.35, 0 }, E));
  tracer->SetNumberOfPhotons(1 << 14);
  tracer->SmoothingOff();
  auto out = Trace(tracer, medium);
  EXPECT_FALSE(tracer->GetUsedCurvedRays());
  EXPECT_TRUE(tracer->GetUsedDeposit());
  const auto emitted = Energy(out, "EnergyEmitted");
  const auto escaped = Energy(out, "EnergyEscaped");
  const double L = nz * s;
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_NEAR(emitted[c], E * 0.8 * 0.8, 1e-4 * E); // the footprint is exactly the face
    const double T = std::exp(-sigma[c] * L);
    EXPECT_NEAR(escaped[c] / emitted[c], T, 0.01 * T) << "channel " << c;
  }
  EXPECT_EQ(Field(out, "TerminatedRoulette"), 0);
  // Slice averages of Radiance against the voxel-averaged analytic profile.
  const float* rad = Radiance(out);
  for (int k = 0; k < nz; k += 3)
  {
    for (int c = 0; c < 3; ++c)
    {
      double mean = 0;
      for (int v = 0; v < 64; ++v)
      {
        mean += rad[3 * (k * 64 + v) + c] / 64.0;
      }
      const double expected =
        0.5 * E * (std::exp(-sigma[c] * k * s) - std::exp(-sigma[c] * (k + 1) * s)) / s;
      EXPECT_NEAR(mean, expected, 0.01 * expected) << "slice " << k << " channel " << c;
    }
  }
  // The deposits are the scattered energy: sum(Radiance) * V = EnergyScattered.
  const auto scattered = Energy(out, "EnergyScattered");
  for (int c = 0; c < 3; ++c)
  {
    double total = 0;
    for (vtkIdType v = 0; v < out->GetNumberOfPoints(); ++v)
    {
      total += rad[3 * v + c] * s * s * s;
    }
    EXPECT_NEAR(total, scattered[c], 1e-4 * scattered[c]);
  }
}

namespace
{
// A refracting, scattering, heterogeneous medium lit by three kinds of light.
vtkSmartPointer<vtkImageData> FoggyLens()
{
  return MakeMedium(24, 20, 16, 0.05,
    [](double x, double y, double z)
    {
      Voxel v;
      const double r =
        std::sqrt((x - 0.6) * (x - 0.6) + (y - 0.45) * (y - 0.45) + (z - 0.35) * (z - 0.35));
      v.N = 1.0 + 0.2 * (1.0 - std::tanh((r - 0.25) / 0.05));
      const double fog = 1.5 + std::sin(7 * x) * std::cos(5 * y);
      v.Extinction = { fog, 1.5 * fog, 2 * fog };
      v.Albedo = { 0.7, 0.8, 0.9 };
      return v;
    });
}

void AddThreeLights(vtkPhotonTracer* tracer)
{
  tracer->AddLight(Directional({ -1, 0.2, 0.1 }, { 0.6, 0.5, 0.4 }, 1.0, { 1, 0.8, 0.6 }));
  tracer->AddLight(Positional({ 0.5, 2.0, 0.4 }, { 0.5, 0, 0.4 }, 120, 1, 0.5));
  tracer->AddLight(Positional({ 0.3, 0.3, 0.3 }, { 1, 0.5, 0.5 }, 40, 2, 0.3, { 0.2, 1, 1 }));
}
}

// emitted = absorbed + escaped + scattered + remaining, per channel, with roulette and the step
// cap both active. Every photon's books close in float (each piece's loss is P (1 - e^-tau),
// split between absorbed and scattered; P is reduced by the same amount), so the totals agree up
// to float and fixed-point rounding: 1e-4 relative, far inside the 0.5%.
TEST(PhotonTracer, EnergyBalanceCloses)
{
  vtkNew<vtkPhotonTracer> tracer;
  AddThreeLights(tracer);
  tracer->SetNumberOfPhotons(1 << 15);
  tracer->SetRouletteThreshold(0.3);
  tracer->SetMaximumNumberOfSteps(20);
  auto medium = FoggyLens();
  auto out = Trace(tracer, medium);
  std::printf("photons %g: escaped %g, roulette %g, step cap %g; steps %g\n",
    Field(out, "PhotonsMarched"), Field(out, "TerminatedEscaped"), Field(out, "TerminatedRoulette"),
    Field(out, "TerminatedStepCap"), Field(out, "TotalSteps"));
  EXPECT_TRUE(tracer->GetUsedCurvedRays());
  EXPECT_TRUE(tracer->GetUsedOctree());
  EXPECT_TRUE(tracer->GetComputedGradient());
  EXPECT_GT(Field(out, "TerminatedRoulette"), 100);
  EXPECT_GT(Field(out, "TerminatedStepCap"), 10);
  EXPECT_GT(Field(out, "TerminatedEscaped"), 100);
  EXPECT_EQ(Field(out, "TerminatedInvalid"), 0);
  EXPECT_EQ(Field(out, "NumberOfPhotons"), 1 << 15);
  const auto emitted = Energy(out, "EnergyEmitted");
  const auto absorbed = Energy(out, "EnergyAbsorbed");
  const auto escaped = Energy(out, "EnergyEscaped");
  const auto scattered = Energy(out, "EnergyScattered");
  const auto remaining = Energy(out, "EnergyRemaining");
  const float* rad = Radiance(out);
  const double V = 0.05 * 0.05 * 0.05;
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_GT(emitted[c], 0);
    EXPECT_GT(absorbed[c], 0.05 * emitted[c]);
    EXPECT_GT(scattered[c], 0.05 * emitted[c]);
    const double books = absorbed[c] + escaped[c] + scattered[c] + remaining[c];
    EXPECT_NEAR(books, emitted[c], 1e-4 * emitted[c]) << "channel " << c;
    // The smoothing moves deposits between voxels but conserves their total.
    double total = 0;
    for (vtkIdType v = 0; v < out->GetNumberOfPoints(); ++v)
    {
      total += rad[3 * v + c] * V;
    }
    EXPECT_NEAR(total, scattered[c], 1e-4 * scattered[c]);
  }
  const float* dir = Direction(out);
  for (vtkIdType v = 0; v < out->GetNumberOfPoints(); ++v)
  {
    const double m = std::sqrt(
      dir[3 * v] * dir[3 * v] + dir[3 * v + 1] * dir[3 * v + 1] + dir[3 * v + 2] * dir[3 * v + 2]);
    ASSERT_TRUE(std::abs(m - 1) < 1e-4 || m == 0) << "voxel " << v;
  }
}

// Russian roulette is unbiased: the escaped energy with an aggressive threshold matches the one
// without roulette. The difference is a mean over 4 seeds, tested against 5 standard errors
// estimated from the seeds' spread (plus 0.1% for the float rounding of either run).
TEST(PhotonTracer, RussianRouletteIsUnbiased)
{
  auto medium = FoggyLens();
  std::vector<double> diff;
  for (unsigned int seed = 1; seed <= 4; ++seed)
  {
    double escaped[2];
    for (int rr = 0; rr < 2; ++rr)
    {
      vtkNew<vtkPhotonTracer> tracer;
      AddThreeLights(tracer);
      tracer->SetNumberOfPhotons(1 << 14);
      tracer->SetSeed(seed);
      tracer->SetRouletteThreshold(rr ? 0.2 : 0.0);
      auto out = Trace(tracer, medium);
      escaped[rr] = Sum(Energy(out, "EnergyEscaped")) / Sum(Energy(out, "EnergyEmitted"));
      if (rr)
      {
        EXPECT_GT(Field(out, "TerminatedRoulette"), 1000);
      }
    }
    diff.push_back(escaped[1] - escaped[0]);
  }
  double mean = 0, var = 0;
  for (double d : diff)
  {
    mean += d / diff.size();
  }
  for (double d : diff)
  {
    var += (d - mean) * (d - mean) / (diff.size() - 1);
  }
  const double se = std::sqrt(var / diff.size());
  EXPECT_LT(std::abs(mean), 5 * se + 1e-3) << "mean " << mean << " se " << se;
  EXPECT_GT(se, 0.0);
}

// Same seed: identical bits; another seed: different deposits (roulette streams differ).
TEST(PhotonTracer, DeterministicForASeed)
{
  auto medium = FoggyLens();
  vtkNew<vtkPhotonTracer> tracer;
  AddThreeLights(tracer);
  tracer->SetNumberOfPhotons(1 << 14);
  tracer->SetRouletteThreshold(0.2);
  auto a = Trace(tracer, medium);
  tracer->Modified();
  auto b = Trace(tracer, medium);
  tracer->SetSeed(7);
  auto c = Trace(tracer, medium);
  const size_t bytes = 3 * sizeof(float) * a->GetNumberOfPoints();
  EXPECT_EQ(std::memcmp(Radiance(a), Radiance(b), bytes), 0);
  EXPECT_EQ(std::memcmp(Direction(a), Direction(b), bytes), 0);
  EXPECT_NE(std::memcmp(Radiance(a), Radiance(c), bytes), 0);
}

// Emitted power of each light type against its closed form. The estimates are Monte Carlo
// (stratified) over the sampled cap or rectangle; the tolerance is 5 standard errors of plain
// Monte Carlo (stratification only lowers the error).
TEST(PhotonTracer, EmittedPowerOfLights)
{
  const double s = 0.1;
  auto medium = Haze(10, 8, 6, s); // box [-0.05, 0.95] x [-0.05, 0.75] x [-0.05, 0.55]
  const int N = 1 << 14;
  // Point light on the axis of the -z face, 0.5 in front of it: solid angle of a rectangle.
  {
    vtkNew<vtkPhotonTracer> tracer;
    tracer->SetNumberOfPhotons(N);
    const double d = 0.5, a = 0.5, b = 0.4;
    tracer->AddLight(Positional({ 0.45, 0.35, -0.05 - d }, { 0.45, 0.35, 0 }, 180, 1, 2.0));
    auto out = Trace(tracer, medium);
    const double omega = 4 * std::asin(a * b / std::sqrt((a * a + d * d) * (b * b + d * d)));
    // Sampled cap: the cone around the box's bounding sphere.
    const double r = 0.5 * std::sqrt(1.0 + 0.64 + 0.36);
    const double D = d + 0.3;
    const double cap = 2 * vtkMath::Pi() * (1 - std::sqrt(1 - r * r / (D * D)));
    const double p = omega / cap;
    const double se = 2.0 * cap * std::sqrt(p * (1 - p) / N);
    EXPECT_NEAR(Field(out, "EnergyEmitted"), 2.0 * omega, 5 * se);
    EXPECT_GT(Field(out, "PhotonsMissed"), 0);
  }
  // Spot inside the box: all photons start inside; power = I0 2 pi (1 - cos^(e+1)) / (e + 1).
  {
    vtkNew<vtkPhotonTracer> tracer;
    tracer->SetNumberOfPhotons(N);
    const double e = 3, cone = 35;
    tracer->AddLight(
      Positional({ 0.4, 0.3, 0.2 }, { 0.4, 1.3, 0.2 }, cone, e, 1.5, { 1, 0.5, 0.25 }));
    auto out = Trace(tracer, medium);
    const double c = std::cos(vtkMath::RadiansFromDegrees(cone));
    const double power = 1.5 * 2 * vtkMath::Pi() * (1 - std::pow(c, e + 1)) / (e + 1);
    const double omega = 2 * vtkMath::Pi() * (1 - c);
    const double se = 1.5 * omega * 0.5 * (1 - std::pow(c, e)) / std::sqrt(N); // sd <= range/2
    const auto emitted = Energy(out, "EnergyEmitted");
    EXPECT_NEAR(emitted[0], power, 5 * se);
    EXPECT_NEAR(emitted[1] / emitted[0], 0.5, 1e-6); // colour x intensity
    EXPECT_NEAR(emitted[2] / emitted[0], 0.25, 1e-6);
    EXPECT_EQ(Field(out, "PhotonsMissed"), 0);
  }
  // Spot outside the box whose 5-degree cone lies inside the box's face: the sampled cap is the
  // spot cone (narrower than the box's), every photon enters, full spot power.
  {
    vtkNew<vtkPhotonTracer> tracer;
    tracer->SetNumberOfPhotons(N);
    const double e = 10, cone = 5;
    tracer->AddLight(Positional({ 0.45, 0.35, -2 }, { 0.45, 0.35, 0 }, cone, e, 4.0));
    auto out = Trace(tracer, medium);
    const double c = std::cos(vtkMath::RadiansFromDegrees(cone));
    const double power = 4.0 * 2 * vtkMath::Pi() * (1 - std::pow(c, e + 1)) / (e + 1);
    const double omega = 2 * vtkMath::Pi() * (1 - c);
    const double se = 4.0 * omega * 0.5 * (1 - std::pow(c, e)) / std::sqrt(N);
    EXPECT_NEAR(Field(out, "EnergyEmitted"), power, 5 * se);
    EXPECT_EQ(Field(out, "PhotonsMissed"), 0);
  }
  // Oblique directional light: E times the box's projected area.
  {
    vtkNew<vtkPhotonTracer> tracer;
    tracer->SetNumberOfPhotons(N);
    double d[3] = { 0.3, -0.5, 0.8 };
    vtkMath::Normalize(d);
    tracer->AddLight(Directional({ 0, 0, 0 }, { d[0], d[1], d[2] }, 3.0));
    auto out = Trace(tracer, medium);
    const double projected =
      std::abs(d[0]) * 0.8 * 0.6 + std::abs(d[1]) * 1.0 * 0.6 + std::abs(d[2]) * 1.0 * 0.8;
    // Rectangle area: from the photons, emitted + missed share the rectangle.
    const double photons = Field(out, "NumberOfPhotons");
    const double hit = photons - Field(out, "PhotonsMissed");
    const double rect = Field(out, "EnergyEmitted") / 3.0 * photons / hit;
    const double p = projected / rect;
    const double se = 3.0 * rect * std::sqrt(p * (1 - p) / N);
    EXPECT_NEAR(Field(out, "EnergyEmitted"), 3.0 * projected, 5 * se + 1e-9);
    // A switched-off light changes nothing.
    auto off = Directional({ 0, 0, 0 }, { 1, 0, 0 }, 5.0);
    off->SwitchOff();
    tracer->AddLight(off);
    auto out2 = Trace(tracer, medium);
    EXPECT_EQ(Field(out2, "EnergyEmitted"), Field(out, "EnergyEmitted"));
  }
  // A point light far along -z (1e3 to 1e9 away, I = E D^2) sends the box the power of a
  // directional light of irradiance E on its -z face, E 1.0 x 0.8, within the 1/d^2 variation
  // over the box (1 + 2 x 0.6 / D): photons started at the light's float position lost the box
  // in rounding beyond ~1e7 (nothing emitted; outside review).
  for (double D : { 1e3, 1e6, 1e8, 1e9 })
  {
    vtkNew<vtkPhotonTracer> tracer;
    tracer->SetNumberOfPhotons(N);
    const double E = 2.0;
    tracer->AddLight(Positional({ 0.45, 0.35, 0.25 - D }, { 0.45, 0.35, 0.25 }, 180, 1, E * D * D));
    auto out = Trace(tracer, medium);
    EXPECT_NEAR(Field(out, "EnergyEmitted") / (E * 1.0 * 0.8), 1.0, 2e-3 + 1.2 / D) << D;
  }
  // A point light at the centre: 4 pi I, every photon emitted.
  {
    vtkNew<vtkPhotonTracer> tracer;
    tracer->SetNumberOfPhotons(N);
    tracer->AddLight(Positional({ 0.45, 0.35, 0.25 }, { 0.45, 0.35, 1 }, 90, 1, 0.7));
    auto out = Trace(tracer, medium);
    EXPECT_NEAR(Field(out, "EnergyEmitted"), 0.7 * 4 * vtkMath::Pi(), 1e-5);
    EXPECT_EQ(Field(out, "PhotonsMissed"), 0);
  }
}

// The grid-local frame: moving the grid and its lights to 1e6 and rotating both by the direction
// matrix gives the same result (the host converts in double before anything becomes float).
TEST(PhotonTracer, GridLocalFrame)
{
  auto medium = FoggyLens();
  vtkNew<vtkPhotonTracer> tracer;
  tracer->SetNumberOfPhotons(1 << 14);
  AddThreeLights(tracer);
  auto reference = Trace(tracer, medium);

  auto moved = vtkSmartPointer<vtkImageData>::New();
  moved->DeepCopy(medium);
  const double o[3] = { 1e6, -2e6, 3e6 };
  moved->SetOrigin(o);
  // Rotation by 90 degrees about z: local x -> world y, local y -> world -x.
  const double R[9] = { 0, -1, 0, 1, 0, 0, 0, 0, 1 };
  moved->SetDirectionMatrix(R);
  auto toWorld = [&](std::array<double, 3> p)
  {
    return std::array<double, 3>{ o[0] + R[0] * p[0] + R[1] * p[1] + R[2] * p[2],
      o[1] + R[3] * p[0] + R[4] * p[1] + R[5] * p[2],
      o[2] + R[6] * p[0] + R[7] * p[1] + R[8] * p[2] };
  };
  vtkNew<vtkPhotonTracer> movedTracer;
  movedTracer->SetNumberOfPhotons(1 << 14);
  vtkLight* light;
  vtkCollectionSimpleIterator it;
  vtkLightCollection* lights = tracer->GetLights();
  for (lights->InitTraversal(it); (light = lights->GetNextLight(it));)
  {
    vtkNew<vtkLight> copy;
    copy->DeepCopy(light);
    double p[3], f[3];
    light->GetPosition(p);
    light->GetFocalPoint(f);
    copy->SetPosition(toWorld({ p[0], p[1], p[2] }).data());
    copy->SetFocalPoint(toWorld({ f[0], f[1], f[2] }).data());
    movedTracer->AddLight(copy);
  }
  auto out = Trace(movedTracer, moved);
  const float* a = Radiance(reference);
  const float* b = Radiance(out);
  double total = 0, diff = 0;
  for (vtkIdType v = 0; v < 3 * out->GetNumberOfPoints(); ++v)
  {
    total += a[v];
    diff += std::abs(a[v] - b[v]);
  }
  EXPECT_GT(total, 0);
  EXPECT_LT(diff / total, 1e-4);
  const double* bounds = out->GetBounds();
  EXPECT_GT(bounds[0], 0.9e6); // the output lives on the moved grid
}

namespace
{
// Brute force octree: for each level from the coarsest, the range of n over the node's voxels
// and their 3x3x3 neighbourhoods.
std::vector<unsigned char> CpuOctree(
  const std::vector<float>& n, const int d[3], float eps, float eps2)
{
  auto at = [&](int i, int j, int k)
  {
    i = std::clamp(i, 0, d[0] - 1);
    j = std::clamp(j, 0, d[1] - 1);
    k = std::clamp(k, 0, d[2] - 1);
    return n[i + d[0] * (j + d[1] * k)];
  };
  int levels = 1;
  while ((1 << (levels - 1)) < std::max({ d[0], d[1], d[2] }))
  {
    ++levels;
  }
  std::vector<unsigned char> out(n.size());
  for (int k = 0; k < d[2]; ++k)
    for (int j = 0; j < d[1]; ++j)
      for (int i = 0; i < d[0]; ++i)
      {
        unsigned char label = 0;
        for (int L = levels - 1; L >= 0; --L)
        {
          const int size = 1 << L;
          const int i0 = (i >> L) << L, j0 = (j >> L) << L, k0 = (k >> L) << L;
          float lo = std::numeric_limits<float>::infinity(), hi = -lo;
          for (int kk = k0 - 1; kk <= std::min(k0 + size, d[2]); ++kk)
            for (int jj = j0 - 1; jj <= std::min(j0 + size, d[1]); ++jj)
              for (int ii = i0 - 1; ii <= std::min(i0 + size, d[0]); ++ii)
              {
                lo = std::min(lo, at(ii, jj, kk));
                hi = std::max(hi, at(ii, jj, kk));
              }
          if (hi - lo < eps)
          {
            label = static_cast<unsigned char>(L);
            break;
          }
          if (hi - lo < eps2)
          {
            label = static_cast<unsigned char>(L | 0x80);
            break;
          }
        }
        out[i + d[0] * (j + d[1] * k)] = label;
      }
  return out;
}
}

// The device octree equals the brute-force one on a grid that is neither cubic nor a power of 2.
TEST(PhotonTracer, OctreeMatchesBruteForce)
{
  const int d[3] = { 37, 20, 9 };
  auto medium = MakeMedium(d[0], d[1], d[2], 0.1,
    [](double x, double y, double z)
    {
      Voxel v;
      v.N = 1.0;
      if (x > 2.0 && y < 1.0)
        v.N = 1.3; // a sharp block
      if (x < 1.2 && z > 0.4)
        v.N = 1.004 + 0.004 * std::sin(9 * x + 4 * y); // variation between eps and eps'
      if (x > 1.3 && x < 1.9 && y > 1.2)
        v.N = 1.1 + 0.05 * y; // a gradient
      return v;
    });
  vtkNew<vtkPhotonTracer> tracer;
  tracer->SetPrimaryTolerance(0.005);
  tracer->SetSecondaryTolerance(0.02);
  vtkNew<vtkImageData> octree;
  ASSERT_TRUE(tracer->BuildOctree(medium, octree));
  auto* level = vtkUnsignedCharArray::SafeDownCast(octree->GetPointData()->GetArray("OctreeLevel"));
  auto* limited =
    vtkUnsignedCharArray::SafeDownCast(octree->GetPointData()->GetArray("OctreeStepLimited"));
  ASSERT_NE(level, nullptr);
  ASSERT_NE(limited, nullptr);
  std::vector<float> n(level->GetNumberOfTuples());
  vtkDataArray* nArray = medium->GetPointData()->GetArray("RefractiveIndex");
  for (size_t v = 0; v < n.size(); ++v)
  {
    n[v] = static_cast<float>(nArray->GetComponent(static_cast<vtkIdType>(v), 0));
  }
  const auto expected = CpuOctree(n, d, 0.005f, 0.02f);
  int mismatches = 0, limitedCount = 0, coarse = 0;
  for (size_t v = 0; v < n.size(); ++v)
  {
    const int l = level->GetValue(static_cast<vtkIdType>(v));
    const int lim = limited->GetValue(static_cast<vtkIdType>(v));
    mismatches += (l != (expected[v] & 0x1f)) || (lim != ((expected[v] & 0x80) ? 1 : 0));
    limitedCount += lim;
    coarse += l >= 2;
  }
  EXPECT_EQ(mismatches, 0);
  EXPECT_GT(limitedCount, 0); // the secondary tolerance is exercised
  EXPECT_GT(coarse, 100);     // and so are large nodes
}

// Without RefractiveIndexGradient the tracer computes it on the device by central differences:
// a medium carrying the same differences explicitly gives the same result.
TEST(PhotonTracer, GradientDefaultsToCentralDifferences)
{
  auto medium = FoggyLens();
  auto withGradient = vtkSmartPointer<vtkImageData>::New();
  withGradient->DeepCopy(medium);
  int d[3];
  medium->GetDimensions(d);
  const double s = medium->GetSpacing()[0];
  vtkDataArray* n = medium->GetPointData()->GetArray("RefractiveIndex");
  vtkNew<vtkFloatArray> g;
  g->SetName("RefractiveIndexGradient");
  g->SetNumberOfComponents(3);
  g->SetNumberOfTuples(n->GetNumberOfTuples());
  auto at = [&](int i, int j, int k)
  { return static_cast<float>(n->GetComponent(i + d[0] * (j + d[1] * k), 0)); };
  for (int k = 0; k < d[2]; ++k)
    for (int j = 0; j < d[1]; ++j)
      for (int i = 0; i < d[0]; ++i)
      {
        const int c[3] = { i, j, k };
        float grad[3];
        for (int a = 0; a < 3; ++a)
        {
          int lo[3] = { i, j, k }, hi[3] = { i, j, k };
          lo[a] = std::max(c[a] - 1, 0);
          hi[a] = std::min(c[a] + 1, d[a] - 1);
          grad[a] = (at(hi[0], hi[1], hi[2]) - at(lo[0], lo[1], lo[2])) /
            static_cast<float>((hi[a] - lo[a]) * s);
        }
        g->SetTypedTuple(i + d[0] * (j + d[1] * k), grad);
      }
  withGradient->GetPointData()->AddArray(g);
  vtkNew<vtkPhotonTracer> tracer;
  AddThreeLights(tracer);
  tracer->SetNumberOfPhotons(1 << 14);
  auto a = Trace(tracer, medium);
  EXPECT_TRUE(tracer->GetComputedGradient());
  auto b = Trace(tracer, withGradient);
  EXPECT_FALSE(tracer->GetComputedGradient());
  const float* ra = Radiance(a);
  const float* rb = Radiance(b);
  double total = 0, diff = 0;
  for (vtkIdType v = 0; v < 3 * a->GetNumberOfPoints(); ++v)
  {
    total += ra[v];
    diff += std::abs(ra[v] - rb[v]);
  }
  EXPECT_LT(diff / total, 1e-3);
}

// Only the work needed: no curved rays, octree or deposits where the medium does not call for
// them; a medium with nothing that scatters gives zero radiance but still closes its books.
TEST(PhotonTracer, VariantsFollowTheMedium)
{
  auto absorbing = MakeMedium(8, 8, 8, 0.1,
    [](double, double, double)
    {
      Voxel v;
      v.Extinction = { 1, 1, 1 };
      return v;
    });
  vtkNew<vtkPhotonTracer> tracer;
  tracer->SetNumberOfPhotons(1 << 12);
  tracer->AddLight(Directional({ 0, 0, -5 }, { 0, 0, 0 }, 1));
  auto out = Trace(tracer, absorbing);
  EXPECT_FALSE(tracer->GetUsedCurvedRays());
  EXPECT_FALSE(tracer->GetUsedOctree());
  EXPECT_FALSE(tracer->GetUsedDeposit());
  EXPECT_TRUE(tracer->GetUsedExtinction());
  EXPECT_EQ(Field(out, "TotalSteps"), Field(out, "PhotonsMarched")); // one straight step each
  EXPECT_EQ(Sum(Energy(out, "EnergyScattered")), 0);
  EXPECT_NEAR(Sum(Energy(out, "EnergyAbsorbed")) + Sum(Energy(out, "EnergyEscaped")),
    Sum(Energy(out, "EnergyEmitted")), 1e-5);
  EXPECT_NEAR(
    Sum(Energy(out, "EnergyEscaped")) / Sum(Energy(out, "EnergyEmitted")), std::exp(-0.8), 1e-3);
  const float* rad = Radiance(out);
  EXPECT_EQ(*std::max_element(rad, rad + 3 * out->GetNumberOfPoints()), 0.0f);

  // n jumps in a ball (1.5 inside) in a haze. Without a gradient array the tracer computes one by
  // central differences: curved steps. With a given gradient of zero (what the voxelizer writes
  // with exact interfaces, whose surfaces carry the jump) nothing bends: straight runs.
  auto jump = [](bool zeroGradient)
  {
    auto medium = MakeMedium(12, 12, 12, 0.1,
      [](double x, double y, double z)
      {
        Voxel v;
        v.N = (x - 0.55) * (x - 0.55) + (y - 0.55) * (y - 0.55) + (z - 0.55) * (z - 0.55) < 0.09
          ? 1.5
          : 1.0;
        v.Extinction = { 0.5, 0.5, 0.5 };
        v.Albedo = { 0.5, 0.5, 0.5 };
        return v;
      });
    if (zeroGradient)
    {
      vtkNew<vtkFloatArray> gradient;
      gradient->SetName(vtkRefractaMedium::RefractiveIndexGradientName());
      gradient->SetNumberOfComponents(3);
      gradient->SetNumberOfTuples(medium->GetNumberOfPoints());
      gradient->Fill(0.0);
      medium->GetPointData()->AddArray(gradient);
    }
    return medium;
  };
  for (bool zeroGradient : { false, true })
  {
    out = Trace(tracer, jump(zeroGradient));
    EXPECT_EQ(tracer->GetUsedCurvedRays(), !zeroGradient);
    EXPECT_EQ(tracer->GetComputedGradient(), !zeroGradient);
    EXPECT_NEAR(Sum(Energy(out, "EnergyAbsorbed")) + Sum(Energy(out, "EnergyEscaped")) +
        Sum(Energy(out, "EnergyScattered")) + Sum(Energy(out, "EnergyRemaining")),
      Sum(Energy(out, "EnergyEmitted")), 1e-4 * Sum(Energy(out, "EnergyEmitted")));
  }
}

// Bad input: an error naming the problem, RequestData fails, the output is empty.
TEST(PhotonTracer, RejectsBadInput)
{
  vtkNew<vtkTest::ErrorObserver> observer;
  vtkNew<vtkPhotonTracer> tracer;
  tracer->AddObserver(vtkCommand::ErrorEvent, observer);
  tracer->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, observer);
  tracer->AddLight(Directional({ 0, 0, -5 }, { 0, 0, 0 }, 1));
  // An image that is not a medium.
  vtkNew<vtkImageData> notMedium;
  notMedium->SetDimensions(4, 4, 4);
  notMedium->AllocateScalars(VTK_FLOAT, 1);
  tracer->SetInputData(notMedium);
  tracer->Update();
  EXPECT_TRUE(observer->GetError());
  EXPECT_NE(observer->GetErrorMessage().find("not a valid Refracta medium"), std::string::npos);
  EXPECT_EQ(tracer->GetOutput()->GetNumberOfPoints(), 0);
  observer->Clear();
  // A light at NaN.
  auto medium = Haze(4, 4, 4, 0.1);
  tracer->SetInputData(medium);
  tracer->AddLight(Positional({ std::nan(""), 0, 0 }, { 0, 0, 0 }, 180, 1, 1));
  tracer->Update();
  EXPECT_TRUE(observer->GetError());
  EXPECT_NE(observer->GetErrorMessage().find("Light 1"), std::string::npos);
  EXPECT_EQ(tracer->GetOutput()->GetNumberOfPoints(), 0);
  observer->Clear();
  // A spot without a direction.
  tracer->RemoveAllLights();
  tracer->AddLight(Positional({ 1, 1, 1 }, { 1, 1, 1 }, 30, 1, 1));
  tracer->Update();
  EXPECT_TRUE(observer->GetError());
  EXPECT_NE(observer->GetErrorMessage().find("focal point"), std::string::npos);
  EXPECT_EQ(tracer->GetOutput()->GetNumberOfPoints(), 0);
  observer->Clear();
  // A NaN setting is refused by its setter, which keeps the value (vtkSetClampMacro kept NaN).
  tracer->SetSmoothingBias(0.01);
  tracer->SetSmoothingBias(std::nan(""));
  EXPECT_NE(observer->GetErrorMessage().find("SetSmoothingBias(nan)"), std::string::npos);
  EXPECT_EQ(tracer->GetSmoothingBias(), 0.01);
  observer->Clear();
  tracer->SetMinimumStep(std::nan(""));
  EXPECT_NE(observer->GetErrorMessage().find("SetMinimumStep(nan)"), std::string::npos);
  EXPECT_TRUE(std::isfinite(tracer->GetMinimumStep()));
  observer->Clear();
  // No light at all is not an error: darkness.
  tracer->RemoveAllLights();
  tracer->Update();
  EXPECT_FALSE(observer->GetError());
  EXPECT_EQ(tracer->GetOutput()->GetNumberOfPoints(), 64);
  EXPECT_EQ(Field(tracer->GetOutput(), "EnergyEmitted"), 0);
}

// Photons start on the proxy box (the voxels that differ from empty space) instead of the whole
// medium: same physics, fewer wasted photons. A 0.4 x 0.4 x 0.4 absorbing block in a 3.2-wide
// empty grid, lit along z: both runs must give the analytic absorbed power
// E A (1 - exp(-sigma L)) within 1% (straight parallel rays: the only error is the lateral
// sampling of the block's face, ~0.1% with these counts), and the proxy walks fewer voxels.
TEST(PhotonTracer, ProxyBoundsGiveTheSameAnswer)
{
  const double s = 0.1;
  auto medium = MakeMedium(32, 32, 32, s,
    [&](double x, double y, double z)
    {
      Voxel v;
      const bool inBlock =
        std::abs(x - 1.55) < 0.2 && std::abs(y - 1.55) < 0.2 && std::abs(z - 1.55) < 0.2;
      v.Extinction = inBlock ? std::array<double, 3>{ 2, 2, 2 } : std::array<double, 3>{ 0, 0, 0 };
      return v;
    });
  double absorbed[2], missed[2]; // missed: voxel pieces walked
  for (int proxy = 0; proxy < 2; ++proxy)
  {
    vtkNew<vtkPhotonTracer> tracer;
    tracer->SetUseProxyBounds(proxy == 1);
    tracer->SetNumberOfPhotons(1 << 15);
    tracer->AddLight(Directional({ 1.55, 1.55, -5 }, { 1.55, 1.55, 0 }, 1.0));
    auto out = Trace(tracer, medium);
    absorbed[proxy] = Field(out, "EnergyAbsorbed");
    missed[proxy] = Field(out, "TotalVoxelPieces");
  }
  // The block covers voxels 14..17 (4 voxels, 0.4 wide) on each axis; sigma_t is sampled
  // trilinearly, so the absorbing region is the block's voxel boxes blurred by one voxel: the
  // analytic reference integrates the trilinear profile along z per (x, y) footprint.
  // Straight rays along z at lateral position (x, y): optical depth = 2 * integral of the
  // trilinear tent product; computed here by fine quadrature.
  auto tent = [&](double u) { // 1D interpolated indicator of voxels 14..17 at voxel coordinate u
    const double c = std::clamp(u, 0.0, 31.0);
    const int i0 = static_cast<int>(std::floor(c));
    const double f = c - i0;
    auto ind = [](int i) { return (i >= 14 && i <= 17) ? 1.0 : 0.0; };
    return (1 - f) * ind(i0) + f * ind(std::min(i0 + 1, 31));
  };
  double expected = 0;
  const int q = 400;
  for (int a = 0; a < q; ++a)
  {
    for (int b = 0; b < q; ++b)
    {
      const double u = 12.0 + 8.0 * (a + 0.5) / q, w = 12.0 + 8.0 * (b + 0.5) / q;
      double tau = 0;
      for (int k = 0; k < 80; ++k)
      {
        tau += 2.0 * tent(u) * tent(w) * tent(12.0 + 8.0 * (k + 0.5) / 80) * (8.0 / 80) * s;
      }
      expected += (1 - std::exp(-tau)) * (8.0 * s / q) * (8.0 * s / q);
    }
  }
  for (int proxy = 0; proxy < 2; ++proxy)
  {
    EXPECT_NEAR(absorbed[proxy], expected, 0.01 * expected) << "proxy " << proxy;
  }
  // With the proxy every photon starts at the block's neighbourhood (0.8 wide instead of 3.2,
  // so 16x more of them cross the block) and skips the empty voxels in front: 20 voxels walked
  // per photon instead of 32.
  EXPECT_LT(missed[1], 0.7 * missed[0]);
}

// Extended lights have the fields of their analytic sources. In a faint haze the deposit is
// sigma_s times the fluence phi = integral of L over directions:
// - a disc at infinity of angular radius delta with irradiance E on a facing plane has radiance
//   E / (pi sin^2 delta) over a cone of 2 pi (1 - cos delta): phi = 2 E / (1 + cos delta)
//   (1.0718 E at 30 degrees instead of E), and the mean travel direction has length
//   (1 + cos delta) / 2 (0.933 instead of 1);
// - a sphere of radius r with intensity I, seen from distance d (sin a = r / d), has radiance
//   I / (pi r^2) over 2 pi (1 - cos a): phi = 2 I (1 - cos a) / r^2 instead of I / d^2.
TEST(PhotonTracer, ExtendedLightsHaveTheirAnalyticFields)
{
  const double s = 0.05, sigma = 1e-4;
  auto medium = MakeMedium(8, 8, 8, s,
    [&](double, double, double)
    {
      Voxel v;
      v.Extinction = { sigma, sigma, sigma };
      v.Albedo = { 1, 1, 1 };
      return v;
    });
  const int voxels = 512;
  {
    const double E = 1.5, delta = 30.0;
    vtkNew<vtkPhotonTracer> tracer;
    tracer->SmoothingOff();
    tracer->SetNumberOfPhotons(1 << 18);
    tracer->SetDirectionalLightAngularRadius(delta);
    tracer->AddLight(Directional({ 0.175, 0.175, -5 }, { 0.175, 0.175, 0 }, E));
    auto out = Trace(tracer, medium);
    const float* rad = Radiance(out);
    double fluence = 0;
    for (int v = 0; v < voxels; ++v)
    {
      fluence += rad[3 * v] / sigma / voxels;
    }
    const double c = std::cos(vtkMath::RadiansFromDegrees(delta));
    EXPECT_NEAR(fluence, 2 * E / (1 + c), 0.01 * E);
  }
  {
    // Sphere centred 0.22 in front of the -z face's centre; radius 0.2 (sin a = 0.9 at the face).
    const double I = 2.0, r = 0.2;
    const std::array<double, 3> at{ 0.175, 0.175, -0.025 - 0.22 };
    double fluence[2] = { 0, 0 }, expected[2] = { 0, 0 };
    for (int extended = 0; extended < 2; ++extended)
    {
      vtkNew<vtkPhotonTracer> tracer;
      tracer->SmoothingOff();
      tracer->SetNumberOfPhotons(1 << 19);
      tracer->SetLightRadius(extended ? r : 0.0);
      tracer->AddLight(Positional(at, { 0.175, 0.175, 0 }, 180, 1, I));
      auto out = Trace(tracer, medium);
      const float* rad = Radiance(out);
      for (int k = 0; k < 8; ++k)
      {
        for (int j = 0; j < 8; ++j)
        {
          for (int i = 0; i < 8; ++i)
          {
            const int v = i + 8 * (j + 8 * k);
            fluence[extended] += rad[3 * v] / sigma;
            const double dx = i * s - at[0], dy = j * s - at[1], dz = k * s - at[2];
            const double d2 = dx * dx + dy * dy + dz * dz;
            const double sinA2 = r * r / d2;
            expected[extended] +=
              extended ? 2 * I * (sinA2 / (1 + std::sqrt(1 - sinA2))) / (r * r) : I / d2;
          }
        }
      }
    }
    // The voxel average of 1/d^2 differs from its centre value by up to ~1% here; the ratio of
    // the two runs cancels most of that. The random start points on the sphere's disc leave
    // about 0.3% of noise on the sum.
    EXPECT_NEAR(fluence[1] / fluence[0], expected[1] / expected[0], 0.01);
    EXPECT_GT(expected[1] / expected[0], 1.05); // the extent does matter at these distances
  }
  // Extents are clamped to their valid ranges (radius >= 0, angular radius in [0, 45] degrees).
  vtkNew<vtkPhotonTracer> tracer;
  tracer->SetLightRadius(-1.0);
  tracer->SetDirectionalLightAngularRadius(90.0);
  EXPECT_EQ(tracer->GetLightRadius(), 0.0);
  EXPECT_EQ(tracer->GetDirectionalLightAngularRadius(), 45.0);
}
