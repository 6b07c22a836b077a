// Empty-space skipping in the view pass must not change the image beyond float rounding.
//
// Scene: a 48^3 grid (unit box) that is empty except for small objects, each exercising one reason
// a macro cell must be marched:
//   A  a hard-edged ball of extinction + emission + Radiance (with RadianceDirection, HG g) +
//      MultipleScattering: samples between an empty and an occupied voxel are nonzero (the
//      trilinear footprint the occupancy grid must dilate for);
//   B  a hard-edged ball of MultipleScattering only (no extinction): lighting alone makes a cell
//      active;
//   C  a smooth lens of refractive index (compact support, ambient n = 1.1 != 1) with no
//      extinction: curved rays bend there and must not be skipped, and since only grad n enters the
//      ray equation, rays are straight (and may be skipped) everywhere else.
// Behind it an equirectangular environment map, seen in each ray's bent exit direction.
// Every configuration (perspective / parallel / camera inside the grid; straight / curved; a
// per-pixel depth limit; a MaxSteps cap that traps rays midway; macro cells of 2, 8 and 64 voxels)
// is rendered with skipping off and on; the assertion is
//   max |on - off| <= tol * max |off| + 1e-7 over all RGBA values (and the same for the path
// transmittance), with tol = 0 (bitwise equal) for straight rays, 2e-5 with a depth limit and
// 1e-4 for curved rays. Skipping keeps each ray's step grid, so straight rays add exactly the same
// terms (skipped steps contribute exactly 0 and multiply T by exactly 1); a depth limit compares
// an accumulated path length (rounding), and curved rays land on positions that differ by
// rounding, which the lens and the environment's stripes amplify. Without the 2-voxel dilation of
// the macro cells (trilinear footprint ignored), 4 of the 6 configurations fail, with differences
// of 2e-3 to 4e-2. The test also asserts that skipping happened (the skipping kernel ran, well
// under half of the macro cells are active, and far fewer steps were marched), so it cannot pass
// by never skipping.
#include "RenderingTestUtilities.h"

#include "vtkCamera.h"
#include "vtkFieldData.h"
#include "vtkLight.h"
#include "vtkMath.h"
#include "vtkPhotonTracer.h"
#include "vtkRefractaImageRenderer.h"
#include "vtkRefractaLightingVolume.h"
#include "vtkRefractaViewPass.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

