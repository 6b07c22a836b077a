// vtkPhotonTracer::ReuseScratchBuffers: a run that borrows the last run's scratch device buffers
// (accumulators, photon state, work arrays: their contents are whatever that run left) must give
// the same bits as a tracer that creates fresh ones; and it must actually borrow them.
#include "vtkNew.h"
#include "vtkOpenCLContext.h"
#include "vtkOpenCLKernelProfile.h"
#include "vtkPhotonTracer.h"

#include "PhotonTestUtilities.h"

#include <gtest/gtest.h>

#include <cstring>

using namespace photontest;

namespace
{
void Configure(vtkPhotonTracer* tracer, double lightY, int photons, int orders)
{
  tracer->RemoveAllLights();
  tracer->AddLight(Directional({ -1, lightY, 0.2 }, { 0.45, 0.4, 0.35 }, 1.0));
  tracer->SetNumberOfPhotons(photons);
  tracer->SetScatteringOrders(orders);
  tracer->SetSeed(5);
}

// The same bits in every array and book; and light in the fog (a test that compares two dark runs
// proves nothing).
void ExpectSameOutput(vtkImageData* a, vtkImageData* b)
{
  ExpectSameBits(a->GetPointData(), b->GetPointData(), "");
  ExpectSameBits(a->GetFieldData(), b->GetFieldData(), "");
  EXPECT_GT(Energy(a, "EnergyScattered")[0], 0.0) << "the light must reach the fog";
}

int BuffersCreatedBy(vtkPhotonTracer* tracer)
{
  vtkOpenCLContext* context = vtkOpenCLContext::GetDefault();
  context->ProfileKernelsOn();
  context->GetKernelProfile()->Reset();
  tracer->Modified();
  tracer->Update();
  vtkOpenCLKernelProfile* profile = context->GetKernelProfile();
  int created = 0;
  for (int i = 0; i < profile->GetNumberOfKernels(); ++i)
  {
    if (std::strcmp(profile->GetKernelLabel(i), "[create buffer]") == 0)
    {
      created += profile->GetNumberOfLaunches(i);
    }
  }
  context->ProfileKernelsOff();
  return created;
}
}

// The kept buffers hold the last run's deposits, photons and work arrays; the next run must not
// see them. Runs: a light, another light and photon count (new sizes: the pool is replaced), then
// that again (every scratch buffer borrowed, full of the run before's values). With and without
// the first-collision split (its S_ms accumulators are scratch too).
TEST(PhotonScratchBuffers, BorrowedBuffersGiveTheSameBitsAsFreshOnes)
{
  auto medium = RefractingFog(18, 16, 14, 1.5, 1.0, { 1, 0.9, 0.8 }, { 0.9, 0.85, 0.8 });
  for (int orders : { 0, 2 })
  {
    vtkNew<vtkPhotonTracer> reusing;
    reusing->SetInputData(medium);
    reusing->ReuseScratchBuffersOn();
    Configure(reusing, 0.3, 1 << 13, orders);
    reusing->Update();
    Configure(reusing, 1.2, 1 << 12, orders);
    reusing->Update();
    Configure(reusing, 1.2, 1 << 12, orders);
    const int borrowing = BuffersCreatedBy(reusing);

    vtkNew<vtkPhotonTracer> fresh;
    fresh->SetInputData(medium);
    Configure(fresh, 1.2, 1 << 12, orders);
    fresh->Update(); // keeps its medium, as `reusing` did
    const int creating = BuffersCreatedBy(fresh);
    ExpectSameOutput(reusing->GetOutput(), fresh->GetOutput());
    std::printf("orders %d: buffers created by a run %d borrowing, %d without\n", orders, borrowing,
      creating);
    EXPECT_LT(borrowing, creating) << "the run must borrow its scratch buffers";
    EXPECT_EQ(reusing->GetUsedScatteringOrders(), fresh->GetUsedScatteringOrders());

    // Off again: the kept buffers are released and runs create their own.
    reusing->ReuseScratchBuffersOff();
    EXPECT_EQ(BuffersCreatedBy(reusing), creating);
    ExpectSameOutput(reusing->GetOutput(), fresh->GetOutput());
  }
}
