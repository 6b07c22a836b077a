// The photon pass under faults and limits: an OpenCL error injected at any point of a run fails
// that run with a reported error, releases every buffer it made, and the next Update() gives the
// clean result; a photon count or grid beyond the (test-lowered) device limits fails before any
// allocation with a message that names the setting to lower and the limit.
#include "PhotonTestUtilities.h"

#include "vtkCommand.h"
#include "vtkExecutive.h"
#include "vtkOpenCLContext.h"
#include "vtkPhotonTracer.h"
#include "vtkTestErrorObserver.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

using namespace photontest;

namespace
{
// A refractive sphere (n = 1.3) in a scattering fog, 20^3 voxels: every stage runs (gradient,
// octree, generation, curved march, resolve, smoothing).
vtkSmartPointer<vtkImageData> SphereInFog(int n)
{
  return MakeMedium(n, n, n, 1.0 / n,
    [&](double x, double y, double z)
    {
      Voxel v;
      const double r =
        std::sqrt((x - 0.5) * (x - 0.5) + (y - 0.5) * (y - 0.5) + (z - 0.5) * (z - 0.5));
      v.N = 1.0 + 0.3 * 0.5 * (1 - std::tanh((r - 0.3) * n));
      v.Extinction = { 2, 2, 2 };
      v.Albedo = { 0.8, 0.8, 0.8 };
      return v;
    });
}

std::vector<float> RadianceCopy(vtkPhotonTracer* tracer)
{
  vtkImageData* out = tracer->GetOutput();
  if (!out->GetPointData()->GetArray(vtkRefractaLightingVolume::RadianceName()))
  {
    return {};
  }
  const float* r = Radiance(out);
  return std::vector<float>(r, r + 3 * out->GetNumberOfPoints());
}

bool Contains(const std::string& text, const std::string& part)
{
  return text.find(part) != std::string::npos;
}
}

TEST(PhotonTracerFaults, AnEnqueueFailureReleasesEverythingAndTheNextUpdateWorks)
{
  vtkNew<vtkOpenCLContext> context;
  ASSERT_TRUE(context->Initialize());
  auto medium = SphereInFog(20);
  vtkNew<vtkPhotonTracer> tracer;
  tracer->SetContext(context);
  tracer->SetInputData(medium);
  tracer->AddLight(Directional({ -1, 0.6, 0.4 }, { 0.5, 0.5, 0.5 }, 1.0));
  tracer->SetNumberOfPhotons(1 << 12);
  tracer->SetPhotonBatchSize(1024); // several march batches, so faults land between them too
  vtkNew<vtkTest::ErrorObserver> observer;
  tracer->AddObserver(vtkCommand::ErrorEvent, observer);
  tracer->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, observer);

  const long long before = vtkOpenCLLiveHandles(0);
  const int enqueuesBefore = context->GetNumberOfEnqueues();
  tracer->Update();
  ASSERT_FALSE(observer->GetError()) << observer->GetErrorMessage();
  const std::vector<float> clean = RadianceCopy(tracer);
  ASSERT_FALSE(clean.empty());
  const int enqueues = context->GetNumberOfEnqueues() - enqueuesBefore;
  // What a finished run keeps: the medium's buffers, reused by the next run of the same input.
  const long long kept = vtkOpenCLLiveHandles(0) - before;
  std::printf("a clean run enqueues %d commands and keeps %lld buffers\n", enqueues, kept);
  ASSERT_GT(enqueues, 10);

  for (int n : { 1, 2, enqueues / 4, enqueues / 2, (3 * enqueues) / 4, enqueues - 1, enqueues })
  {
    // A new input each time, so that the run uploads the medium (the first enqueues) again.
    medium->Modified();
    observer->Clear();
    context->SetFailingEnqueue(n);
    tracer->Update();
    EXPECT_TRUE(observer->GetError()) << "fault at enqueue " << n;
    EXPECT_TRUE(Contains(observer->GetErrorMessage(), "injected")) << observer->GetErrorMessage();
    EXPECT_TRUE(RadianceCopy(tracer).empty()) << "fault at enqueue " << n;
    EXPECT_LE(vtkOpenCLLiveHandles(0), before + kept) << "fault at enqueue " << n;

    observer->Clear();
    tracer->Modified();
    tracer->Update();
    EXPECT_FALSE(observer->GetError()) << observer->GetErrorMessage();
    EXPECT_EQ(RadianceCopy(tracer), clean) << "the run after a fault at enqueue " << n;
    EXPECT_EQ(vtkOpenCLLiveHandles(0), before + kept) << "after the fault at enqueue " << n;
  }
}

