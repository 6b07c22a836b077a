// Progress and abort of the transport passes (issue 12): ProgressEvent values are monotone, many
// and end at 1; an observer that calls AbortExecuteOn() at the first value above 0.2 makes
// Update() return within 0.5 s with an empty output; after AbortExecuteOff() the next Update()
// gives the full result. Photon batches and chunks do not change the photon pass's result. The
// light-ray pass (issue 15) does the same with both of its methods.
#include "PhotonTestUtilities.h"
#include "ProgressTestUtilities.h"

#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLatticeBoltzmannLighting.h"
#include "vtkLatticeBoltzmannSolver.h"
#include "vtkLightRaySingleScattering.h"
#include "vtkNew.h"
#include "vtkPhotonDiffusionSchedule.h"
#include "vtkPhotonTracer.h"
#include "vtkPointData.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <set>
#include <vector>

namespace
{
using refracta_test::Clock;
using refracta_test::ExpectGoodProgress;
using refracta_test::ProgressLog;

// Runs `filter` with an abort at the first progress above 0.2; returns the seconds from the abort
// to the return of Update().
double AbortedRun(vtkAlgorithm* filter, ProgressLog* log)
{
  log->Reset(0.2);
  const auto start = Clock::now();
  filter->Update();
  const auto end = Clock::now();
  EXPECT_TRUE(log->Aborted);
  const double latency = std::chrono::duration<double>(end - log->AbortTime).count();
  std::printf("aborted after %.3f s; Update() returned %.3f s after the abort\n",
    std::chrono::duration<double>(log->AbortTime - start).count(), latency);
  return latency;
}

// A glass ball (n = 1.3) in a thin scattering fog, lit by one directional light.
vtkSmartPointer<vtkImageData> FoggyBall(int n)
{
  const double c = 0.5 * (n - 1);
  const double r = 0.35 * n;
  return photontest::MakeMedium(n, n, n, 1.0,
    [=](double x, double y, double z)
    {
      photontest::Voxel v;
      const double d2 = (x - c) * (x - c) + (y - c) * (y - c) + (z - c) * (z - c);
      const bool inside = d2 < r * r;
      v.N = inside ? 1.3 : 1.0;
      const double s = inside ? 0.02 : 0.005;
      v.Extinction = { s, s, s };
      v.Albedo = { 0.8, 0.8, 0.8 };
      return v;
    });
}

vtkSmartPointer<vtkPhotonTracer> MakeTracer(vtkImageData* medium, int photons)
{
  auto tracer = vtkSmartPointer<vtkPhotonTracer>::New();
  tracer->SetInputData(medium);
  tracer->AddLight(photontest::Directional({ -100, 30, 20 }, { 0, 0, 0 }, 1.0));
  tracer->SetNumberOfPhotons(photons);
  return tracer;
}
}

TEST(PhotonTracerProgress, ProgressAndAbort)
{
  // 2^17 photons through 96^3: a full run takes ~6 s on the 2-core CPU (2^20 take ~45 s).
  const int Photons = 1 << 17;
  vtkSmartPointer<vtkImageData> medium = FoggyBall(96);
  vtkSmartPointer<vtkPhotonTracer> tracer = MakeTracer(medium, Photons);
  vtkNew<ProgressLog> log;
  tracer->AddObserver(vtkCommand::ProgressEvent, log);

  const double latency = AbortedRun(tracer, log);
  EXPECT_LT(latency, 0.5);
  EXPECT_TRUE(tracer->GetLastRunAborted());
  EXPECT_EQ(tracer->GetOutput()->GetNumberOfPoints(), 0);
  EXPECT_EQ(tracer->GetOutput()->GetPointData()->GetArray("Radiance"), nullptr);

  tracer->AbortExecuteOff();
  log->Reset(2.0);
  const auto start = Clock::now();
  tracer->Update();
  const double full = std::chrono::duration<double>(Clock::now() - start).count();
  std::printf("full run %.2f s (octree %.3f, generation %.3f, marching %.2f, smoothing %.3f), "
              "%d batches\n",
    full, tracer->GetOctreeSeconds(), tracer->GetGenerationSeconds(), tracer->GetMarchingSeconds(),
    tracer->GetSmoothingSeconds(), tracer->GetNumberOfBatches());
  EXPECT_FALSE(tracer->GetLastRunAborted());
  ExpectGoodProgress(log->Values, "photon tracer");
  vtkImageData* out = tracer->GetOutput();
  ASSERT_EQ(out->GetNumberOfPoints(), medium->GetNumberOfPoints());
  ASSERT_NE(out->GetPointData()->GetArray("Radiance"), nullptr);
  EXPECT_EQ(photontest::Field(out, "NumberOfPhotons"), Photons);
  EXPECT_EQ(
    photontest::Field(out, "PhotonsMarched") + photontest::Field(out, "PhotonsMissed"), Photons);
  const auto emitted = photontest::Energy(out, "EnergyEmitted");
  const auto absorbed = photontest::Energy(out, "EnergyAbsorbed");
  const auto escaped = photontest::Energy(out, "EnergyEscaped");
  const auto scattered = photontest::Energy(out, "EnergyScattered");
  const auto remaining = photontest::Energy(out, "EnergyRemaining");
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_GT(scattered[c], 0.0);
    EXPECT_NEAR(
      absorbed[c] + escaped[c] + scattered[c] + remaining[c], emitted[c], 1e-4 * emitted[c]);
  }
}

