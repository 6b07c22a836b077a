// Tests of vtkPhotonDiffusionSchedule: the photon marching in chunks of k steps interleaved with
// the Lattice-Boltzmann diffusion gives the same result as marching everything and then
// diffusing. Asserted, for a straight-ray medium and a curved-ray one (a sphere of higher index):
// - the chunked marching deposits exactly what the unchunked marching deposits (curved rays:
//   Radiance equal to the bit, same steps and fixed-point sums; straight rays, walked in
//   one-voxel segments when chunked: equal to 1e-5) and closes the same energy books;
// - the interleaved schedule really interleaves (more than one chunk, diffusion steps during the
//   marching);
// - MultipleScattering agrees between the two schedules within 1e-3 of its maximum (both solved
//   to a per-step relative change of 1e-7; the lattice's fixed point depends only on the final
//   source), for k = 4 and 16.
#include "PhotonTestUtilities.h"
#include "vtkLatticeBoltzmannLighting.h"
#include "vtkLatticeBoltzmannSolver.h"
#include "vtkPhotonDiffusionSchedule.h"
#include "vtkPhotonTracer.h"
#include "vtkRefractaLightingVolume.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

using namespace photontest;

namespace
{
vtkSmartPointer<vtkImageData> RunSchedule(vtkImageData* medium, int mode, int k)
{
  vtkNew<vtkPhotonDiffusionSchedule> schedule;
  schedule->SetInputData(medium);
  schedule->SetMode(mode);
  schedule->SetStepsPerChunk(k);
  vtkPhotonTracer* tracer = schedule->GetPhotonTracer();
  tracer->AddLight(Directional({ -100, 3, 5 }, { 0, 3, 5 }, 1.0, { 1.0, 0.8, 0.6 }));
  tracer->SetNumberOfPhotons(4096);
  tracer->SetAdaptiveStepping(false);
  tracer->SetFixedStep(1.0);
  vtkLatticeBoltzmannSolver* solver = schedule->GetSolver();
  solver->SetTolerance(1e-7);
  solver->SetMaximumIterations(20000);
  schedule->Update();
  auto result = vtkSmartPointer<vtkImageData>::New();
  result->ShallowCopy(schedule->GetOutput());
  return result;
}

// A homogeneous scattering medium of nx x ny x nz half-unit voxels.
vtkSmartPointer<vtkImageData> Fog(int nx, int ny, int nz, const std::array<double, 3>& albedo)
{
  return MakeMedium(nx, ny, nz, 0.5,
    [&](double, double, double)
    {
      Voxel v;
      v.Extinction = { 1.2, 1.0, 0.8 };
      v.Albedo = albedo;
      return v;
    });
}

// One directional light from -x towards (0, aim, aim), its source at height lightY (moving it
// slants the beam), `photons` photons, the lattice solved to `tolerance`.
void AimLight(
  vtkPhotonDiffusionSchedule* schedule, double lightY, double aim, int photons, double tolerance)
{
  vtkPhotonTracer* tracer = schedule->GetPhotonTracer();
  tracer->RemoveAllLights();
  tracer->AddLight(Directional({ -100, lightY, aim }, { 0, aim, aim }, 1.0, { 1.0, 0.8, 0.6 }));
  tracer->SetNumberOfPhotons(photons);
  schedule->GetSolver()->SetTolerance(tolerance);
  schedule->GetSolver()->SetMaximumIterations(20000);
}

// The largest difference between two arrays of the same shape, over the largest magnitude of `b`
// (peak returned in `peak`).
double LargestDifference(vtkDataArray* a, vtkDataArray* b, double& peak)
{
  peak = 0;
  double largest = 0;
  const int n = b->GetNumberOfComponents();
  for (vtkIdType t = 0; t < b->GetNumberOfTuples(); ++t)
  {
    for (int c = 0; c < n; ++c)
    {
      peak = std::max(peak, std::fabs(b->GetComponent(t, c)));
      largest = std::max(largest, std::fabs(a->GetComponent(t, c) - b->GetComponent(t, c)));
    }
  }
  return largest;
}
}