TEST(PhotonTracerFaults, PhotonsOrGridBeyondTheDeviceLimitsAreNamed)
{
  vtkNew<vtkOpenCLContext> context;
  ASSERT_TRUE(context->Initialize());
  context->SetSimulatedMaximumAllocationBytes(1 << 20);
  vtkNew<vtkTest::ErrorObserver> observer;
  vtkNew<vtkPhotonTracer> tracer;
  tracer->SetContext(context);
  tracer->AddObserver(vtkCommand::ErrorEvent, observer);
  tracer->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, observer);
  tracer->AddLight(Directional({ -1, 0.6, 0.4 }, { 0.5, 0.5, 0.5 }, 1.0));
  const long long before = vtkOpenCLLiveHandles(0);
  const int enqueues = context->GetNumberOfEnqueues();

  // 2^17 photons: 2 MiB per photon array against 1 MiB per allocation.
  tracer->SetInputData(SphereInFog(16));
  tracer->SetNumberOfPhotons(1 << 17);
  tracer->Update();
  std::string msg = observer->GetErrorMessage();
  EXPECT_TRUE(Contains(msg, "131072 photons needs 2.0 MiB for the photon positions")) << msg;
  EXPECT_TRUE(Contains(msg, "allows 1.0 MiB per allocation")) << msg;
  EXPECT_TRUE(Contains(msg, "lower NumberOfPhotons")) << msg;
  EXPECT_GT(tracer->GetPlannedDeviceMemoryBytes(), 6.0 * (1 << 20));
  EXPECT_EQ(vtkOpenCLLiveHandles(0), before) << "nothing may be allocated before the check";
  EXPECT_EQ(context->GetNumberOfEnqueues(), enqueues);

  // A 48^3 scattering grid: 5.1 MiB for the radiance and direction accumulators.
  observer->Clear();
  tracer->SetInputData(SphereInFog(48));
  tracer->SetNumberOfPhotons(1 << 12);
  tracer->Update();
  msg = observer->GetErrorMessage();
  EXPECT_TRUE(Contains(msg, "grid 48 x 48 x 48 needs")) << msg;
  EXPECT_TRUE(Contains(msg, "lower the grid size")) << msg;
  EXPECT_EQ(vtkOpenCLLiveHandles(0), before);

  // The device's total: many small buffers over a lowered global memory.
  observer->Clear();
  context->SetSimulatedMaximumAllocationBytes(0);
  context->SetSimulatedGlobalMemoryBytes(1 << 20);
  tracer->Update();
  msg = observer->GetErrorMessage();
  EXPECT_TRUE(Contains(msg, "of device memory in all")) << msg;
  EXPECT_TRUE(Contains(msg, "CL_DEVICE_GLOBAL_MEM_SIZE")) << msg;

  // Within the limits the same tracer runs, and the plan covers what it allocated.
  observer->Clear();
  context->SetSimulatedGlobalMemoryBytes(0);
  tracer->Update();
  EXPECT_FALSE(observer->GetError()) << observer->GetErrorMessage();
  EXPECT_GE(tracer->GetPlannedDeviceMemoryBytes(), 0.95 * tracer->GetPeakDeviceMemoryBytes());
  std::printf("48^3, 4096 photons: planned %.0f bytes, allocated %.0f bytes\n",
    tracer->GetPlannedDeviceMemoryBytes(), tracer->GetPeakDeviceMemoryBytes());
}