// Batches of any size and the chunked march give bit-identical deposits and books.
TEST(PhotonTracerProgress, BatchesDoNotChangeTheResult)
{
  vtkSmartPointer<vtkImageData> medium = FoggyBall(48);
  const int photons = 50000; // not a multiple of the batch sizes
  std::vector<std::vector<float>> radiance;
  std::vector<double> emitted, scattered;
  struct Setup
  {
    int Batch;
    int Steps;
    const char* Name;
  };
  const Setup setups[] = { { photons, 0, "one batch" }, { 1000, 0, "batches of 1000" },
    { 0, 0, "automatic batches" }, { 0, 8, "chunks of 8 steps" } };
  for (const Setup& s : setups)
  {
    vtkSmartPointer<vtkPhotonTracer> tracer = MakeTracer(medium, photons);
    tracer->SetPhotonBatchSize(s.Batch);
    tracer->SetStepsPerChunk(s.Steps);
    tracer->Update();
    vtkImageData* out = tracer->GetOutput();
    ASSERT_EQ(out->GetNumberOfPoints(), medium->GetNumberOfPoints()) << s.Name;
    const float* r = photontest::Radiance(out);
    radiance.emplace_back(r, r + 3 * out->GetNumberOfPoints());
    emitted.push_back(photontest::Energy(out, "EnergyEmitted")[0]);
    scattered.push_back(photontest::Energy(out, "EnergyScattered")[0]);
    std::printf("%s: %d batches, %d chunks, marching %.3f s\n", s.Name,
      tracer->GetNumberOfBatches(), tracer->GetNumberOfChunks(), tracer->GetMarchingSeconds());
  }
  for (size_t i = 1; i < radiance.size(); ++i)
  {
    EXPECT_TRUE(radiance[i] == radiance[0]) << setups[i].Name << " differs from one batch";
    EXPECT_EQ(emitted[i], emitted[0]) << setups[i].Name;
    EXPECT_EQ(scattered[i], scattered[0]) << setups[i].Name;
  }
}

namespace
{
vtkSmartPointer<vtkFloatArray> Filled(const char* name, int comps, vtkIdType n, float value)
{
  auto array = vtkSmartPointer<vtkFloatArray>::New();
  array->SetName(name);
  array->SetNumberOfComponents(comps);
  array->SetNumberOfTuples(n);
  array->Fill(value);
  return array;
}
}