TEST(PhotonDiffusionSchedule, InterleavedMatchesSequential)
{
  const double h = 0.5;
  for (bool curved : { false, true })
  {
    vtkSmartPointer<vtkImageData> medium = MakeMedium(20, 14, 16, h,
      [&](double x, double y, double z)
      {
        Voxel v;
        const double r2 = (x - 5) * (x - 5) + (y - 3.25) * (y - 3.25) + (z - 3.75) * (z - 3.75);
        v.N = curved && r2 < 6.0 ? 1.3 : 1.0;
        v.Extinction = { 1.2, 1.0, 0.8 };
        v.Albedo = { 0.9, 0.95, 0.99 };
        return v;
      });
    vtkSmartPointer<vtkImageData> sequential =
      RunSchedule(medium, vtkPhotonDiffusionSchedule::SEQUENTIAL, 16);
    ASSERT_GT(sequential->GetNumberOfPoints(), 0);
    const vtkIdType n = sequential->GetNumberOfPoints();
    vtkDataArray* msSeq =
      sequential->GetPointData()->GetArray(vtkRefractaLightingVolume::MultipleScatteringName());
    vtkDataArray* radSeq =
      sequential->GetPointData()->GetArray(vtkRefractaLightingVolume::RadianceName());
    ASSERT_TRUE(msSeq && radSeq);
    double peak = 0;
    for (vtkIdType t = 0; t < n; ++t)
    {
      for (int c = 0; c < 3; ++c)
      {
        peak = std::max(peak, msSeq->GetComponent(t, c));
      }
    }
    ASSERT_GT(peak, 0);
    for (int k : { 4, 16 })
    {
      vtkSmartPointer<vtkImageData> interleaved =
        RunSchedule(medium, vtkPhotonDiffusionSchedule::INTERLEAVED, k);
      ASSERT_EQ(interleaved->GetNumberOfPoints(), n);
      vtkDataArray* msInt =
        interleaved->GetPointData()->GetArray(vtkRefractaLightingVolume::MultipleScatteringName());
      vtkDataArray* radInt =
        interleaved->GetPointData()->GetArray(vtkRefractaLightingVolume::RadianceName());
      ASSERT_TRUE(msInt && radInt);
      double radDiff = 0, msDiff = 0;
      for (vtkIdType t = 0; t < n; ++t)
      {
        for (int c = 0; c < 3; ++c)
        {
          radDiff =
            std::max(radDiff, std::abs(radInt->GetComponent(t, c) - radSeq->GetComponent(t, c)));
          msDiff =
            std::max(msDiff, std::abs(msInt->GetComponent(t, c) - msSeq->GetComponent(t, c)));
        }
      }
      const auto eSeq = Energy(sequential, "EnergyScattered");
      const auto eInt = Energy(interleaved, "EnergyScattered");
      const double chunks = Field(interleaved, "ScheduleChunks");
      const double during = Field(interleaved, "ScheduleDiffusionStepsDuringMarching");
      std::printf("%s rays, k = %d: %g chunks, %g lattice steps during marching, LBL steps "
                  "sequential %g / interleaved %g; max |Radiance diff| %.3g; max |S_ms diff| / "
                  "max S_ms = %.3e; time sequential %.3f s, interleaved %.3f s\n",
        curved ? "curved" : "straight", k, chunks, during,
        Field(sequential, "LatticeBoltzmannIterations"),
        Field(interleaved, "LatticeBoltzmannIterations"), radDiff, msDiff / peak,
        Field(sequential, "ScheduleTotalSeconds"), Field(interleaved, "ScheduleTotalSeconds"));
      double radPeak = 0;
      for (vtkIdType t = 0; t < n; ++t)
      {
        radPeak = std::max(radPeak, radSeq->GetComponent(t, 0));
      }
      if (curved)
      {
        // Same steps in the same order: the same fixed-point sums, to the bit.
        EXPECT_EQ(radDiff, 0.0);
        for (int c = 0; c < 3; ++c)
        {
          EXPECT_EQ(eSeq[c], eInt[c]);
        }
      }
      else
      {
        // A straight ray is one chord unchunked and k one-voxel segments chunked: the voxel walk
        // rounds differently (float), nothing else changes.
        EXPECT_LT(radDiff, 1e-5 * radPeak);
        for (int c = 0; c < 3; ++c)
        {
          EXPECT_NEAR(eSeq[c], eInt[c], 1e-5 * eSeq[c]);
        }
      }
      EXPECT_GT(chunks, 1);
      EXPECT_GT(during, 0);
      EXPECT_EQ(Field(interleaved, "LatticeBoltzmannConverged"), 1);
      EXPECT_LT(msDiff / peak, 1e-3);
    }
  }
}