namespace
{
const int N = 48;

struct Scene
{
  vtkSmartPointer<vtkImageData> Medium;
  vtkSmartPointer<vtkImageData> Lighting;
  vtkSmartPointer<vtkImageData> Environment;
};

double Distance(const double p[3], double x, double y, double z)
{
  return std::sqrt((p[0] - x) * (p[0] - x) + (p[1] - y) * (p[1] - y) + (p[2] - z) * (p[2] - z));
}

Scene MakeScene(bool refractive)
{
  Scene scene;
  const double s = 1.0 / N;
  scene.Medium = refracta_test::MakeGrid(N, N, N, s);
  vtkFloatArray* extinction = refracta_test::AddConstant(scene.Medium, "Extinction", 3, 0, 0, 0);
  vtkFloatArray* emission = refracta_test::AddConstant(scene.Medium, "Emission", 3, 0, 0, 0);
  refracta_test::AddConstant(scene.Medium, "Albedo", 3, 0.8, 0.8, 0.8);
  refracta_test::AddConstant(scene.Medium, "Anisotropy", 1, 0.5);
  vtkFloatArray* index =
    refractive ? refracta_test::AddConstant(scene.Medium, "RefractiveIndex", 1, 1.1) : nullptr;
  scene.Lighting = vtkSmartPointer<vtkImageData>::New();
  scene.Lighting->CopyStructure(scene.Medium);
  vtkFloatArray* radiance = refracta_test::AddConstant(
    scene.Lighting, vtkRefractaLightingVolume::RadianceName(), 3, 0, 0, 0);
  vtkFloatArray* direction = refracta_test::AddConstant(
    scene.Lighting, vtkRefractaLightingVolume::RadianceDirectionName(), 3, 0, 0, 1);
  vtkFloatArray* multiple = refracta_test::AddConstant(
    scene.Lighting, vtkRefractaLightingVolume::MultipleScatteringName(), 3, 0, 0, 0);
  const double a[3] = { 0.3, 0.35, 0.6 }, b[3] = { 0.72, 0.62, 0.3 }, c[3] = { 0.58, 0.4, 0.42 };
  for (int k = 0; k < N; ++k)
  {
    for (int j = 0; j < N; ++j)
    {
      for (int i = 0; i < N; ++i)
      {
        const vtkIdType id = i + N * (j + static_cast<vtkIdType>(N) * k);
        const double p[3] = { i * s, j * s, k * s };
        if (Distance(p, a[0], a[1], a[2]) < 0.09)
        {
          extinction->SetTuple3(id, 14, 9, 4);
          emission->SetTuple3(id, 0.8, 1.2, 0.4);
          radiance->SetTuple3(id, 2.0, 1.5, 1.0);
          direction->SetTuple3(id, 0.6, 0.0, 0.8);
          multiple->SetTuple3(id, 1.0, 2.0, 3.0);
        }
        if (Distance(p, b[0], b[1], b[2]) < 0.07)
        {
          multiple->SetTuple3(id, 6.0, 3.0, 1.0);
        }
        const double r = Distance(p, c[0], c[1], c[2]) / 0.14;
        if (index && r < 1)
        {
          index->SetValue(id, static_cast<float>(1.1 + 0.35 * (1 - r * r) * (1 - r * r)));
        }
      }
    }
  }
  // Equirectangular environment: smooth in longitude, stripes in latitude.
  const int ew = 64, eh = 32;
  scene.Environment = refracta_test::MakeGrid(ew, eh, 1, 1.0);
  vtkNew<vtkFloatArray> rgb;
  rgb->SetNumberOfComponents(3);
  rgb->SetNumberOfTuples(ew * eh);
  for (int j = 0; j < eh; ++j)
  {
    for (int i = 0; i < ew; ++i)
    {
      rgb->SetTuple3(i + ew * j, 0.5 + 0.5 * std::sin(6.283 * i / ew * 3), (j + 0.5) / eh,
        (j / 4) % 2 ? 0.9 : 0.1);
    }
  }
  scene.Environment->GetPointData()->SetScalars(rgb);
  return scene;
}

struct Config
{
  const char* Name;
  bool Refractive;
  int RayMode;
  bool Parallel;
  bool Inside; // camera inside the grid
  bool DepthLimit;
  int MaxSteps;
  int CellSize;
  bool ExpectSkip = true; // false where one macro cell covers the grid (nothing to skip)
};

void SetCamera(vtkCamera* camera, const Config& config)
{
  camera->SetFocalPoint(0.5, 0.5, 0.5);
  if (config.Inside)
  {
    camera->SetPosition(0.9, 0.85, 0.95); // inside [-s/2, 1 - s/2]^3
    camera->SetFocalPoint(0.4, 0.45, 0.45);
    camera->SetViewAngle(70);
  }
  else
  {
    camera->SetPosition(1.7, 1.2, 2.3);
    camera->SetViewAngle(35);
  }
  camera->SetViewUp(0, 1, 0);
  camera->SetParallelProjection(config.Parallel);
  camera->SetParallelScale(0.62);
}

void CheckConfig(const Config& config)
{
  SCOPED_TRACE(config.Name);
  const Scene scene = MakeScene(config.Refractive);
  vtkNew<vtkRefractaViewPass> pass;
  pass->SetRayMode(config.RayMode);
  pass->SetMaxSteps(config.MaxSteps);
  pass->SetMacroCellSize(config.CellSize);
  pass->SetEnvironmentMap(scene.Environment);
  ASSERT_TRUE(pass->SetMedium(scene.Medium));
  ASSERT_TRUE(pass->SetLighting(scene.Lighting));
  vtkNew<vtkCamera> camera;
  SetCamera(camera, config);
  const int w = 64, h = 56;
  const std::vector<float> depth = refracta_test::HashedDepthLimits(w, h, 3.0);
  const float* limit = config.DepthLimit ? depth.data() : nullptr;
  std::vector<float> off, on, offT, onT;
  pass->EmptySpaceSkippingOff();
  ASSERT_TRUE(pass->Render(camera, w, h, nullptr, limit, off, &offT));
  EXPECT_FALSE(pass->GetLastSkipping());
  const double stepsOff = pass->GetLastTotalSteps();
  pass->EmptySpaceSkippingOn();
  ASSERT_TRUE(pass->Render(camera, w, h, nullptr, limit, on, &onT));
  EXPECT_EQ(pass->GetLastSkipping(), config.ExpectSkip);
  EXPECT_EQ(
    pass->GetLastCurved(), config.Refractive && config.RayMode != vtkRefractaViewPass::STRAIGHT);
  const double stepsOn = pass->GetLastTotalSteps();
  const double fraction = pass->GetLastActiveCellFraction();

  const double scale = refracta_test::MaxAbs(off);
  const double diff = refracta_test::MaxDiff(on, off);
  const double diffT = refracta_test::MaxDiff(onT, offT);
  std::cout << config.Name << ": max |on - off| = " << diff << " (image max " << scale
            << "), transmittance " << diffT << ", active cells " << fraction << ", steps "
            << stepsOn << " vs " << stepsOff << " (" << stepsOff / std::max(stepsOn, 1.0)
            << "x fewer)\n";
  EXPECT_GT(scale, 0.3); // the scene is visible
  // Straight rays without a depth limit add exactly the same terms: bitwise equal. A depth limit
  // compares the accumulated path length (k steps at once vs one by one: rounding). Curved rays
  // land on positions that differ by rounding, which the lens and the environment's stripes
  // (0.8 per texel) amplify to ~1e-5.
  const double tolerance = config.Refractive ? 1e-4 : (config.DepthLimit ? 2e-5 : 0.0);
  EXPECT_LE(diff, tolerance * scale + (tolerance > 0 ? 1e-7 : 0.0));
  EXPECT_LE(diffT, tolerance + (tolerance > 0 ? 1e-7 : 0.0));
  if (config.ExpectSkip)
  {
    EXPECT_LT(fraction, 0.5);
    EXPECT_LT(stepsOn, 0.6 * stepsOff);
  }
  else
  {
    EXPECT_EQ(fraction, 1.0);
    EXPECT_EQ(diff, 0.0);
  }
}
}

