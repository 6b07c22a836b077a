// The eight-lane view-pass kernel (vtkRefractaViewPass::LaneMarching, Kernels/view_lanes.cl) must
// render what the general kernel renders, and run only where it applies.
//
// Scene: a 40 x 33 x 29 grid with a far origin, unequal spacings and a rotated frame, holding an
// emission-absorption medium of grey extinction (the packed layout vtkTransferFunctionMedium
// produces): a soft ball of extinction 6-30 per unit with RGB emission, a thick slab (extinction
// 400 per unit: steps of optical depth > 1/2, the exp branch of the step integration) and empty
// space around them (macro cells to skip). The lit variant gives the ball an RGB extinction,
// albedo, HG anisotropy g = 0.6 and a varying refractive index (sources weighted 1 / n^2 per step,
// rays kept straight), and adds a lighting volume: single-scattered Radiance with a
// RadianceDirection that turns across the grid, and MultipleScattering. Every configuration renders
// an image whose width is not a multiple of 8 (lanes past the edge) with LaneMarching off (the
// general kernel) and on, and asserts that the lane kernel ran, that the steps marched are the
// same, and that
//   max |on - off| <= 1e-5 max |off| + 1e-7 over RGBA and the path transmittance:
// the two kernels take the same steps at the same positions and differ by float rounding only
// (the step weight's exp in SIMD lanes, and the order of a few operations). Configurations:
// perspective from outside with skipping and the default cutoff; parallel with a per-pixel depth
// limit and an environment map; the camera inside the grid with a MaxSteps cap that stops rays
// midway and a uniform refractive index n = 1.3 (sources count 1 / n^2); cutoff 0 through the
// thick slab; the lit medium with skipping (perspective) and without (parallel, depth limit);
// curved rays through the lit medium (its varying n) with skipping and an environment, in parallel
// with a depth limit, and from inside with a step cap (bound 1e-4: the bending carries rounding).
// Both kernels' background part (Render's `background`) agrees the same way, and is exactly what
// the background adds: the image less it equals the render against a black background; where a
// depth limit (opaque geometry) ends a ray, even after it left the box, it is 0.
// Breaking the kernel's bookkeeping (e.g. not masking ended lanes, or taking the background for
// rays stopped by the cap) fails these by O(0.1). Scenes the lane kernel cannot render (lighting,
// curved rays) must use the general kernel.
#include "RenderingTestUtilities.h"

#include "vtkCamera.h"
#include "vtkFieldData.h"
#include "vtkMath.h"
#include "vtkMatrix3x3.h"
#include "vtkPlaneSource.h"
#include "vtkRefractaImageRenderer.h"
#include "vtkRefractaLightingVolume.h"
#include "vtkRefractaSurfaceSet.h"
#include "vtkRefractaViewPass.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

