// Tests of vtkReferenceRenderer's robustness: the same image for a seed whatever the threads, hard
// inputs that stay finite, the environment map's lookup, and bad inputs that get clear errors and
// an empty output.
#include "ReferenceTestUtilities.h"

#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkMath.h"
#include "vtkMatrix3x3.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkReferenceRenderer.h"
#include "vtkSMPTools.h"
#include "vtkTestErrorObserver.h"
#include "vtkUnsignedCharArray.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

using namespace reftest;

// ---------------------------------------------------------------------------------------------
// Determinism: same seed -> identical bits (also with one thread instead of the default); another
// seed -> a different image.
TEST(ReferenceRenderer, DeterministicPerSeed)
{
  const int dims[3] = { 8, 8, 8 };
  const double spacing[3] = { 0.1, 0.1, 0.1 }, origin[3] = { 0, 0, 0 };
  auto medium = MakeMedium(dims, spacing, origin,
    [](int i, int j, int k, Voxel& v)
    {
      v.N = 1.0 + 0.05 * i + 0.02 * j * k / 8.0;
      v.G = 0.4;
      v.Sigma[0] = 2 + i;
      v.Sigma[1] = 3;
      v.Sigma[2] = 1 + k;
      v.Albedo[0] = v.Albedo[1] = v.Albedo[2] = 0.7;
      v.Emission[1] = 0.1 * j;
    });
  const double towards[3] = { 0.3, 0.4, 0.866 };
  vtkNew<vtkCamera> cam;
  cam->SetPosition(0.4, -1.5, 0.9);
  cam->SetFocalPoint(0.35, 0.35, 0.35);
  cam->SetViewUp(0, 0, 1);
  auto render = [&](unsigned int seed)
  {
    vtkNew<vtkReferenceRenderer> r;
    r->SetInputData(medium);
    r->SetCamera(cam);
    r->AddLight(Directional(towards, 2.0));
    r->SetImageSize(8, 8);
    r->SetSamplesPerPixel(Spp(4));
    r->SetSeed(seed);
    r->Update();
    std::vector<float> v;
    vtkDataArray* a = r->GetOutput()->GetPointData()->GetArray("HDR");
    for (vtkIdType i = 0; i < a->GetNumberOfValues(); ++i)
    {
      v.push_back(static_cast<float>(a->GetComponent(i / 4, i % 4)));
    }
    return v;
  };
  const auto a = render(5);
  const auto b = render(5);
  const int threads = vtkSMPTools::GetEstimatedNumberOfThreads();
  vtkSMPTools::Initialize(1);
  const auto c = render(5);
  vtkSMPTools::Initialize(threads);
  const auto d = render(6);
  EXPECT_EQ(a, b);
  EXPECT_EQ(a, c);
  EXPECT_NE(a, d);
}