TEST(LatticeBoltzmannProgress, ProgressAndAbort)
{
  // A full solve takes a few seconds on the 2-core CPU (~600 iterations).
  const int n = 32;
  auto medium = vtkSmartPointer<vtkImageData>::New();
  medium->SetDimensions(n, n, n);
  const vtkIdType count = medium->GetNumberOfPoints();
  medium->GetPointData()->AddArray(Filled("Extinction", 3, count, 1.0f));
  medium->GetPointData()->AddArray(Filled("Albedo", 3, count, 0.95f));
  auto lighting = vtkSmartPointer<vtkImageData>::New();
  lighting->SetDimensions(n, n, n);
  auto radiance = Filled("Radiance", 3, count, 0.0f);
  for (vtkIdType v = 0; v < count; ++v)
  {
    if (v % n < 4) // a beam entering through the -x face
    {
      radiance->SetTuple3(v, 1.0, 2.0, 3.0);
    }
  }
  lighting->GetPointData()->AddArray(radiance);

  vtkNew<vtkLatticeBoltzmannLighting> filter;
  filter->SetInputData(medium);
  filter->SetLightingData(lighting);
  filter->SetBoundary(1);
  filter->SetTolerance(1e-5);
  filter->SetMaximumIterations(20000);
  vtkNew<ProgressLog> log;
  filter->AddObserver(vtkCommand::ProgressEvent, log);
  const double latency = AbortedRun(filter, log);
  EXPECT_LT(latency, 0.5);
  EXPECT_TRUE(filter->GetLastRunAborted());
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 0);

  filter->AbortExecuteOff();
  log->Reset(2.0);
  const auto start = Clock::now();
  filter->Update();
  std::printf("full solve %.2f s\n", std::chrono::duration<double>(Clock::now() - start).count());
  EXPECT_FALSE(filter->GetLastRunAborted());
  ExpectGoodProgress(log->Values, "Lattice-Boltzmann lighting");
  vtkImageData* out = filter->GetOutput();
  ASSERT_EQ(out->GetNumberOfPoints(), count);
  ASSERT_NE(out->GetPointData()->GetArray("MultipleScattering"), nullptr);
  vtkDataArray* converged = out->GetFieldData()->GetArray("LatticeBoltzmannConverged");
  ASSERT_NE(converged, nullptr);
  EXPECT_EQ(converged->GetTuple1(0), 1);
  std::printf(
    "%g iterations\n", out->GetFieldData()->GetArray("LatticeBoltzmannIterations")->GetTuple1(0));
}

// The schedule drives both passes: its abort reaches whichever stage is running.
TEST(PhotonDiffusionScheduleProgress, ProgressAndAbort)
{
  vtkSmartPointer<vtkImageData> medium = FoggyBall(32);
  vtkNew<vtkPhotonDiffusionSchedule> schedule;
  schedule->SetInputData(medium);
  schedule->GetPhotonTracer()->AddLight(photontest::Directional({ -100, 30, 20 }, { 0, 0, 0 }, 1));
  schedule->GetPhotonTracer()->SetNumberOfPhotons(1 << 14);
  schedule->GetSolver()->SetTolerance(1e-6);
  vtkNew<ProgressLog> log;
  schedule->AddObserver(vtkCommand::ProgressEvent, log);
  const double latency = AbortedRun(schedule, log);
  EXPECT_LT(latency, 0.5);
  EXPECT_TRUE(schedule->GetLastRunAborted());
  EXPECT_EQ(schedule->GetOutput()->GetNumberOfPoints(), 0);

  schedule->AbortExecuteOff();
  log->Reset(2.0);
  schedule->Update();
  EXPECT_FALSE(schedule->GetLastRunAborted());
  ExpectGoodProgress(log->Values, "photon/diffusion schedule");
  vtkImageData* out = schedule->GetOutput();
  ASSERT_EQ(out->GetNumberOfPoints(), medium->GetNumberOfPoints());
  EXPECT_NE(out->GetPointData()->GetArray("MultipleScattering"), nullptr);
  EXPECT_EQ(photontest::Field(out, "NumberOfPhotons"), 1 << 14);
}