namespace
{
const int NX = 40, NY = 33, NZ = 29;

// The medium; with `index` a uniform RefractiveIndex n = 1.3; `lit`: see the file comment.
vtkSmartPointer<vtkImageData> Medium(bool index, bool lit = false)
{
  const double origin[3] = { 250.0, -120.0, 35.0 };
  auto medium = refracta_test::MakeGrid(NX, NY, NZ, 0.025, origin);
  medium->SetSpacing(0.025, 0.03, 0.035);
  const double a = vtkMath::RadiansFromDegrees(25.0), b = vtkMath::RadiansFromDegrees(-15.0);
  const double rz[9] = { std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a), 0, 0, 0, 1 };
  const double rx[9] = { 1, 0, 0, 0, std::cos(b), -std::sin(b), 0, std::sin(b), std::cos(b) };
  double m[9];
  vtkMatrix3x3::Multiply3x3(rx, rz, m);
  medium->SetDirectionMatrix(m);
  vtkFloatArray* extinction = refracta_test::AddConstant(medium, "Extinction", 3, 0, 0, 0);
  vtkFloatArray* emission = refracta_test::AddConstant(medium, "Emission", 3, 0, 0, 0);
  vtkFloatArray* n =
    index || lit ? refracta_test::AddConstant(medium, "RefractiveIndex", 1, 1.3) : nullptr;
  if (lit)
  {
    refracta_test::AddConstant(medium, "Albedo", 3, 0.8, 0.7, 0.6);
    refracta_test::AddConstant(medium, "Anisotropy", 1, 0.6);
  }
  for (int k = 0; k < NZ; ++k)
  {
    for (int j = 0; j < NY; ++j)
    {
      for (int i = 0; i < NX; ++i)
      {
        const vtkIdType id = i + NX * (j + static_cast<vtkIdType>(NY) * k);
        const double x = (i - 14.0) / 9.0, y = (j - 15.0) / 9.0, z = (k - 12.0) / 8.0;
        const double r2 = x * x + y * y + z * z;
        if (r2 < 1.0)
        {
          const double s = 6.0 + 24.0 * (1.0 - r2);
          extinction->SetTuple3(id, s, lit ? 0.7 * s : s, lit ? 0.4 * s : s);
          if (lit)
          {
            n->SetValue(id, static_cast<float>(1.3 + 0.2 * (1.0 - r2)));
          }
          emission->SetTuple3(id, 3.0 * (1.0 - r2), 1.0 + x, 2.0 * std::abs(y));
        }
        else if (i >= 31 && i <= 34 && j >= 4 && j <= 28 && k >= 5 && k <= 24)
        {
          extinction->SetTuple3(id, 400.0, 400.0, 400.0); // a thick slab: tau > 1/2 per step
          emission->SetTuple3(id, 0.5, 2.0, 0.25);
        }
      }
    }
  }
  return medium;
}

// The lighting volume of the lit medium.
vtkSmartPointer<vtkImageData> Lighting(vtkImageData* medium)
{
  auto lighting = vtkSmartPointer<vtkImageData>::New();
  lighting->CopyStructure(medium);
  vtkFloatArray* radiance =
    refracta_test::AddConstant(lighting, vtkRefractaLightingVolume::RadianceName(), 3, 0, 0, 0);
  vtkFloatArray* direction = refracta_test::AddConstant(
    lighting, vtkRefractaLightingVolume::RadianceDirectionName(), 3, 0, 0, 1);
  vtkFloatArray* multiple = refracta_test::AddConstant(
    lighting, vtkRefractaLightingVolume::MultipleScatteringName(), 3, 0, 0, 0);
  for (int k = 0; k < NZ; ++k)
  {
    for (int j = 0; j < NY; ++j)
    {
      for (int i = 0; i < NX; ++i)
      {
        const vtkIdType id = i + NX * (j + static_cast<vtkIdType>(NY) * k);
        const double x = (i - 14.0) / 9.0, y = (j - 15.0) / 9.0, z = (k - 12.0) / 8.0;
        if (x * x + y * y + z * z < 1.3)
        {
          const double a = 0.15 * i;
          radiance->SetTuple3(id, 2.0 + x, 1.5, 1.0 + 0.5 * z);
          direction->SetTuple3(id, std::cos(a), std::sin(a), 0.0);
          multiple->SetTuple3(id, 0.5, 0.8 + 0.3 * y, 1.2);
        }
      }
    }
  }
  return lighting;
}

vtkSmartPointer<vtkImageData> Environment()
{
  const int ew = 32, eh = 16;
  auto image = refracta_test::MakeGrid(ew, eh, 1, 1.0);
  vtkNew<vtkFloatArray> rgb;
  rgb->SetNumberOfComponents(3);
  rgb->SetNumberOfTuples(ew * eh);
  for (int j = 0; j < eh; ++j)
  {
    for (int i = 0; i < ew; ++i)
    {
      rgb->SetTuple3(i + ew * j, 0.5 + 0.5 * std::sin(0.6 * i), (j + 0.5) / eh, (j / 2) % 2);
    }
  }
  image->GetPointData()->SetScalars(rgb);
  return image;
}