// ---------------------------------------------------------------------------------------------
// Hard inputs stay finite: albedo 1 with g = +-0.999 in an optically thick slab, a steep index
// step (n 1 -> 2.5 over one voxel) with a point light inside the medium.
TEST(ReferenceRenderer, HardInputsStayFinite)
{
  const int dims[3] = { 6, 6, 6 };
  const double spacing[3] = { 1, 1, 1 }, origin[3] = { 0, 0, 0 };
  const double towards[3] = { 0.2, 0.1, 0.97 };
  vtkNew<vtkCamera> cam;
  cam->SetPosition(2.5, -6, 8);
  cam->SetFocalPoint(2.5, 2.5, 2.5);
  cam->SetViewUp(0, 0, 1);
  for (double g : { 0.999, -0.999 })
  {
    Voxel v;
    v.G = g;
    for (int c = 0; c < 3; ++c)
    {
      v.Sigma[c] = 4.0; // tau = 24 across
      v.Albedo[c] = 1.0;
    }
    auto medium = Homogeneous(dims, spacing, origin, v);
    vtkNew<vtkReferenceRenderer> r;
    r->SetInputData(medium);
    r->SetCamera(cam);
    r->AddLight(Directional(towards, 1.0));
    r->SetImageSize(8, 8);
    r->SetSamplesPerPixel(Spp(4));
    r->Update();
    vtkDataArray* hdr = r->GetOutput()->GetPointData()->GetArray("HDR");
    vtkDataArray* se = r->GetOutput()->GetPointData()->GetArray("StandardError");
    ASSERT_NE(hdr, nullptr);
    double sum = 0;
    for (vtkIdType i = 0; i < 64; ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        ASSERT_TRUE(std::isfinite(hdr->GetComponent(i, c)));
        ASSERT_TRUE(std::isfinite(se->GetComponent(i, c)));
        ASSERT_GE(hdr->GetComponent(i, c), 0.0);
        sum += hdr->GetComponent(i, c);
      }
    }
    EXPECT_GT(sum, 0) << "g = " << g;
    EXPECT_EQ(FieldValue(r->GetOutput(), "NonFiniteSamples"), 0);
    std::cout << "albedo 1, g = " << g << ": mean " << sum / 192 << ", "
              << FieldValue(r->GetOutput(), "RenderSeconds") << " s, truncated "
              << FieldValue(r->GetOutput(), "TruncatedPaths") << "\n";
  }
  // Enormous contrast: sigma_t = 1e5 in a 2^3 core, 0.01 elsewhere (32^3 voxels). Per-block
  // majorants confine the 1e5 majorant to the blocks around the core (a global majorant would
  // take ~3e6 null collisions per ray everywhere); finite, non-negative, bounded time.
  {
    const int bigDims[3] = { 32, 32, 32 };
    auto contrast = MakeMedium(bigDims, spacing, origin,
      [](int i, int j, int k, Voxel& v)
      {
        const bool core = i >= 15 && i <= 16 && j >= 15 && j <= 16 && k >= 15 && k <= 16;
        for (int c = 0; c < 3; ++c)
        {
          v.Sigma[c] = core ? 1e5 : 0.01;
          v.Albedo[c] = 0.9;
        }
      });
    const double focal[3] = { 15.5, 15.5, 15.5 }, dop[3] = { 0, 0, -1 }, up[3] = { 0, 1, 0 };
    vtkNew<vtkReferenceRenderer> r;
    r->SetInputData(contrast);
    r->SetCamera(ParallelCamera(focal, dop, up, 8.0));
    r->AddLight(Directional(towards, 1.0));
    r->SetBackgroundColor(1, 1, 1);
    r->SetImageSize(4, 4);
    r->SetSamplesPerPixel(4);
    r->Update();
    const double secs = FieldValue(r->GetOutput(), "RenderSeconds");
    std::cout << "contrast 1e7: " << secs << " s\n";
    EXPECT_LT(secs, 30.0);
    vtkDataArray* hdr = r->GetOutput()->GetPointData()->GetArray("HDR");
    ASSERT_NE(hdr, nullptr);
    for (vtkIdType i = 0; i < 16; ++i)
    {
      ASSERT_TRUE(std::isfinite(hdr->GetComponent(i, 0)));
      ASSERT_GE(hdr->GetComponent(i, 0), 0.0);
    }
  }
  // Steep index step, point light in the medium, curved rays.
  auto medium = MakeMedium(dims, spacing, origin,
    [](int i, int, int, Voxel& v)
    {
      v.N = i < 3 ? 1.0 : 2.5;
      v.G = 0.9;
      for (int c = 0; c < 3; ++c)
      {
        v.Sigma[c] = 0.3;
        v.Albedo[c] = 0.95;
      }
    });
  vtkNew<vtkLight> pl;
  pl->PositionalOn();
  pl->SetConeAngle(180);
  pl->SetPosition(1, 2.5, 2.5);
  pl->SetIntensity(5);
  vtkNew<vtkReferenceRenderer> r;
  r->SetInputData(medium);
  r->SetCamera(cam);
  r->AddLight(pl);
  // LightRadius 0 is a delta light, which the reference refuses for point lights: give the
  // radius the renderer used to substitute silently (1% of the voxel box's diagonal).
  r->SetLightRadius(0.01 *
    std::sqrt(std::pow(dims[0] * spacing[0], 2) + std::pow(dims[1] * spacing[1], 2) +
      std::pow(dims[2] * spacing[2], 2)));
  r->SetImageSize(8, 8);
  r->SetSamplesPerPixel(Spp(4));
  r->Update();
  vtkDataArray* hdr = r->GetOutput()->GetPointData()->GetArray("HDR");
  ASSERT_NE(hdr, nullptr);
  for (vtkIdType i = 0; i < 64; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      ASSERT_TRUE(std::isfinite(hdr->GetComponent(i, c)));
      ASSERT_GE(hdr->GetComponent(i, c), 0.0);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Environment map (vtkRefractaEnvironmentMap, VTK's skybox convention with the default up +y and
// right +x): an empty medium seen along +x shows the map at u = 0.75, v = 0.5 (bilinear between
// the four pixels around that point); 8-bit maps are divided by 255.
TEST(ReferenceRenderer, EnvironmentMapLookup)
{
  const int dims[3] = { 2, 2, 2 };
  const double spacing[3] = { 1, 1, 1 }, origin[3] = { 0, 0, 0 };
  auto medium = Homogeneous(dims, spacing, origin, Voxel{});
  vtkNew<vtkImageData> env;
  env->SetDimensions(4, 2, 1);
  vtkNew<vtkFloatArray> s;
  s->SetNumberOfComponents(3);
  s->SetNumberOfTuples(8);
  for (int p = 0; p < 8; ++p)
  {
    s->SetTuple3(p, p, 10 * p, 100 * p);
  }
  env->GetPointData()->SetScalars(s);
  const double focal[3] = { 0.5, 0.5, 0.5 }, dop[3] = { 1, 0, 0 }, up[3] = { 0, 0, 1 };
  vtkNew<vtkReferenceRenderer> r;
  r->SetInputData(medium);
  r->SetCamera(ParallelCamera(focal, dop, up, 1.0));
  r->SetEnvironmentMap(env);
  r->SetImageSize(2, 2);
  r->SetSamplesPerPixel(Spp(2));
  r->Update();
  // u = 0.75 -> fx = 0.75 * 4 - 0.5 = 2.5 (between columns 2 and 3); v = 0.5 -> fy = 0.5 (rows
  // 0, 1).
  const double expected = 0.25 * (2 + 3 + 6 + 7);
  vtkDataArray* hdr = r->GetOutput()->GetPointData()->GetArray("HDR");
  ASSERT_NE(hdr, nullptr);
  EXPECT_NEAR(hdr->GetComponent(0, 0), expected, 1e-5);
  EXPECT_NEAR(hdr->GetComponent(0, 1), 10 * expected, 1e-4);
  // Rays travelling -y (the -up pole): v = 0 -> bottom row, constant.
  const double dop2[3] = { 0, -1, 0 }, up2[3] = { 0, 0, 1 };
  r->SetCamera(ParallelCamera(focal, dop2, up2, 1.0));
  r->Update();
  hdr = r->GetOutput()->GetPointData()->GetArray("HDR");
  // Bottom row (0..3) at v = 0 clamps to row 0; u = atan2(0, 0) / 2pi + 1/2 = 0.5: columns 1, 2.
  EXPECT_NEAR(hdr->GetComponent(0, 0), 1.5, 1e-5);
}

// ---------------------------------------------------------------------------------------------
// Bad inputs: a clear error, RequestData fails, the output is empty.
TEST(ReferenceRenderer, BadInputsGiveClearErrors)
{
  const int dims[3] = { 3, 3, 3 };
  const double spacing[3] = { 1, 1, 1 }, origin[3] = { 0, 0, 0 };
  Voxel good;
  good.Sigma[0] = good.Sigma[1] = good.Sigma[2] = 1;
  auto medium = Homogeneous(dims, spacing, origin, good);
  const double focal[3] = { 1, 1, 1 }, dop[3] = { 0, 0, -1 }, up[3] = { 0, 1, 0 };
  auto run = [](vtkReferenceRenderer* r, const char* expect)
  {
    vtkNew<vtkTest::ErrorObserver> obs, execObs;
    r->AddObserver(vtkCommand::ErrorEvent, obs);
    r->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, execObs);
    r->Modified();
    r->Update();
    EXPECT_TRUE(obs->GetError()) << expect;
    EXPECT_NE(obs->GetErrorMessage().find(expect), std::string::npos)
      << "message: " << obs->GetErrorMessage();
    EXPECT_EQ(r->GetOutput()->GetNumberOfPoints(), 0);
  };
  {
    vtkNew<vtkReferenceRenderer> r; // no camera
    r->SetInputData(medium);
    r->SetImageSize(4, 4);
    run(r, "SetCamera");
  }
  {
    Voxel bad = good;
    bad.Albedo[1] = 2.0;
    auto badMedium = Homogeneous(dims, spacing, origin, bad);
    vtkNew<vtkReferenceRenderer> r;
    r->SetInputData(badMedium);
    r->SetCamera(ParallelCamera(focal, dop, up, 1.0));
    r->SetImageSize(4, 4);
    run(r, "Albedo");
  }
  {
    vtkNew<vtkImageData> notMedium; // scalars but no medium array
    notMedium->SetDimensions(3, 3, 3);
    notMedium->AllocateScalars(VTK_FLOAT, 1);
    vtkNew<vtkReferenceRenderer> r;
    r->SetInputData(notMedium);
    r->SetCamera(ParallelCamera(focal, dop, up, 1.0));
    r->SetImageSize(4, 4);
    run(r, "not a valid Refracta medium");
  }
  {
    vtkNew<vtkImageData> env;
    env->SetDimensions(4, 2, 1);
    env->AllocateScalars(VTK_FLOAT, 5); // 1 to 4 components (grey to RGBA) are maps
    vtkNew<vtkReferenceRenderer> r;
    r->SetInputData(medium);
    r->SetCamera(ParallelCamera(focal, dop, up, 1.0));
    r->SetEnvironmentMap(env);
    r->SetImageSize(4, 4);
    run(r, "EnvironmentMap");
  }
  {
    vtkNew<vtkReferenceRenderer> r;
    r->SetInputData(medium);
    const double badUp[3] = { 0, 0, 1 };
    r->SetCamera(ParallelCamera(focal, dop, badUp, 1.0));
    r->SetImageSize(4, 4);
    run(r, "view up");
  }
  {
    vtkNew<vtkReferenceRenderer> r;
    r->SetInputData(medium);
    r->SetCamera(ParallelCamera(focal, dop, up, 1.0));
    r->SetBackgroundColor(-1, 0, 0);
    r->SetImageSize(4, 4);
    run(r, "BackgroundColor");
  }
  {
    vtkNew<vtkReferenceRenderer> r;
    r->SetInputData(medium);
    r->SetCamera(ParallelCamera(focal, dop, up, 1.0));
    vtkNew<vtkLight> degenerate; // directional, position == focal point
    degenerate->PositionalOff();
    degenerate->SetPosition(1, 2, 3);
    degenerate->SetFocalPoint(1, 2, 3);
    r->AddLight(degenerate);
    r->SetImageSize(4, 4);
    run(r, "direction is undefined");
  }
  // TraceRay on an invalid medium.
  {
    vtkNew<vtkReferenceRenderer> r;
    vtkNew<vtkTest::ErrorObserver> obs;
    r->AddObserver(vtkCommand::ErrorEvent, obs);
    vtkNew<vtkImageData> empty;
    const double o[3] = { 0, 0, 0 }, d[3] = { 1, 0, 0 };
    double e[3], ed[3];
    EXPECT_EQ(r->TraceRay(empty, o, d, 1.0, e, ed), -1);
    EXPECT_TRUE(obs->GetError());
  }
  // Clamped settings.
  vtkNew<vtkReferenceRenderer> r;
  r->SetImageSize(0, -3);
  EXPECT_EQ(r->GetImageSize()[0], 1);
  EXPECT_EQ(r->GetImageSize()[1], 1);
  r->SetSamplesPerPixel(0);
  EXPECT_EQ(r->GetSamplesPerPixel(), 1);
}