TEST(ViewPassSkipping, StraightPerspective)
{
  CheckConfig(
    { "straight perspective", false, vtkRefractaViewPass::STRAIGHT, false, false, false, 0, 8 });
}

TEST(ViewPassSkipping, StraightParallelDepthLimit)
{
  CheckConfig({ "straight parallel, depth limit", false, vtkRefractaViewPass::AUTO, true, false,
    true, 0, 8 });
}

TEST(ViewPassSkipping, StraightCameraInsideCellSizes)
{
  CheckConfig({ "straight, camera inside, cells of 2", false, vtkRefractaViewPass::STRAIGHT, false,
    true, false, 0, 2 });
  CheckConfig({ "straight, camera inside, cells of 64 (clamped grid)", false,
    vtkRefractaViewPass::STRAIGHT, false, true, false, 0, 64, false });
}

TEST(ViewPassSkipping, CurvedPerspectiveEnvironment)
{
  CheckConfig(
    { "curved perspective", true, vtkRefractaViewPass::CURVED, false, false, false, 0, 8 });
}

TEST(ViewPassSkipping, CurvedParallelDepthLimitCells4)
{
  CheckConfig({ "curved parallel, depth limit, cells of 4", true, vtkRefractaViewPass::AUTO, true,
    false, true, 0, 4 });
}

TEST(ViewPassSkipping, CurvedCameraInsideMaxStepsCap)
{
  // MaxSteps 40 traps rays midway (no background): the cap counts skipped steps too.
  CheckConfig({ "curved, camera inside, MaxSteps 40", true, vtkRefractaViewPass::CURVED, false,
    true, false, 40, 8 });
}