struct Config
{
  const char* Name;
  bool Parallel = false;
  bool Inside = false;
  bool DepthLimit = false;
  bool Environment = false;
  bool Index = false;
  bool Lit = false;
  bool Curved = false; // the lit medium's varying n bends the rays
  bool Skipping = true;
  int MaxSteps = 0;
  double Cutoff = 1e-4;
};

void SetCamera(vtkCamera* camera, const Config& config, vtkImageData* medium)
{
  double bounds[6]; // world bounds (through the grid's frame)
  medium->GetBounds(bounds);
  const double p[3] = { 0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3]),
    0.5 * (bounds[4] + bounds[5]) };
  camera->SetFocalPoint(p);
  if (config.Inside)
  {
    camera->SetPosition(p[0] + 0.2, p[1] + 0.1, p[2] + 0.15);
    camera->SetViewAngle(80);
  }
  else
  {
    camera->SetPosition(p[0] + 1.1, p[1] + 0.7, p[2] + 1.6);
    camera->SetViewAngle(40);
  }
  camera->SetViewUp(0, 1, 0);
  camera->SetParallelProjection(config.Parallel);
  camera->SetParallelScale(0.7);
}

void CheckConfig(const Config& config)
{
  SCOPED_TRACE(config.Name);
  vtkSmartPointer<vtkImageData> medium = Medium(config.Index, config.Lit);
  vtkNew<vtkRefractaViewPass> pass;
  // A uniform index gives straight rays; the lit medium's varying one bends them or is ignored.
  pass->SetRayMode(config.Curved
      ? vtkRefractaViewPass::CURVED
      : (config.Lit ? vtkRefractaViewPass::STRAIGHT : vtkRefractaViewPass::AUTO));
  pass->SetMaxSteps(config.MaxSteps);
  pass->SetTransmittanceCutoff(config.Cutoff);
  pass->SetEmptySpaceSkipping(config.Skipping);
  pass->SetBackgroundColor(0.1, 0.2, 0.3);
  if (config.Environment)
  {
    pass->SetEnvironmentMap(Environment());
  }
  ASSERT_TRUE(pass->SetMedium(medium));
  if (config.Lit)
  {
    ASSERT_TRUE(pass->SetLighting(Lighting(medium)));
  }
  vtkNew<vtkCamera> camera;
  SetCamera(camera, config, medium);
  const int w = 61, h = 43;
  const std::vector<float> depth = refracta_test::HashedDepthLimits(w, h, 2.5);
  const float* limit = config.DepthLimit ? depth.data() : nullptr;
  std::vector<float> off, on, offT, onT, offB, onB;
  pass->LaneMarchingOff();
  ASSERT_TRUE(pass->Render(camera, w, h, nullptr, limit, off, &offT, nullptr, &offB));
  EXPECT_FALSE(pass->GetLastLaneMarching());
  EXPECT_EQ(pass->GetLastCurved(), config.Curved);
  const double stepsOff = pass->GetLastTotalSteps();
  pass->LaneMarchingOn();
  ASSERT_TRUE(pass->Render(camera, w, h, nullptr, limit, on, &onT, nullptr, &onB));
  EXPECT_TRUE(pass->GetLastLaneMarching());
  EXPECT_EQ(pass->GetLastSkipping(), config.Skipping);
  const double stepsOn = pass->GetLastTotalSteps();

  const double scale = refracta_test::MaxAbs(off);
  const double diff = refracta_test::MaxDiff(on, off);
  const double diffT = refracta_test::MaxDiff(onT, offT);
  const double diffB = refracta_test::MaxDiff(onB, offB);
  std::cout << config.Name << ": max |lanes - general| = " << diff << " (image max " << scale
            << "), transmittance " << diffT << ", steps " << stepsOn << " vs " << stepsOff << "\n";
  EXPECT_GT(scale, 0.3); // the scene is visible
  EXPECT_EQ(stepsOn, stepsOff);
  // Curved rays integrate positions whose rounding (vector square roots, the order of a few
  // products) the bending carries along: a looser bound, as for skipping's curved rays.
  const double tolerance = config.Curved ? 1e-4 : 1e-5;
  EXPECT_LE(diff, tolerance * scale + 1e-7);
  EXPECT_LE(diffT, tolerance + 1e-7);
  EXPECT_LE(diffB, tolerance * scale + 1e-7);

  // The background part is exactly what the background adds: the same render against a black
  // background (no environment) is the image less that part, and has none.
  pass->SetBackgroundColor(0, 0, 0);
  pass->SetEnvironmentMap(nullptr);
  std::vector<float> black, blackB;
  ASSERT_TRUE(pass->Render(camera, w, h, nullptr, limit, black, nullptr, nullptr, &blackB));
  EXPECT_EQ(refracta_test::MaxAbs(blackB), 0.0);
  // Opaque geometry at a finite depth limit ends the ray even after it left the box: no
  // background there, from either kernel.
  double seen = 0.0, worst = 0.0, behindGeometry = 0.0;
  for (size_t p = 0; p < black.size(); p += 4)
  {
    for (int c = 0; c < 3; ++c)
    {
      seen = std::max(seen, static_cast<double>(onB[p + c]));
      worst = std::max(worst, std::abs(double(on[p + c]) - onB[p + c] - black[p + c]));
      if (limit && std::isfinite(limit[p / 4]))
      {
        behindGeometry = std::max({ behindGeometry, double(onB[p + c]), double(offB[p + c]) });
      }
    }
  }
  std::cout << "  background part up to " << seen << ", |L - B - L_black| <= " << worst << "\n";
  if (config.MaxSteps == 0 && !limit) // (a step cap or geometry stops every ray before it)
  {
    EXPECT_GT(seen, 0.05); // the background shows
  }
  EXPECT_EQ(behindGeometry, 0.0);
  EXPECT_LE(worst, tolerance * scale + 1e-6);
}
}