// Light rays and the interpolation: progress per chunk of voxels (and per grid level of the
// dynamic sampling), abort within a chunk, an aborted run leaves an empty output and the next
// run the full one, identical to a run that was never aborted.
TEST(LightRayProgress, ProgressAndAbort)
{
  // A cloud on 48^3 voxels lit by 4 directional lights: about 0.5 s a run on the 2-core CPU.
  const int n = 48;
  const double c = 0.5 * (n - 1);
  vtkSmartPointer<vtkImageData> medium = photontest::MakeMedium(
    n, n, n, 1.0,
    [=](double x, double y, double z)
    {
      photontest::Voxel v;
      const double r2 = ((x - c) * (x - c) + (y - c) * (y - c) + (z - c) * (z - c)) / (c * c);
      const double s = r2 < 1 ? 0.2 * (1 - r2) * (1.2 + std::sin(0.3 * x) * std::cos(0.2 * z)) : 0;
      v.Extinction = { s, s, s };
      v.Albedo = { 0.9, 0.9, 0.9 };
      return v;
    },
    false);
  for (int method :
    { vtkLightRaySingleScattering::LIGHT_RAYS, vtkLightRaySingleScattering::INTERPOLATED })
  {
    const char* name = vtkLightRaySingleScattering::GetMethodName(method);
    vtkNew<vtkLightRaySingleScattering> rays;
    rays->SetInputData(medium);
    rays->SetMethod(method);
    for (int l = 0; l < 4; ++l)
    {
      const double a = 1.57 * l;
      rays->AddLight(photontest::Directional(
        { 100 * std::cos(a), 60.0 - 10 * l, 100 * std::sin(a) }, { c, c, c }, 0.2));
    }
    vtkNew<ProgressLog> log;
    rays->AddObserver(vtkCommand::ProgressEvent, log);
    const double latency = AbortedRun(rays, log);
    EXPECT_LT(latency, 0.5) << name;
    EXPECT_TRUE(rays->GetLastRunAborted()) << name;
    EXPECT_EQ(rays->GetOutput()->GetNumberOfPoints(), 0) << name;
    EXPECT_EQ(rays->GetOutput()->GetPointData()->GetArray("Radiance"), nullptr) << name;

    rays->AbortExecuteOff();
    log->Reset(2.0);
    const auto start = Clock::now();
    rays->Update();
    std::printf(
      "%s: full run %.2f s\n", name, std::chrono::duration<double>(Clock::now() - start).count());
    EXPECT_FALSE(rays->GetLastRunAborted()) << name;
    ExpectGoodProgress(log->Values, name);
    vtkImageData* out = rays->GetOutput();
    ASSERT_EQ(out->GetNumberOfPoints(), medium->GetNumberOfPoints()) << name;
    vtkDataArray* radiance = out->GetPointData()->GetArray("Radiance");
    ASSERT_NE(radiance, nullptr) << name;

    // The same as a fresh filter that was never aborted (chunking changes nothing).
    vtkNew<vtkLightRaySingleScattering> fresh;
    fresh->SetInputData(medium);
    fresh->SetMethod(method);
    fresh->SetLights(rays->GetLights());
    fresh->Update();
    vtkDataArray* expected = fresh->GetOutput()->GetPointData()->GetArray("Radiance");
    ASSERT_NE(expected, nullptr) << name;
    double lit = 0;
    for (vtkIdType v = 0; v < radiance->GetNumberOfValues(); ++v)
    {
      ASSERT_EQ(radiance->GetVariantValue(v).ToFloat(), expected->GetVariantValue(v).ToFloat())
        << name << " value " << v;
      lit += radiance->GetVariantValue(v).ToDouble();
    }
    EXPECT_GT(lit, 0.0) << name;
  }
}

// The box means at sharp voxels (a dense slab's face and the slab's voxels on the grid's faces,
// about 15k of them on 48^3: most of a run) report progress from 0.9 to 0.95 and see an abort
// there within a chunk: an empty output, no error.
TEST(LightRayProgress, AbortDuringTheBoxMeans)
{
  const int n = 48;
  vtkSmartPointer<vtkImageData> medium = photontest::MakeMedium(
    n, n, n, 1.0,
    [=](double, double y, double)
    {
      photontest::Voxel v;
      const double s = y < 24 ? 2.0 : 0.0;
      v.Extinction = { s, s, s };
      v.Albedo = { 0.8, 0.8, 0.8 };
      return v;
    },
    false);
  vtkNew<vtkLightRaySingleScattering> rays;
  rays->SetInputData(medium);
  rays->AddLight(photontest::Directional({ 30, 100, 10 }, { 23.5, 23.5, 23.5 }, 1.0));
  vtkNew<ProgressLog> log;
  rays->AddObserver(vtkCommand::ProgressEvent, log);
  log->Reset(0.9);
  const auto start = Clock::now();
  rays->Update();
  const double latency = std::chrono::duration<double>(Clock::now() - log->AbortTime).count();
  std::printf("aborted after %.3f s; Update() returned %.3f s after the abort\n",
    std::chrono::duration<double>(log->AbortTime - start).count(), latency);
  EXPECT_TRUE(log->Aborted);
  EXPECT_LT(latency, 0.5);
  EXPECT_TRUE(rays->GetLastRunAborted());
  EXPECT_EQ(rays->GetOutput()->GetNumberOfPoints(), 0);
  EXPECT_GT(rays->GetNumberOfBoxMeanVoxels(), 10000);

  rays->AbortExecuteOff();
  log->Reset(2.0);
  rays->Update();
  EXPECT_FALSE(rays->GetLastRunAborted());
  ExpectGoodProgress(log->Values, "light rays with box means");
  EXPECT_EQ(rays->GetOutput()->GetNumberOfPoints(), medium->GetNumberOfPoints());
}