// The lens makes grad n nonzero only around C: straight rays through the same medium may skip the
// lens's cells, curved rays may not.
TEST(ViewPassSkipping, GradientCellsOnlyMatterForCurvedRays)
{
  const Scene scene = MakeScene(true);
  vtkNew<vtkRefractaViewPass> pass;
  ASSERT_TRUE(pass->SetMedium(scene.Medium));
  ASSERT_TRUE(pass->SetLighting(scene.Lighting));
  vtkNew<vtkCamera> camera;
  SetCamera(camera, { "", true, 0, false, false, false, 0, 8 });
  std::vector<float> hdr;
  pass->SetRayMode(vtkRefractaViewPass::STRAIGHT);
  ASSERT_TRUE(pass->Render(camera, 16, 16, nullptr, nullptr, hdr));
  const double straight = pass->GetLastActiveCellFraction();
  pass->SetRayMode(vtkRefractaViewPass::CURVED);
  ASSERT_TRUE(pass->Render(camera, 16, 16, nullptr, nullptr, hdr));
  const double curved = pass->GetLastActiveCellFraction();
  EXPECT_GT(curved, straight);
  EXPECT_LT(curved, 0.5);
}

// The real pipeline: a photon-traced lighting volume (whose smoothed Radiance reaches into the
// vacuum around the object, where it still adds to the view-pass sum) through the image renderer,
// skipping off and on: the same HDR image (straight rays: bitwise).
TEST(ViewPassSkipping, PhotonTracedLightingThroughImageRenderer)
{
  const int n = 32;
  auto medium = refracta_test::MakeGrid(n, n, n, 1.0 / n);
  vtkFloatArray* extinction = refracta_test::AddConstant(medium, "Extinction", 3, 0, 0, 0);
  refracta_test::AddConstant(medium, "Albedo", 3, 0.9, 0.8, 0.7);
  int objectVoxels = 0;
  for (int k = 0; k < n; ++k)
  {
    for (int j = 0; j < n; ++j)
    {
      for (int i = 0; i < n; ++i)
      {
        const double p[3] = { double(i) / n, double(j) / n, double(k) / n };
        if (Distance(p, 0.4, 0.5, 0.5) < 0.12)
        {
          extinction->SetTuple3(i + n * (j + static_cast<vtkIdType>(n) * k), 20, 20, 20);
          ++objectVoxels;
        }
      }
    }
  }
  vtkNew<vtkPhotonTracer> tracer;
  tracer->SetInputData(medium);
  vtkNew<vtkLight> light;
  light->SetPositional(false);
  light->SetPosition(3, 3, 3);
  light->SetFocalPoint(0.5, 0.5, 0.5);
  tracer->AddLight(light);
  tracer->SetNumberOfPhotons(20000);
  tracer->Update();
  vtkDataArray* radiance =
    tracer->GetOutput()->GetPointData()->GetArray(vtkRefractaLightingVolume::RadianceName());
  ASSERT_NE(radiance, nullptr);
  int lit = 0;
  for (vtkIdType i = 0; i < radiance->GetNumberOfTuples(); ++i)
  {
    lit += radiance->GetComponent(i, 0) + radiance->GetComponent(i, 1) > 0 ? 1 : 0;
  }
  std::cout << "photon-traced Radiance is nonzero in " << lit << " voxels, the object has "
            << objectVoxels << "\n";

  vtkNew<vtkRefractaImageRenderer> renderer;
  renderer->SetInputData(medium);
  renderer->SetInputConnection(1, tracer->GetOutputPort());
  vtkNew<vtkCamera> camera;
  camera->SetPosition(1.5, 1.1, 2.2);
  camera->SetFocalPoint(0.5, 0.5, 0.5);
  renderer->SetCamera(camera);
  renderer->SetImageSize(48, 48);
  std::vector<float> images[2];
  for (int on = 0; on < 2; ++on)
  {
    renderer->SetEmptySpaceSkipping(on == 1);
    renderer->Update();
    vtkImageData* out = renderer->GetOutput();
    EXPECT_EQ(out->GetFieldData()->GetArray("EmptySpaceSkipping")->GetTuple1(0), on);
    vtkFloatArray* hdr = vtkFloatArray::SafeDownCast(out->GetPointData()->GetArray("HDR"));
    ASSERT_NE(hdr, nullptr);
    images[on].assign(hdr->GetPointer(0), hdr->GetPointer(0) + hdr->GetNumberOfValues());
  }
  EXPECT_GT(refracta_test::MaxAbs(images[0]), 1e-3); // the lit object is visible
  EXPECT_EQ(refracta_test::MaxDiff(images[0], images[1]), 0.0);
}