TEST(ViewPassLaneMarching, PerspectiveSkipping)
{
  CheckConfig({ "perspective, skipping" });
}

TEST(ViewPassLaneMarching, ParallelDepthLimitEnvironment)
{
  Config config{ "parallel, depth limit, environment" };
  config.Parallel = true;
  config.DepthLimit = true;
  config.Environment = true;
  config.Skipping = false;
  CheckConfig(config);
}

TEST(ViewPassLaneMarching, CameraInsideStepCapUniformIndex)
{
  Config config{ "camera inside, MaxSteps 23, n = 1.3" };
  config.Inside = true;
  config.Index = true;
  config.MaxSteps = 23;
  CheckConfig(config);
}

TEST(ViewPassLaneMarching, ThickSlabWithoutCutoff)
{
  Config config{ "cutoff 0 through the thick slab" };
  config.Cutoff = 0.0;
  CheckConfig(config);
}

TEST(ViewPassLaneMarching, LitMediumSkipping)
{
  Config config{ "lit: RGB extinction, single + multiple scattering, 1 / n^2, skipping" };
  config.Lit = true;
  CheckConfig(config);
}

TEST(ViewPassLaneMarching, LitMediumParallelDepthLimit)
{
  Config config{ "lit, parallel, depth limit, no skipping" };
  config.Lit = true;
  config.Parallel = true;
  config.DepthLimit = true;
  config.Skipping = false;
  CheckConfig(config);
}

TEST(ViewPassLaneMarching, CurvedSkippingEnvironment)
{
  Config config{ "curved, skipping, environment" };
  config.Lit = true;
  config.Curved = true;
  config.Environment = true;
  CheckConfig(config);
}

TEST(ViewPassLaneMarching, CurvedParallelDepthLimit)
{
  Config config{ "curved, parallel, depth limit, no skipping" };
  config.Lit = true;
  config.Curved = true;
  config.Parallel = true;
  config.DepthLimit = true;
  config.Skipping = false;
  CheckConfig(config);
}

