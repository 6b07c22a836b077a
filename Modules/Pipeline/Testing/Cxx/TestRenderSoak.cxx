// Soak: one vtkRefractaRenderPipeline re-renders a small refractive fog many times while the light
// and the camera move (every render re-runs the photon pass and the view pass). Host memory (the
// resident set, /proc/self/statm) and device allocations (live cl_mem handles) must stay flat:
// after a warm-up, the live buffer count is the same after every render, and the resident set
// grows by less than a small allowance (allocator noise, not a per-render leak).
//
// The number of renders is REFRACTA_SOAK_RENDERS (default 50, in the default suite; the `long`
// test runs 1000).
#include "vtkCamera.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkOpenCLHandle.h"
#include "vtkPhotonTracer.h"
#include "vtkPointData.h"
#include "vtkRefractaRenderPipeline.h"
#include "vtkRefractaViewPass.h"
#include "vtkSmartPointer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <unistd.h>

namespace
{
double ResidentMiB()
{
  std::ifstream statm("/proc/self/statm");
  long size = 0, resident = 0;
  statm >> size >> resident;
  return resident * static_cast<double>(sysconf(_SC_PAGESIZE)) / (1024.0 * 1024.0);
}

// A 16^3 fog with a slightly refractive ball: curved rays in both passes.
vtkSmartPointer<vtkImageData> Fog()
{
  const int n = 16;
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(n, n, n);
  image->SetSpacing(1.0 / (n - 1), 1.0 / (n - 1), 1.0 / (n - 1));
  auto add = [&](const char* name, int comps)
  {
    vtkNew<vtkFloatArray> a;
    a->SetName(name);
    a->SetNumberOfComponents(comps);
    a->SetNumberOfTuples(image->GetNumberOfPoints());
    image->GetPointData()->AddArray(a);
    return a.GetPointer();
  };
  vtkFloatArray* ext = add("Extinction", 3);
  vtkFloatArray* alb = add("Albedo", 3);
  vtkFloatArray* idx = add("RefractiveIndex", 1);
  for (vtkIdType id = 0; id < image->GetNumberOfPoints(); ++id)
  {
    double p[3];
    image->GetPoint(id, p);
    const double r = std::sqrt(
      (p[0] - 0.5) * (p[0] - 0.5) + (p[1] - 0.5) * (p[1] - 0.5) + (p[2] - 0.5) * (p[2] - 0.5));
    const double ball = 0.5 * (1.0 - std::tanh((r - 0.25) / 0.05));
    for (int c = 0; c < 3; ++c)
    {
      ext->SetComponent(id, c, 2.0 + 4.0 * ball);
      alb->SetComponent(id, c, 0.8);
    }
    idx->SetValue(id, static_cast<float>(1.0 + 0.2 * ball));
  }
  return image;
}
}

TEST(RenderSoak, MovingLightAndCameraKeepMemoryFlat)
{
  const char* env = std::getenv("REFRACTA_SOAK_RENDERS");
  const int renders = env ? std::max(10, std::atoi(env)) : 50;
  vtkNew<vtkRefractaRenderPipeline> pipeline;
  pipeline->SetMedium(Fog());
  vtkNew<vtkLight> light;
  light->SetLightTypeToSceneLight();
  light->SetPositional(false);
  light->SetFocalPoint(0.5, 0.5, 0.5);
  light->SetIntensity(2.0);
  pipeline->AddLight(light);
  vtkNew<vtkCamera> camera;
  camera->SetFocalPoint(0.5, 0.5, 0.5);
  camera->SetViewUp(0, 1, 0);
  pipeline->SetCamera(camera);
  pipeline->MultipleScatteringOff();
  pipeline->GetPhotonTracer()->SetNumberOfPhotons(1 << 11);

  auto move = [&](int i)
  {
    const double a = 0.1 * i, b = 0.07 * i;
    light->SetPosition(0.5 + 3 * std::cos(a), 3.0, 0.5 + 3 * std::sin(a));
    camera->SetPosition(0.5 + 3 * std::sin(b), 0.6, 0.5 + 3 * std::cos(b));
  };
  // Warm-up: kernels compiled, caches and allocator pools filled.
  const int warmup = 5;
  for (int i = 0; i < warmup; ++i)
  {
    move(i);
    ASSERT_TRUE(pipeline->Render(32, 24)) << "warm-up render " << i;
  }
  const long long buffers = vtkOpenCLLiveHandles(0);
  const long long kernels = vtkOpenCLLiveHandles(1);
  const double rss0 = ResidentMiB();
  const int lightRuns0 = pipeline->GetNumberOfLightPassRuns();
  double rssHalf = rss0;
  for (int i = warmup; i < warmup + renders; ++i)
  {
    move(i);
    ASSERT_TRUE(pipeline->Render(32, 24)) << "render " << i;
    ASSERT_EQ(vtkOpenCLLiveHandles(0), buffers) << "live cl_mem after render " << i;
    ASSERT_EQ(vtkOpenCLLiveHandles(1), kernels) << "live cl_kernel after render " << i;
    if (i == warmup + renders / 2)
    {
      rssHalf = ResidentMiB();
    }
  }
  const double rss1 = ResidentMiB();
  std::printf("%d renders (%d light passes): live buffers %lld, kernels %lld; resident set %.1f "
              "MiB -> %.1f MiB (half-way %.1f MiB)\n",
    renders, pipeline->GetNumberOfLightPassRuns() - lightRuns0, buffers, kernels, rss0, rss1,
    rssHalf);
  EXPECT_EQ(pipeline->GetNumberOfLightPassRuns() - lightRuns0, renders)
    << "every render re-ran the light pass";
  // A per-render leak of even 10 KiB shows as 0.5 MiB over 50 renders and 10 MiB over 1000;
  // the allowance is 4 MiB plus 1 KiB a render, and the second half may not grow more than the
  // first half plus 2 MiB (a leak grows steadily, allocator warm-up does not).
  EXPECT_LT(rss1 - rss0, 4.0 + renders / 1024.0);
  EXPECT_LT(rss1 - rssHalf, (rssHalf - rss0) + 2.0);
}
