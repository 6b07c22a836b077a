// Progress and abort of vtkRefractaImageRenderer (issue 12): the view pass renders in tiles of
// rows; ProgressEvent values are monotone, many and end at 1; an observer that calls
// AbortExecuteOn() at the first value above 0.2 makes Update() return within 0.5 s with an empty
// output; after AbortExecuteOff() the next Update() renders the full image, and the tiled image
// is identical to the untiled one.
#include "ProgressTestUtilities.h"
#include "RenderingTestUtilities.h"

#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkRefractaImageRenderer.h"
#include "vtkRefractaViewPass.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <set>
#include <vector>

namespace
{
using refracta_test::Clock;
using refracta_test::ProgressLog;

// A glass ball with a graded index, emitting and absorbing: curved rays.
vtkSmartPointer<vtkImageData> GlowingBall(int n)
{
  vtkSmartPointer<vtkImageData> image = refracta_test::MakeGrid(n, n, n, 1.0 / (n - 1));
  refracta_test::AddConstant(image, "Extinction", 3, 1.0, 1.5, 2.0);
  refracta_test::AddConstant(image, "Emission", 3, 0.5, 0.4, 0.3);
  vtkFloatArray* index = refracta_test::AddConstant(image, "RefractiveIndex", 1, 1.0);
  for (int k = 0; k < n; ++k)
  {
    for (int j = 0; j < n; ++j)
    {
      for (int i = 0; i < n; ++i)
      {
        const double x = double(i) / (n - 1) - 0.5, y = double(j) / (n - 1) - 0.5,
                     z = double(k) / (n - 1) - 0.5;
        const double r2 = x * x + y * y + z * z;
        index->SetValue(i + n * (j + n * k), static_cast<float>(1.0 + 0.4 * std::exp(-r2 / 0.04)));
      }
    }
  }
  return image;
}
}

TEST(ImageRendererProgress, ProgressAbortAndTiles)
{
  vtkNew<vtkCamera> camera;
  camera->SetFocalPoint(0.5, 0.5, 0.5);
  camera->SetPosition(0.5, 0.8, 2.4);
  camera->SetViewAngle(35);
  vtkNew<vtkRefractaImageRenderer> renderer;
  renderer->SetInputData(GlowingBall(64));
  renderer->SetCamera(camera);
  renderer->SetImageSize(640, 480);
  renderer->SetStepSize(0.5);
  vtkNew<ProgressLog> log;
  renderer->AddObserver(vtkCommand::ProgressEvent, log);

  // 1. Abort at the first progress above 0.2.
  log->AbortAbove = 0.2;
  auto start = Clock::now();
  renderer->Update();
  const auto end = Clock::now();
  ASSERT_TRUE(log->Aborted);
  const double latency = std::chrono::duration<double>(end - log->AbortTime).count();
  std::printf("aborted after %.3f s; Update() returned %.3f s after the abort\n",
    std::chrono::duration<double>(log->AbortTime - start).count(), latency);
  EXPECT_LT(latency, 0.5);
  EXPECT_TRUE(renderer->GetLastRunAborted());
  EXPECT_EQ(renderer->GetOutput()->GetNumberOfPoints(), 0);

  // 2. The full render after AbortExecuteOff().
  renderer->AbortExecuteOff();
  log->Reset(2.0);
  start = Clock::now();
  renderer->Update();
  std::printf("full render %.2f s, %d tiles\n",
    std::chrono::duration<double>(Clock::now() - start).count(),
    renderer->GetViewPass()->GetLastNumberOfTiles());
  EXPECT_FALSE(renderer->GetLastRunAborted());
  ASSERT_EQ(renderer->GetOutput()->GetNumberOfPoints(), 640 * 480);
  refracta_test::ExpectGoodProgress(log->Values, "image renderer");
  vtkNew<vtkImageData> tiled;
  tiled->DeepCopy(renderer->GetOutput());

  // 3. One tile: the same image, bit for bit.
  renderer->GetViewPass()->SetTilePixels(1 << 30);
  renderer->GetViewPass()->SetTileSeconds(0);
  renderer->Update();
  EXPECT_EQ(renderer->GetViewPass()->GetLastNumberOfTiles(), 1);
  auto* a = vtkFloatArray::SafeDownCast(tiled->GetPointData()->GetArray("HDR"));
  auto* b = vtkFloatArray::SafeDownCast(renderer->GetOutput()->GetPointData()->GetArray("HDR"));
  ASSERT_TRUE(a && b);
  ASSERT_EQ(a->GetNumberOfValues(), b->GetNumberOfValues());
  vtkIdType differ = 0;
  double sum = 0;
  for (vtkIdType v = 0; v < a->GetNumberOfValues(); ++v)
  {
    differ += a->GetValue(v) != b->GetValue(v);
    sum += a->GetValue(v);
  }
  EXPECT_EQ(differ, 0);
  EXPECT_GT(sum, 0.0);
}
