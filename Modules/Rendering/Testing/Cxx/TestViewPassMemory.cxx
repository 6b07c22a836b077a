// Memory planning of the view pass: an image whose HDR buffer exceeds the device's largest
// allocation (lowered with the context's test hook) is rendered in buffer tiles with the same
// pixels as in one buffer, perspective and parallel, curved rays included; a 16384 x 16384 image
// that the host cannot hold fails at once, before any image buffer exists, with a message that
// names the image, the memory needed, the limit and the setting to lower.
#include "RenderingTestUtilities.h"

#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkFloatArray.h"
#include "vtkOpenCLContext.h"
#include "vtkOpenCLHandle.h"
#include "vtkOpenCLMemoryPlan.h"
#include "vtkPointData.h"
#include "vtkRefractaViewPass.h"
#include "vtkTestErrorObserver.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <string>
#include <vector>

using namespace refracta_test;

namespace
{
// A 20^3 emitting, absorbing fog with a refractive ball (curved view rays).
vtkSmartPointer<vtkImageData> Medium()
{
  auto image = MakeGrid(20, 20, 20, 0.05);
  AddConstant(image, "Extinction", 3, 2.0, 2.5, 3.0);
  AddConstant(image, "Emission", 3, 1.0, 0.6, 0.3);
  vtkFloatArray* n = AddConstant(image, "RefractiveIndex", 1, 1.0);
  for (vtkIdType id = 0; id < image->GetNumberOfPoints(); ++id)
  {
    double p[3];
    image->GetPoint(id, p);
    const double r = std::sqrt((p[0] - 0.475) * (p[0] - 0.475) + (p[1] - 0.475) * (p[1] - 0.475) +
      (p[2] - 0.475) * (p[2] - 0.475));
    n->SetValue(id, static_cast<float>(1.0 + 0.15 * 0.5 * (1 - std::tanh((r - 0.25) / 0.05))));
  }
  return image;
}

bool Contains(const std::string& text, const std::string& part)
{
  return text.find(part) != std::string::npos;
}
}

TEST(ViewPassMemory, ImagesLargerThanOneAllocationRenderInBufferTiles)
{
  vtkNew<vtkOpenCLContext> context;
  ASSERT_TRUE(context->Initialize());
  vtkNew<vtkRefractaViewPass> pass;
  pass->SetContext(context);
  auto medium = Medium(); // the pass does not hold a reference to it
  ASSERT_TRUE(pass->SetMedium(medium));
  vtkNew<vtkCamera> camera;
  camera->SetPosition(0.6, 0.55, 2.5);
  camera->SetFocalPoint(0.475, 0.475, 0.475);
  const int w = 61, h = 47;
  for (bool parallel : { false, true })
  {
    camera->SetParallelProjection(parallel);
    camera->SetParallelScale(0.6);
    std::vector<float> whole, wholeT, tiled, tiledT;
    context->SetSimulatedMaximumAllocationBytes(0);
    ASSERT_TRUE(pass->Render(camera, w, h, nullptr, nullptr, whole, &wholeT));
    EXPECT_EQ(pass->GetLastNumberOfBufferTiles(), 1);
    // 5 rows of 16-byte pixels per allocation: 10 buffer tiles, the last one 2 rows.
    context->SetSimulatedMaximumAllocationBytes(w * 16.0 * 5);
    ASSERT_TRUE(pass->Render(camera, w, h, nullptr, nullptr, tiled, &tiledT));
    EXPECT_EQ(pass->GetLastNumberOfBufferTiles(), 10);
    ASSERT_EQ(tiled.size(), whole.size());
    double worst = 0, peak = 0;
    for (size_t i = 0; i < whole.size(); ++i)
    {
      worst = std::max(worst, std::abs(double(tiled[i]) - whole[i]));
      worst = std::max(worst, std::abs(double(tiledT[i]) - wholeT[i]));
      peak = std::max(peak, std::abs(double(whole[i])));
    }
    std::printf("%s: largest difference tiled vs whole %.3g (peak %.3g)\n",
      parallel ? "parallel" : "perspective", worst, peak);
    EXPECT_LE(worst, 1e-4 * peak);
    EXPECT_GT(peak, 0.0);
  }
}

TEST(ViewPassMemory, ImageBeyondTheLimitsFailsBeforeAllocating)
{
  vtkNew<vtkOpenCLContext> context;
  ASSERT_TRUE(context->Initialize());
  vtkNew<vtkRefractaViewPass> pass;
  pass->SetContext(context);
  auto medium = Medium(); // the pass does not hold a reference to it
  ASSERT_TRUE(pass->SetMedium(medium));
  vtkNew<vtkCamera> camera;
  camera->SetPosition(0.6, 0.55, 2.5);
  camera->SetFocalPoint(0.475, 0.475, 0.475);
  vtkNew<vtkTest::ErrorObserver> observer;
  pass->AddObserver(vtkCommand::ErrorEvent, observer);
  context->SetSimulatedMaximumAllocationBytes(1024.0 * 1024 * 1024);
  context->SetSimulatedHostMemoryBytes(2.0 * 1024 * 1024 * 1024);
  const long long buffers = vtkOpenCLLiveHandles(0);
  const int enqueues = context->GetNumberOfEnqueues();
  std::vector<float> hdr;
  const auto start = std::chrono::steady_clock::now();
  EXPECT_FALSE(pass->Render(camera, 16384, 16384, nullptr, nullptr, hdr));
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::string msg = observer->GetErrorMessage();
  std::printf("%s\n(%.3f s)\n", msg.c_str(), seconds);
  EXPECT_TRUE(Contains(msg, "image 16384 x 16384 (in tiles of 4096 rows)")) << msg;
  EXPECT_TRUE(Contains(msg, "needs 5.0 GiB of host memory")) << msg;
  EXPECT_TRUE(Contains(msg, "HDR image")) << msg;
  EXPECT_TRUE(Contains(msg, "this machine has 2.0 GiB: lower the image size")) << msg;
  EXPECT_EQ(vtkOpenCLLiveHandles(0), buffers);
  EXPECT_EQ(context->GetNumberOfEnqueues(), enqueues);
  EXPECT_TRUE(hdr.empty());
  EXPECT_LT(seconds, 1.0);
  // The device part was planned in buffer tiles: one tile's HDR buffer is exactly 1 GiB.
  EXPECT_NEAR(pass->GetMemoryPlan()->GetLargestDeviceBufferBytes(), 1024.0 * 1024 * 1024, 1.0);

  // A single row that exceeds one allocation cannot be tiled: the message names the image size.
  observer->Clear();
  context->SetSimulatedHostMemoryBytes(0);
  context->SetSimulatedMaximumAllocationBytes(1000);
  EXPECT_FALSE(pass->Render(camera, 100, 10, nullptr, nullptr, hdr));
  EXPECT_TRUE(Contains(observer->GetErrorMessage(),
    "per allocation (CL_DEVICE_MAX_MEM_ALLOC_SIZE): "
    "lower the image size"))
    << observer->GetErrorMessage();
  EXPECT_EQ(vtkOpenCLLiveHandles(0), buffers);
}