TEST(ViewPassLaneMarching, CurvedCameraInsideStepCap)
{
  Config config{ "curved, camera inside, MaxSteps 23" };
  config.Lit = true;
  config.Curved = true;
  config.Inside = true;
  config.MaxSteps = 23;
  CheckConfig(config);
}

TEST(ViewPassLaneMarching, OnlyWhereItApplies)
{
  // Surfaces need the general kernel.
  vtkSmartPointer<vtkImageData> medium = Medium(false);
  vtkNew<vtkRefractaViewPass> pass;
  ASSERT_TRUE(pass->SetMedium(medium));
  vtkNew<vtkCamera> camera;
  SetCamera(camera, Config{ "" }, medium);
  std::vector<float> hdr;
  ASSERT_TRUE(pass->Render(camera, 16, 16, nullptr, nullptr, hdr));
  EXPECT_TRUE(pass->GetLastLaneMarching());

  double bounds[6];
  medium->GetBounds(bounds);
  vtkNew<vtkPlaneSource> floor;
  floor->SetOrigin(bounds[0] - 1, bounds[2] - 0.1, bounds[4] - 1);
  floor->SetPoint1(bounds[1] + 1, bounds[2] - 0.1, bounds[4] - 1);
  floor->SetPoint2(bounds[0] - 1, bounds[2] - 0.1, bounds[5] + 1);
  floor->Update();
  vtkNew<vtkRefractaSurfaceSet> surfaces;
  surfaces->AddSurface(floor->GetOutput());
  pass->SetSurfaces(surfaces);
  ASSERT_TRUE(pass->Render(camera, 16, 16, nullptr, nullptr, hdr));
  EXPECT_FALSE(pass->GetLastLaneMarching());
  pass->SetSurfaces(nullptr);
  ASSERT_TRUE(pass->Render(camera, 16, 16, nullptr, nullptr, hdr));
  EXPECT_TRUE(pass->GetLastLaneMarching());
}

TEST(ViewPassLaneMarching, ImagesNarrowerThanEightLanes)
{
  // Rows shorter than a work-item's eight pixels and widths that leave a partial work-item.
  vtkSmartPointer<vtkImageData> medium = Medium(false);
  vtkNew<vtkRefractaViewPass> pass;
  ASSERT_TRUE(pass->SetMedium(medium));
  vtkNew<vtkCamera> camera;
  SetCamera(camera, Config{ "" }, medium);
  const int sizes[][2] = { { 1, 1 }, { 3, 5 }, { 9, 2 }, { 17, 3 } };
  for (const auto& size : sizes)
  {
    SCOPED_TRACE(std::to_string(size[0]) + " x " + std::to_string(size[1]));
    std::vector<float> off, on;
    pass->LaneMarchingOff();
    ASSERT_TRUE(pass->Render(camera, size[0], size[1], nullptr, nullptr, off));
    pass->LaneMarchingOn();
    ASSERT_TRUE(pass->Render(camera, size[0], size[1], nullptr, nullptr, on));
    EXPECT_TRUE(pass->GetLastLaneMarching());
    ASSERT_EQ(on.size(), size_t(4) * size[0] * size[1]);
    EXPECT_LE(refracta_test::MaxDiff(on, off), 1e-5 * refracta_test::MaxAbs(off) + 1e-7);
  }
}

TEST(ViewPassLaneMarching, TheImageRendererSaysWhichKernelRan)
{
  vtkSmartPointer<vtkImageData> medium = Medium(false);
  vtkNew<vtkCamera> camera;
  SetCamera(camera, Config{ "" }, medium);
  vtkNew<vtkRefractaImageRenderer> renderer;
  renderer->SetInputData(medium);
  renderer->SetCamera(camera);
  renderer->SetImageSize(24, 16);
  renderer->Update();
  vtkDataArray* lanes = renderer->GetOutput()->GetFieldData()->GetArray("LaneMarching");
  ASSERT_NE(lanes, nullptr);
  EXPECT_EQ(lanes->GetTuple1(0), 1.0);
}