// Edge cases: an all-vacuum medium (every cell empty: the image is exactly the background), a
// 1 x 1 x 1 grid, clamped knobs, and the image renderer's knob and field data.
TEST(ViewPassSkipping, EdgeCasesAndKnobs)
{
  vtkNew<vtkRefractaViewPass> pass;
  pass->SetMacroCellSize(-3);
  EXPECT_EQ(pass->GetMacroCellSize(), 2);
  pass->SetMacroCellSize(1000);
  EXPECT_EQ(pass->GetMacroCellSize(), 64);
  EXPECT_TRUE(pass->GetEmptySpaceSkipping());

  auto vacuum = refracta_test::MakeGrid(20, 20, 20, 0.05);
  refracta_test::AddConstant(vacuum, "Extinction", 3, 0, 0, 0);
  pass->SetBackgroundColor(0.2, 0.4, 0.6);
  ASSERT_TRUE(pass->SetMedium(vacuum));
  vtkNew<vtkCamera> camera;
  camera->SetPosition(0.5, 0.5, 3);
  camera->SetFocalPoint(0.5, 0.5, 0.5);
  std::vector<float> hdr;
  ASSERT_TRUE(pass->Render(camera, 24, 24, nullptr, nullptr, hdr));
  EXPECT_TRUE(pass->GetLastSkipping());
  EXPECT_EQ(pass->GetLastActiveCellFraction(), 0.0);
  for (size_t p = 0; p < hdr.size(); p += 4)
  {
    ASSERT_EQ(hdr[p], 0.2f);
    ASSERT_EQ(hdr[p + 1], 0.4f);
    ASSERT_EQ(hdr[p + 2], 0.6f);
    ASSERT_EQ(hdr[p + 3], 0.0f);
  }
  // At most 3 steps per ray: the jump to the exit and the step(s) that leave.
  EXPECT_LE(pass->GetLastTotalSteps(), 3.0 * 24 * 24);

  auto tiny = refracta_test::MakeGrid(1, 1, 1, 0.1);
  refracta_test::AddConstant(tiny, "Extinction", 3, 5, 5, 5);
  ASSERT_TRUE(pass->SetMedium(tiny));
  camera->SetPosition(0, 0, 0.3);
  camera->SetFocalPoint(0, 0, 0);
  ASSERT_TRUE(pass->Render(camera, 8, 8, nullptr, nullptr, hdr));
  EXPECT_FALSE(pass->GetLastSkipping()); // its only cell is active: the plain kernel runs
  EXPECT_GT(hdr[4 * (4 + 8 * 4) + 3], 0.3f);

  // The image renderer forwards the knob and records what happened.
  const Scene scene = MakeScene(false);
  vtkNew<vtkRefractaImageRenderer> renderer;
  renderer->SetInputData(scene.Medium);
  renderer->SetLightingData(scene.Lighting);
  vtkNew<vtkCamera> view;
  SetCamera(view, { "", false, 0, false, false, false, 0, 8 });
  renderer->SetCamera(view);
  renderer->SetImageSize(32, 32);
  renderer->Update();
  vtkFieldData* fd = renderer->GetOutput()->GetFieldData();
  ASSERT_NE(fd->GetArray("EmptySpaceSkipping"), nullptr);
  EXPECT_EQ(fd->GetArray("EmptySpaceSkipping")->GetTuple1(0), 1.0);
  EXPECT_LT(fd->GetArray("ActiveCellFraction")->GetTuple1(0), 0.5);
  renderer->EmptySpaceSkippingOff();
  EXPECT_FALSE(renderer->GetEmptySpaceSkipping());
  renderer->Update();
  fd = renderer->GetOutput()->GetFieldData();
  EXPECT_EQ(fd->GetArray("EmptySpaceSkipping")->GetTuple1(0), 0.0);
  EXPECT_EQ(fd->GetArray("ActiveCellFraction")->GetTuple1(0), 1.0);
}