// A light move on an unchanged medium restarts the solver instead of validating the medium and
// uploading its coefficients again, and gives exactly what a fresh schedule gives for the moved
// light; a modified medium is set up again.
TEST(PhotonDiffusionSchedule, LightMoveReusesTheMediumOnTheDevice)
{
  vtkSmartPointer<vtkImageData> medium = Fog(12, 10, 8, { 0.7, 0.75, 0.8 });
  auto configure = [](vtkPhotonDiffusionSchedule* schedule, double lightY)
  { AimLight(schedule, lightY, 2.0, 2048, 1e-5); };
  vtkNew<vtkPhotonDiffusionSchedule> persistent;
  persistent->SetInputData(medium);
  configure(persistent, 2.0);
  persistent->Update();
  configure(persistent, 40.0);
  persistent->Update();
  EXPECT_EQ(persistent->GetNumberOfSolverInitializations(), 1);

  vtkNew<vtkPhotonDiffusionSchedule> fresh;
  fresh->SetInputData(medium);
  configure(fresh, 40.0);
  fresh->Update();
  const char* name = vtkRefractaLightingVolume::MultipleScatteringName();
  vtkDataArray* a = persistent->GetOutput()->GetPointData()->GetArray(name);
  vtkDataArray* b = fresh->GetOutput()->GetPointData()->GetArray(name);
  ASSERT_TRUE(a && b);
  ASSERT_EQ(a->GetNumberOfTuples(), b->GetNumberOfTuples());
  double peak = 0;
  for (vtkIdType t = 0; t < a->GetNumberOfTuples(); ++t)
  {
    for (int c = 0; c < 3; ++c)
    {
      EXPECT_EQ(a->GetComponent(t, c), b->GetComponent(t, c)) << t;
      peak = std::max(peak, a->GetComponent(t, c));
    }
  }
  EXPECT_GT(peak, 0);
  EXPECT_EQ(Field(persistent->GetOutput(), "LatticeBoltzmannIterations"),
    Field(fresh->GetOutput(), "LatticeBoltzmannIterations"));

  medium->Modified();
  persistent->Update();
  EXPECT_EQ(persistent->GetNumberOfSolverInitializations(), 2);
}

// WarmStart: a light move iterates the lattice on from the last field. Asserted against a cold
// solve of the same light on the same photons (same seed): MultipleScattering within 2e-3 of its
// maximum (both to a per-check relative change of 1e-6: each stops within about tolerance /
// (1 - contraction) of the fixed point), in fewer lattice steps; the first run and the run after a
// medium change are cold; the field data says which run was warm.
TEST(PhotonDiffusionSchedule, WarmStartAgreesWithColdInFewerSteps)
{
  vtkSmartPointer<vtkImageData> medium = Fog(16, 12, 12, { 0.9, 0.95, 0.99 });
  auto configure = [](vtkPhotonDiffusionSchedule* schedule, double lightY)
  { AimLight(schedule, lightY, 3.0, 4096, 1e-6); };
  vtkNew<vtkPhotonDiffusionSchedule> warm;
  warm->SetInputData(medium);
  warm->WarmStartOn();
  configure(warm, 3.0);
  warm->Update();
  EXPECT_FALSE(warm->GetLastRunWarm()) << "nothing to start from on the first run";
  configure(warm, 20.0); // the light moves: the beam enters higher and slanted
  warm->Update();
  ASSERT_TRUE(warm->GetLastRunWarm());
  EXPECT_EQ(Field(warm->GetOutput(), "ScheduleWarmStart"), 1.0);
  EXPECT_EQ(warm->GetNumberOfSolverInitializations(), 1);

  vtkNew<vtkPhotonDiffusionSchedule> cold;
  cold->SetInputData(medium);
  configure(cold, 20.0);
  cold->Update();
  EXPECT_EQ(Field(cold->GetOutput(), "ScheduleWarmStart"), 0.0);
  const double warmSteps = Field(warm->GetOutput(), "LatticeBoltzmannIterations");
  const double coldSteps = Field(cold->GetOutput(), "LatticeBoltzmannIterations");
  EXPECT_EQ(Field(warm->GetOutput(), "LatticeBoltzmannConverged"), 1.0);
  EXPECT_LT(warmSteps, coldSteps);
  std::printf("lattice steps: warm %g, cold %g\n", warmSteps, coldSteps);

  const char* name = vtkRefractaLightingVolume::MultipleScatteringName();
  vtkDataArray* a = warm->GetOutput()->GetPointData()->GetArray(name);
  vtkDataArray* b = cold->GetOutput()->GetPointData()->GetArray(name);
  ASSERT_TRUE(a && b);
  double peak = 0;
  const double largest = LargestDifference(a, b, peak);
  ASSERT_GT(peak, 0);
  EXPECT_LT(largest, 2e-3 * peak);
  std::printf("warm vs cold: largest difference %g of peak %g\n", largest, peak);

  medium->Modified();
  warm->Update();
  EXPECT_FALSE(warm->GetLastRunWarm()) << "a new medium starts cold";
}

// The first-collision split through the schedule (issue 14): asked to interleave, it runs
// sequentially (the chunks carry S1, not the handed-on source) and says so, and its
// MultipleScattering is vtkLatticeBoltzmannLighting's on the same photons (the two consumers of
// the split's source agree to the lattice's tolerance).
TEST(PhotonDiffusionSchedule, FirstCollisionSplitRunsSequentiallyLikeTheLightingFilter)
{
  vtkSmartPointer<vtkImageData> medium = Fog(10, 8, 8, { 0.9, 0.9, 0.9 });
  vtkNew<vtkPhotonDiffusionSchedule> schedule;
  schedule->SetInputData(medium);
  schedule->SetMode(vtkPhotonDiffusionSchedule::INTERLEAVED);
  AimLight(schedule, 3.0, 2.0, 4096, 1e-7);
  schedule->GetPhotonTracer()->SetScatteringOrders(2);
  schedule->Update();
  EXPECT_FALSE(schedule->GetLastRunInterleaved());
  EXPECT_EQ(schedule->GetPhotonTracer()->GetUsedScatteringOrders(), 2);

  vtkNew<vtkLatticeBoltzmannLighting> lighting;
  lighting->SetInputData(medium);
  lighting->SetLightingData(schedule->GetPhotonTracer()->GetOutput());
  lighting->SetTolerance(1e-7);
  lighting->SetMaximumIterations(20000);
  lighting->Update();
  const char* name = vtkRefractaLightingVolume::MultipleScatteringName();
  vtkDataArray* a = schedule->GetOutput()->GetPointData()->GetArray(name);
  vtkDataArray* b = lighting->GetOutput()->GetPointData()->GetArray(name);
  ASSERT_TRUE(a && b);
  double peak = 0;
  const double difference = LargestDifference(a, b, peak);
  ASSERT_GT(peak, 0.0);
  EXPECT_LT(difference, 1e-4 * peak);

  schedule->GetPhotonTracer()->SetScatteringOrders(0);
  schedule->Update();
  EXPECT_TRUE(schedule->GetLastRunInterleaved()) << "no split: interleaved as asked";
}
