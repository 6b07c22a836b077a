// Opaque surfaces in the view pass (vtkRefractaViewPass::SetSurfaces, Kernels/view_surfaces.cl).
//
// - A Lambertian plane under a point light, given the analytic irradiance per texel (E = I cos
//   theta / r^2 at the texel's centroid, the midpoint rule for the texel mean a photon estimate
//   gives): every pixel that sees the plane must show E(p) rho / pi at its hit point p within 1%
//   with the LINEAR_TEXEL reconstruction (NEAREST_TEXEL is measured and must be worse: that is
//   the filter's justification, Physics.md); the surface depth output is the hit distance, the
//   pixel opaque; pixels that miss the plane see the background. The plane lies outside (under)
//   the medium's grid, and a second plane stands beside it: rays that never meet the grid see it.
// - A plane behind a uniform absorbing slab (RGB extinction) is seen attenuated by exp(-tau),
//   tau = sigma times the chord through the slab, within 1% (the kernel integrates exactly, so
//   the error is float rounding); a small square inside the slab is seen through half of it.
// - A ball lens (n = 1.5, tanh boundary 0.7 voxel wide) in front of a plane whose left half is red
//   and right half blue: inside the silhouette the colours are swapped (the lens inverts), pixel
//   by pixel as an independent double-precision Snell's-law trace of the sharp sphere predicts,
//   outside a rim band and away from the colour edge's image (tolerances at the test).
// - Camera moves do not upload the surfaces again; moving a surface (its matrix) does.
// - Bad irradiance arrays are errors naming the array.
#include "SurfaceTestScene.h"

#include "vtkCamera.h"
#include "vtkFieldData.h"
#include "vtkLight.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkPhotonTracer.h"
#include "vtkPlaneSource.h"
#include "vtkPolyData.h"
#include "vtkRefractaBVH.h"
#include "vtkRefractaImageRenderer.h"
#include "vtkRefractaLightingVolume.h"
#include "vtkRefractaSurfaceMaterial.h"
#include "vtkRefractaSurfaceSet.h"
#include "vtkRefractaViewPass.h"
#include "vtkSphereSource.h"
#include "vtkTestErrorObserver.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>

namespace
{
using refracta_test::ClearMedium;
using refracta_test::Lighting;
using refracta_test::Material;
using refracta_test::PixelRay;
using refracta_test::Plane;
const double Pi = vtkMath::Pi();

}

//------------------------------------------------------------------------------
// Plane z = 0, [-1, 1]^2, under a point light of intensity I at (0.3, 0.2, 1); a clear medium
// grid floats above it at z in [0.55, 0.95] (so the plane is outside the grid), and a second
// plane x = 1.2 stands beside it. The camera looks down from z = 2.2.
TEST(ViewPassSurfaces, PointLightPlaneRadianceIsIrradianceTimesAlbedoOverPi)
{
  const double light[3] = { 0.3, 0.2, 1.0 }, intensity = 2.0;
  const double albedo[3] = { 0.5, 0.7, 0.9 };
  const double o0[3] = { -1, -1, 0 }, p1[3] = { 1, -1, 0 }, p2[3] = { -1, 1, 0 };
  const double sideX = 1.2;
  const double s0[3] = { sideX, -1, 0 }, s1[3] = { sideX, 1, 0 }, s2[3] = { sideX, -1, 1 };
  vtkNew<vtkRefractaSurfaceSet> set;
  set->AddSurface(Plane(o0, p1, p2), Material(albedo[0], albedo[1], albedo[2]));
  set->AddSurface(Plane(s0, s1, s2), Material(0.2, 0.2, 0.2));
  const double gridOrigin[3] = { -0.3, -0.3, 0.6 };
  auto medium = ClearMedium(4, 0.1, gridOrigin);
  auto lighting = Lighting(medium, set,
    [&](const double p[3], double e[3])
    {
      double toLight[3];
      vtkMath::Subtract(light, p, toLight);
      const double r2 = vtkMath::Dot(toLight, toLight);
      // cos theta against the plane's normal (z) for the floor, x for the side plane.
      const double cosTheta =
        std::abs(p[2]) < 1e-9 ? toLight[2] / std::sqrt(r2) : std::abs(toLight[0]) / std::sqrt(r2);
      e[0] = e[1] = e[2] = intensity * cosTheta / r2;
    });
  vtkNew<vtkCamera> camera;
  camera->SetPosition(0.1, 0.0, 2.2);
  camera->SetFocalPoint(0.1, 0.0, 0.0);
  camera->SetViewUp(0, 1, 0);
  camera->SetViewAngle(60);
  vtkNew<vtkRefractaViewPass> pass;
  pass->SetBackgroundColor(0.01, 0.02, 0.03);
  ASSERT_TRUE(pass->SetMedium(medium));
  ASSERT_TRUE(pass->SetLighting(lighting));
  pass->SetSurfaces(set);
  const int w = 96, h = 96;
  vtkRefractaViewPass::RayFrame frame;
  ASSERT_TRUE(vtkRefractaViewPass::ComputeRayFrame(camera, medium, nullptr, w, h, frame));

  double worst[2] = { 0, 0 }, mean[2] = { 0, 0 };
  for (int filter : { vtkRefractaViewPass::NEAREST_TEXEL, vtkRefractaViewPass::LINEAR_TEXEL })
  {
    pass->SetSurfaceFilter(filter);
    std::vector<float> hdr, transmittance, depth;
    ASSERT_TRUE(pass->Render(camera, w, h, nullptr, nullptr, hdr, &transmittance, &depth));
    int floor = 0, side = 0, missed = 0;
    for (int j = 0; j < h; ++j)
    {
      for (int i = 0; i < w; ++i)
      {
        const size_t p = i + static_cast<size_t>(w) * j;
        double o[3], d[3];
        PixelRay(frame, medium, i, j, w, h, o, d);
        const double t = -o[2] / d[2];
        const double hit[3] = { o[0] + t * d[0], o[1] + t * d[1], 0 };
        const double tSide = (sideX - o[0]) / d[0];
        const bool onSide = tSide > 0 && tSide < t && std::abs(o[1] + tSide * d[1]) < 1 &&
          o[2] + tSide * d[2] > 0 && o[2] + tSide * d[2] < 1;
        if (onSide)
        {
          ++side;
          EXPECT_EQ(hdr[4 * p + 3], 1.0f) << "a surface pixel is opaque";
          continue;
        }
        if (std::abs(hit[0]) > 1 || std::abs(hit[1]) > 1)
        {
          ++missed;
          EXPECT_NEAR(hdr[4 * p + 2], 0.03, 1e-6)
            << "a ray missing every surface sees the background";
          EXPECT_TRUE(std::isinf(depth[p]));
          EXPECT_EQ(transmittance[4 * p], 1.0f);
          continue;
        }
        // Keep clear of the plane's outline by half a pixel's footprint (a pixel centre there
        // may see either side).
        if (std::abs(hit[0]) > 0.98 || std::abs(hit[1]) > 0.98)
        {
          continue;
        }
        ++floor;
        double toLight[3];
        vtkMath::Subtract(light, hit, toLight);
        const double r2 = vtkMath::Dot(toLight, toLight);
        const double e = intensity * (toLight[2] / std::sqrt(r2)) / r2;
        for (int c = 0; c < 3; ++c)
        {
          const double want = e * albedo[c] / Pi;
          const double err = std::abs(hdr[4 * p + c] - want) / want;
          worst[filter] = std::max(worst[filter], err);
          mean[filter] += err / 3;
        }
        EXPECT_NEAR(depth[p], t, 1e-5 * t) << "surface depth at pixel " << i << "," << j;
        EXPECT_EQ(transmittance[4 * p + 1], 0.0f);
        EXPECT_EQ(hdr[4 * p + 3], 1.0f);
      }
    }
    mean[filter] /= std::max(floor, 1);
    std::cout << (filter == vtkRefractaViewPass::LINEAR_TEXEL ? "linear" : "nearest")
              << " texel: worst relative error " << worst[filter] << ", mean " << mean[filter]
              << " over " << floor << " pixels (" << side << " on the side plane, " << missed
              << " missing), texel size " << set->GetEffectiveTexelSize() << "\n";
    EXPECT_GT(floor, 4000);
    EXPECT_GT(side, 100);
    EXPECT_GT(missed, 100);
  }
  EXPECT_LE(worst[vtkRefractaViewPass::LINEAR_TEXEL], 0.01);
  EXPECT_LT(mean[vtkRefractaViewPass::LINEAR_TEXEL], mean[vtkRefractaViewPass::NEAREST_TEXEL]);
}

//------------------------------------------------------------------------------
// A mesh finer than its texels (a sphere of radius 0.5 with 96 x 48 segments, texels of 0.1: one
// texel per triangle) under a directional light, given the smooth sphere's irradiance
// E = I n.l per texel, once exact and once with 25% Gaussian noise per texel (what a photon
// estimate of few photons per triangle gives). Every pixel that sees the sphere where n.l > 0.3,
// inside 0.85 of its silhouette, is compared with E(p) rho / pi at the exact sphere's hit point.
// The corners shared by the triangles at a mesh point (vtkRefractaSurfaceSet build step 7) must
// (a) reproduce the smooth field within 0.5% RMS without noise (one texel per triangle is
// piecewise constant: about 1.5%) and (b) cut the noise by at least 2x against the hit texel
// alone (measured about 3x; without shared corners a one-texel triangle's linear reconstruction
// is its texel, and both are the same).
TEST(ViewPassSurfaces, FineMeshIsShadedContinuouslyAcrossItsTriangles)
{
  vtkNew<vtkSphereSource> source;
  source->SetRadius(0.5);
  source->SetThetaResolution(96);
  source->SetPhiResolution(48);
  source->Update();
  const double albedo = 0.6, intensity = 1.5;
  double l[3] = { 0.3, 0.2, 1.0 };
  vtkMath::Normalize(l);
  vtkNew<vtkRefractaSurfaceSet> set;
  set->AddSurface(source->GetOutput(), Material(albedo, albedo, albedo));
  set->SetTexelSize(0.1);
  const double gridOrigin[3] = { 1.5, -0.2, -0.2 };
  auto medium = ClearMedium(4, 0.1, gridOrigin);
  vtkNew<vtkCamera> camera;
  camera->SetPosition(0, 0, 3);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetViewUp(0, 1, 0);
  camera->SetViewAngle(24);
  const int w = 128, h = 128;
  vtkRefractaViewPass::RayFrame frame;
  ASSERT_TRUE(vtkRefractaViewPass::ComputeRayFrame(camera, medium, nullptr, w, h, frame));
  double rms[2][2] = { { 0, 0 }, { 0, 0 } }; // [noisy][filter]
  for (int noisy = 0; noisy < 2; ++noisy)
  {
    std::mt19937 random(7);
    std::normal_distribution<double> noise(0.0, 0.25);
    auto lighting = Lighting(medium, set,
      [&](const double c[3], double e[3])
      {
        double n[3] = { c[0], c[1], c[2] };
        vtkMath::Normalize(n);
        const double factor = noisy ? 1.0 + noise(random) : 1.0;
        e[0] = e[1] = e[2] = std::max(0.0, intensity * vtkMath::Dot(n, l) * factor);
      });
    vtkNew<vtkRefractaViewPass> pass;
    ASSERT_TRUE(pass->SetMedium(medium));
    ASSERT_TRUE(pass->SetLighting(lighting));
    pass->SetSurfaces(set);
    for (int filter : { vtkRefractaViewPass::NEAREST_TEXEL, vtkRefractaViewPass::LINEAR_TEXEL })
    {
      pass->SetSurfaceFilter(filter);
      std::vector<float> hdr;
      ASSERT_TRUE(pass->Render(camera, w, h, nullptr, nullptr, hdr));
      double sum2 = 0, ratio = 0;
      int pixels = 0;
      for (int j = 0; j < h; ++j)
      {
        for (int i = 0; i < w; ++i)
        {
          double o[3], d[3];
          PixelRay(frame, medium, i, j, w, h, o, d);
          // The exact sphere: |o + t d| = R, the nearer root.
          const double b = vtkMath::Dot(o, d), c = vtkMath::Dot(o, o) - 0.25;
          const double impact2 = c + 0.25 - b * b; // squared distance of the ray from the centre
          if (impact2 > 0.85 * 0.85 * 0.25)
          {
            continue;
          }
          const double t = -b - std::sqrt(b * b - c);
          double n[3] = { o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2] };
          vtkMath::Normalize(n);
          const double cosine = vtkMath::Dot(n, l);
          if (cosine < 0.3)
          {
            continue;
          }
          const double want = intensity * cosine * albedo / Pi;
          const double r = hdr[4 * (i + size_t(w) * j)] / want;
          sum2 += (r - 1) * (r - 1);
          ratio += r;
          ++pixels;
        }
      }
      ASSERT_GT(pixels, 4000);
      rms[noisy][filter] = std::sqrt(sum2 / pixels);
      std::cout << (noisy ? "noisy" : "exact") << " irradiance, "
                << (filter == vtkRefractaViewPass::LINEAR_TEXEL ? "linear" : "nearest")
                << " texel: per-pixel RMS " << rms[noisy][filter] << ", mean ratio "
                << ratio / pixels << " over " << pixels << " pixels\n";
      EXPECT_NEAR(ratio / pixels, 1.0, 0.01) << "no bias";
    }
  }
  EXPECT_LT(rms[0][vtkRefractaViewPass::LINEAR_TEXEL], 0.005);
  EXPECT_LT(
    rms[1][vtkRefractaViewPass::LINEAR_TEXEL], 0.5 * rms[1][vtkRefractaViewPass::NEAREST_TEXEL]);
}

//------------------------------------------------------------------------------
// The same law through the photon pass: a 20 x 20 plane (albedo 0.5) at z = 0, a point light of
// intensity I = 2 at height h = 5 inside a small vacuum grid, NumberOfPhotons photons (2^20 by
// default; REFRACTA_SURFACE_PHOTONS overrides it for measurements). The camera looks down at the
// plane's central 12 x 12 (rho up to 6 = 1.2 h). Checks, over the pixels:
// - the mean of L / (E rho / pi) is 1 within 1% (no bias: the photon estimate, the texel layout
//   and the view pass's units agree);
// - the same ratio averaged over 8 x 8 blocks of pixels is within 3% of 1 (block noise);
// - the per-pixel RMS deviation (photon noise after the filter) is printed for both filters and
//   the linear one's must be smaller (it averages ~6 texels per corner).
// Measured (texel 0.22, the automatic size): per-pixel RMS 4.8% / 1.7% / 0.62% with the linear
// filter at 2^18 / 2^20 / 2^22 photons (26% / 9.8% / 3.7% with the hit texel alone); mean ratio
// within 4e-4 of 1; worst linear block 2.4% / 0.94% / 0.37%.
TEST(ViewPassSurfaces, PointLightPlaneThroughThePhotonPass)
{
  const double h = 5.0, intensity = 2.0, rho = 0.5;
  auto medium = refracta_test::MakeGrid(8, 8, 8, 0.5);
  medium->SetOrigin(-1.75, -1.75, h - 1.75);
  refracta_test::AddConstant(medium, "Extinction", 3, 0, 0, 0);
  refracta_test::AddConstant(medium, "RefractiveIndex", 1, 1.0);
  const double o0[3] = { -10, -10, 0 }, p1[3] = { 10, -10, 0 }, p2[3] = { -10, 10, 0 };
  vtkNew<vtkRefractaSurfaceSet> set;
  set->AddSurface(Plane(o0, p1, p2), Material(rho, rho, rho));
  vtkNew<vtkLight> light;
  light->SetPositional(true);
  light->SetPosition(0, 0, h);
  light->SetFocalPoint(0, 0, 0);
  light->SetConeAngle(180);
  light->SetExponent(0);
  light->SetIntensity(intensity);
  vtkNew<vtkPhotonTracer> tracer;
  tracer->SetInputData(medium);
  tracer->SetSurfaces(set);
  tracer->AddLight(light);
  const char* photons = std::getenv("REFRACTA_SURFACE_PHOTONS");
  tracer->SetNumberOfPhotons(photons ? std::atoi(photons) : (1 << 20));
  tracer->Update();
  ASSERT_TRUE(tracer->GetUsedSurfaces());
  vtkNew<vtkCamera> camera;
  camera->SetPosition(0, 0, 12);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetViewUp(0, 1, 0);
  camera->ParallelProjectionOn();
  camera->SetParallelScale(6);
  vtkNew<vtkRefractaViewPass> pass;
  ASSERT_TRUE(pass->SetMedium(medium));
  ASSERT_TRUE(pass->SetLighting(tracer->GetOutput()));
  pass->SetSurfaces(set);
  const int w = 96, h2 = 96;
  double rms[2] = { 0, 0 };
  for (int filter : { vtkRefractaViewPass::NEAREST_TEXEL, vtkRefractaViewPass::LINEAR_TEXEL })
  {
    pass->SetSurfaceFilter(filter);
    std::vector<float> hdr;
    ASSERT_TRUE(pass->Render(camera, w, h2, nullptr, nullptr, hdr));
    double sum = 0, sum2 = 0, worstBlock = 0;
    std::vector<double> blocks((w / 8) * (h2 / 8), 0.0);
    for (int j = 0; j < h2; ++j)
    {
      for (int i = 0; i < w; ++i)
      {
        const double x = 12.0 * (i + 0.5) / w - 6, y = 12.0 * (j + 0.5) / h2 - 6;
        const double e = intensity * h / std::pow(h * h + x * x + y * y, 1.5);
        const double ratio = hdr[4 * (i + static_cast<size_t>(w) * j)] / (e * rho / Pi);
        sum += ratio;
        sum2 += (ratio - 1) * (ratio - 1);
        blocks[(i / 8) + (w / 8) * (j / 8)] += ratio / 64;
      }
    }
    for (double b : blocks)
    {
      worstBlock = std::max(worstBlock, std::abs(b - 1));
    }
    const double mean = sum / (w * h2);
    rms[filter] = std::sqrt(sum2 / (w * h2));
    std::cout << (filter == vtkRefractaViewPass::LINEAR_TEXEL ? "linear" : "nearest") << " texel, "
              << tracer->GetNumberOfPhotons() << " photons: mean L / (E rho / pi) " << mean
              << ", per-pixel RMS deviation " << rms[filter] << ", worst 8 x 8 block " << worstBlock
              << " (texel size " << set->GetEffectiveTexelSize() << ")\n";
    EXPECT_NEAR(mean, 1.0, 0.01);
    if (filter == vtkRefractaViewPass::LINEAR_TEXEL)
    {
      EXPECT_LT(worstBlock, 0.03);
    }
  }
  EXPECT_LT(rms[vtkRefractaViewPass::LINEAR_TEXEL], rms[vtkRefractaViewPass::NEAREST_TEXEL]);
}

//------------------------------------------------------------------------------
// Slab: a 10 x 10 x 6 grid (spacing 0.1, so [-0.05, 0.95] x [-0.05, 0.95] x [-0.05, 0.55]) with
// extinction (0.8, 1.6, 3.2); a plane at z = -0.5 behind it with E = pi (radiance = albedo); a
// small square at z = 0.25 inside the slab. Perspective camera from above, off axis.
TEST(ViewPassSurfaces, PlaneBehindAbsorbingSlabIsAttenuatedByBeerLambert)
{
  const double sigma[3] = { 0.8, 1.6, 3.2 };
  auto medium = refracta_test::MakeGrid(10, 10, 6, 0.1);
  refracta_test::AddConstant(medium, "Extinction", 3, sigma[0], sigma[1], sigma[2]);
  vtkNew<vtkRefractaSurfaceSet> set;
  const double o0[3] = { -3, -3, -0.5 }, p1[3] = { 3, -3, -0.5 }, p2[3] = { -3, 3, -0.5 };
  const double q0[3] = { 0.3, 0.3, 0.25 }, q1[3] = { 0.6, 0.3, 0.25 }, q2[3] = { 0.3, 0.6, 0.25 };
  set->AddSurface(Plane(o0, p1, p2), Material(0.9, 0.8, 0.7));
  set->AddSurface(Plane(q0, q1, q2), Material(0.6, 0.6, 0.6));
  auto lighting =
    Lighting(medium, set, [](const double*, double e[3]) { e[0] = e[1] = e[2] = Pi; });
  vtkNew<vtkCamera> camera;
  camera->SetPosition(0.7, 0.2, 2.5);
  camera->SetFocalPoint(0.45, 0.45, 0.0);
  camera->SetViewAngle(40);
  vtkNew<vtkRefractaViewPass> pass;
  ASSERT_TRUE(pass->SetMedium(medium));
  ASSERT_TRUE(pass->SetLighting(lighting));
  pass->SetSurfaces(set);
  const int w = 96, h = 96;
  std::vector<float> hdr, depth;
  ASSERT_TRUE(pass->Render(camera, w, h, nullptr, nullptr, hdr, nullptr, &depth));
  vtkRefractaViewPass::RayFrame f;
  ASSERT_TRUE(vtkRefractaViewPass::ComputeRayFrame(camera, medium, nullptr, w, h, f));
  double worst = 0;
  int through = 0, square = 0;
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      double o[3], d[3];
      PixelRay(f, medium, i, j, w, h, o, d);
      const double tSquare = (0.25 - o[2]) / d[2];
      const double xs = o[0] + tSquare * d[0], ys = o[1] + tSquare * d[1];
      const bool onSquare = xs > 0.3 && xs < 0.6 && ys > 0.3 && ys < 0.6;
      const double zEnd = onSquare ? 0.25 : -0.5;
      const double tEnd = (zEnd - o[2]) / d[2];
      if (std::abs(xs - 0.3) < 0.01 || std::abs(xs - 0.6) < 0.01 || std::abs(ys - 0.3) < 0.01 ||
        std::abs(ys - 0.6) < 0.01)
      {
        continue; // the square's outline
      }
      // Chord of the ray through the box before the surface, in double.
      double t0 = 0, t1 = tEnd;
      const double lo[3] = { -0.05, -0.05, -0.05 }, hi[3] = { 0.95, 0.95, 0.55 };
      for (int a = 0; a < 3; ++a)
      {
        const double ta = (lo[a] - o[a]) / d[a], tb = (hi[a] - o[a]) / d[a];
        t0 = std::max(t0, std::min(ta, tb));
        t1 = std::min(t1, std::max(ta, tb));
      }
      const double chord = std::max(t1 - t0, 0.0);
      // Rays grazing the box's edges: skip a band 0.01 wide around them.
      if (chord > 0 && chord < 0.01)
      {
        continue;
      }
      through += (chord > 0.3 && !onSquare) ? 1 : 0;
      square += onSquare ? 1 : 0;
      const double rho[3] = { onSquare ? 0.6 : 0.9, onSquare ? 0.6 : 0.8, onSquare ? 0.6 : 0.7 };
      const size_t p = i + static_cast<size_t>(w) * j;
      for (int c = 0; c < 3; ++c)
      {
        const double want = rho[c] * std::exp(-sigma[c] * chord);
        worst = std::max(worst, std::abs(hdr[4 * p + c] - want) / want);
      }
      EXPECT_NEAR(depth[p], tEnd, 1e-5 * tEnd);
    }
  }
  std::cout << "slab: worst relative error " << worst << " (" << through << " pixels through the "
            << "slab to the plane, " << square << " on the square inside it)\n";
  EXPECT_LE(worst, 0.01);
  EXPECT_GT(through, 1000);
  EXPECT_GT(square, 100);
}

//------------------------------------------------------------------------------
namespace
{
// Ball lens: a 64^3 grid on [0, 1]^3, sphere centre (0.5, 0.5, 0.5), radius 0.3, n = 1.5 inside,
// tanh boundary 0.7 voxel wide (as the photon optics test). Plane z = PlaneZ below the grid.
const int LensN = 64;
const double LensH = 1.0 / (LensN - 1), LensR = 0.3, LensIndex = 1.5, PlaneZ = -0.6;

vtkSmartPointer<vtkImageData> BallLensMedium()
{
  auto medium = refracta_test::MakeGrid(LensN, LensN, LensN, LensH);
  refracta_test::AddConstant(medium, "Extinction", 3, 0, 0, 0);
  vtkFloatArray* n = refracta_test::AddConstant(medium, "RefractiveIndex", 1, 1.0);
  for (vtkIdType p = 0; p < medium->GetNumberOfPoints(); ++p)
  {
    double x[3];
    medium->GetPoint(p, x);
    const double r =
      std::sqrt(std::pow(x[0] - 0.5, 2) + std::pow(x[1] - 0.5, 2) + std::pow(x[2] - 0.5, 2));
    n->SetValue(p,
      static_cast<float>(1 + 0.5 * (LensIndex - 1) * (1 - std::tanh((r - LensR) / (0.7 * LensH)))));
  }
  return medium;
}

// Refracts unit d at unit normal m (facing against d) from index n1 into n2; false on total
// internal reflection.
bool Refract(const double d[3], const double m[3], double n1, double n2, double out[3])
{
  const double eta = n1 / n2, c = -vtkMath::Dot(d, m);
  const double k = 1 - eta * eta * (1 - c * c);
  if (k < 0)
  {
    return false;
  }
  for (int a = 0; a < 3; ++a)
  {
    out[a] = eta * d[a] + (eta * c - std::sqrt(k)) * m[a];
  }
  return true;
}

// The sharp sphere traced in double: where the ray (x, y, 2) -> -z lands on the plane z = PlaneZ
// (x coordinate); false when it misses the sphere.
bool SnellLanding(double x, double y, double* landingX)
{
  const double c[3] = { 0.5, 0.5, 0.5 };
  double o[3] = { x, y, 2.0 }, d[3] = { 0, 0, -1 };
  auto sphere = [&](const double* p, const double* dir, bool far, double* t)
  {
    double oc[3];
    vtkMath::Subtract(p, c, oc);
    const double b = vtkMath::Dot(oc, dir), q = vtkMath::Dot(oc, oc) - LensR * LensR;
    const double disc = b * b - q;
    if (disc < 0)
    {
      return false;
    }
    *t = far ? -b + std::sqrt(disc) : -b - std::sqrt(disc);
    return *t > 0;
  };
  double t;
  if (!sphere(o, d, false, &t))
  {
    return false;
  }
  double p[3], m[3], inside[3];
  for (int a = 0; a < 3; ++a)
  {
    p[a] = o[a] + t * d[a];
    m[a] = (p[a] - c[a]) / LensR;
  }
  if (!Refract(d, m, 1.0, LensIndex, inside) || !sphere(p, inside, true, &t))
  {
    return false;
  }
  double q[3], out[3];
  for (int a = 0; a < 3; ++a)
  {
    q[a] = p[a] + t * inside[a];
    m[a] = -(q[a] - c[a]) / LensR; // inward normal faces against the outgoing ray
  }
  if (!Refract(inside, m, LensIndex, 1.0, out) || out[2] >= 0)
  {
    return false;
  }
  const double s = (PlaneZ - q[2]) / out[2];
  *landingX = q[0] + s * out[0];
  return true;
}
}

// Red for x < 0.5, blue for x > 0.5 (two planes), lit uniformly (radiance = albedo). A parallel
// camera looks down -z over [0, 1]^2. Inside the silhouette the lens (focus f = n R / (2 (n - 1))
// = 0.45 from the centre, the plane 1.1 from it) inverts the image: left pixels see blue.
TEST(ViewPassSurfaces, BallLensSwapsRedAndBlueAsSnellsLawPredicts)
{
  auto medium = BallLensMedium();
  vtkNew<vtkRefractaSurfaceSet> set;
  const double r0[3] = { -2, -2, PlaneZ }, r1[3] = { 0.5, -2, PlaneZ }, r2[3] = { -2, 3, PlaneZ };
  const double b0[3] = { 0.5, -2, PlaneZ }, b1[3] = { 3, -2, PlaneZ }, b2[3] = { 0.5, 3, PlaneZ };
  set->AddSurface(Plane(r0, r1, r2), Material(0.9, 0.1, 0.1));
  set->AddSurface(Plane(b0, b1, b2), Material(0.1, 0.1, 0.9));
  auto lighting =
    Lighting(medium, set, [](const double*, double e[3]) { e[0] = e[1] = e[2] = Pi; });
  vtkNew<vtkCamera> camera;
  camera->SetPosition(0.5, 0.5, 3.0);
  camera->SetFocalPoint(0.5, 0.5, 0.5);
  camera->SetViewUp(0, 1, 0);
  camera->ParallelProjectionOn();
  camera->SetParallelScale(0.5);
  vtkNew<vtkRefractaViewPass> pass;
  ASSERT_TRUE(pass->SetMedium(medium));
  ASSERT_TRUE(pass->SetLighting(lighting));
  pass->SetSurfaces(set);
  const int w = 128, h = 128;
  std::vector<float> hdr;
  ASSERT_TRUE(pass->Render(camera, w, h, nullptr, nullptr, hdr));
  EXPECT_TRUE(pass->GetLastCurved());
  // Tolerances: the smoothed index (tanh, 0.7 voxel) and the one-voxel steps bend rays near the
  // rim differently from the sharp sphere: pixels within RimBand of the silhouette are not
  // compared; nor are pixels whose sharp-sphere landing point lies within EdgeBand of the
  // colour edge x = 0.5 (its image through the lens is where a small bending error flips the
  // colour).
  const double RimBand = 3 * LensH, EdgeBand = 0.01;
  int inside = 0, swapped = 0, outside = 0, mismatches = 0;
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      const double x = (i + 0.5) / w, y = (j + 0.5) / h;
      const float* px = &hdr[4 * (i + static_cast<size_t>(w) * j)];
      const bool seesRed = px[0] > px[2];
      const double r = std::hypot(x - 0.5, y - 0.5);
      if (std::abs(r - LensR) < RimBand)
      {
        continue;
      }
      double landing = x;
      if (r < LensR)
      {
        ASSERT_TRUE(SnellLanding(x, y, &landing)) << i << "," << j;
        ++inside;
        swapped += ((x < 0.5) != (landing < 0.5)) ? 1 : 0;
      }
      else
      {
        ++outside;
      }
      if (std::abs(landing - 0.5) < EdgeBand)
      {
        continue;
      }
      const bool wantRed = landing < 0.5;
      if (seesRed != wantRed)
      {
        ++mismatches;
      }
      // The surface's colour arrives whole: the clear lens absorbs nothing.
      EXPECT_NEAR(std::max(px[0], px[2]), 0.9f, 0.9f * 0.01f) << i << "," << j;
    }
  }
  std::cout << "ball lens: " << inside << " pixels inside the silhouette (" << swapped
            << " swapped by the sharp-sphere trace), " << outside << " outside, " << mismatches
            << " disagree with the trace\n";
  EXPECT_GT(inside, 3000);
  EXPECT_GT(swapped, inside * 8 / 10) << "a ball lens in front of a far plane inverts";
  EXPECT_EQ(mismatches, 0);
}

// The same lens in front of a plane whose albedo encodes x (red = (x + 0.5) / 2 over [-0.5, 1.5],
// point colours interpolated, texels 0.004 wide): each pixel's red gives where its ray landed,
// compared with the sharp-sphere trace. Pixels within 3 voxels (0.16 R) of the silhouette are
// excluded. Tolerances (measured: 0.0078, 0.061 and 0.0074): within 0.01 for rays within 0.6 R
// of the axis, 0.08 for all, 0.01 on average. The difference grows towards the rim and does not
// shrink with 4x smaller steps (0.053 worst): it is the smoothed boundary (tanh 0.7 voxel,
// trilinear n, central-difference grad n on a 64^3 grid), which marginal rays cross most
// obliquely and which then bends them differently from a sharp sphere, not the surface lookup.
TEST(ViewPassSurfaces, BallLensLandingPointsMatchSnellsLaw)
{
  auto medium = BallLensMedium();
  vtkNew<vtkPlaneSource> source;
  source->SetOrigin(-0.5, -0.5, PlaneZ);
  source->SetPoint1(1.5, -0.5, PlaneZ);
  source->SetPoint2(-0.5, 1.5, PlaneZ);
  source->SetResolution(4, 4);
  source->Update();
  vtkPolyData* plane = source->GetOutput();
  vtkNew<vtkFloatArray> colours;
  colours->SetNumberOfComponents(3);
  colours->SetNumberOfTuples(plane->GetNumberOfPoints());
  for (vtkIdType p = 0; p < plane->GetNumberOfPoints(); ++p)
  {
    double x[3];
    plane->GetPoint(p, x);
    colours->SetTuple3(p, (x[0] + 0.5) / 2, 0.5, 0.5);
  }
  plane->GetPointData()->SetScalars(colours);
  vtkNew<vtkRefractaSurfaceMaterial> material;
  material->UseScalarColorsOn();
  vtkNew<vtkRefractaSurfaceSet> set;
  set->AddSurface(plane, material);
  set->SetTexelSize(0.004);
  auto lighting =
    Lighting(medium, set, [](const double*, double e[3]) { e[0] = e[1] = e[2] = Pi; });
  vtkNew<vtkCamera> camera;
  camera->SetPosition(0.5, 0.5, 3.0);
  camera->SetFocalPoint(0.5, 0.5, 0.5);
  camera->SetViewUp(0, 1, 0);
  camera->ParallelProjectionOn();
  camera->SetParallelScale(0.5);
  vtkNew<vtkRefractaViewPass> pass;
  ASSERT_TRUE(pass->SetMedium(medium));
  ASSERT_TRUE(pass->SetLighting(lighting));
  pass->SetSurfaces(set);
  const int w = 96, h = 96;
  std::vector<float> hdr;
  ASSERT_TRUE(pass->Render(camera, w, h, nullptr, nullptr, hdr));
  double worst = 0, worstCentral = 0, sum = 0;
  int count = 0;
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      const double x = (i + 0.5) / w, y = (j + 0.5) / h;
      const double r = std::hypot(x - 0.5, y - 0.5);
      double landing;
      if (r > LensR - 3 * LensH || !SnellLanding(x, y, &landing))
      {
        continue;
      }
      const double measured = 2 * hdr[4 * (i + static_cast<size_t>(w) * j)] - 0.5;
      worst = std::max(worst, std::abs(measured - landing));
      if (r < 0.6 * LensR)
      {
        worstCentral = std::max(worstCentral, std::abs(measured - landing));
      }
      sum += std::abs(measured - landing);
      ++count;
    }
  }
  std::cout << "ball lens landing: worst " << worst << " (" << worstCentral
            << " within 0.6 R), mean " << sum / count << " over " << count
            << " pixels inside the silhouette (rim band 3 voxels excluded)\n";
  EXPECT_GT(count, 1500);
  EXPECT_LT(worstCentral, 0.01);
  EXPECT_LT(worst, 0.08);
  EXPECT_LT(sum / count, 0.01);
}

//------------------------------------------------------------------------------
TEST(ViewPassSurfaces, CameraMovesDoNotUploadSurfacesAgain)
{
  const double o0[3] = { -1, -1, -0.5 }, p1[3] = { 1, -1, -0.5 }, p2[3] = { -1, 1, -0.5 };
  vtkNew<vtkRefractaSurfaceSet> set;
  vtkNew<vtkMatrix4x4> matrix;
  set->AddSurface(Plane(o0, p1, p2, 8), Material(0.5, 0.5, 0.5), matrix);
  const double origin[3] = { 0, 0, 0 };
  auto medium = ClearMedium(8, 0.1, origin);
  auto lighting = Lighting(medium, set, [](const double*, double e[3]) { e[0] = e[1] = e[2] = 1; });
  vtkNew<vtkRefractaViewPass> pass;
  ASSERT_TRUE(pass->SetMedium(medium));
  ASSERT_TRUE(pass->SetLighting(lighting));
  pass->SetSurfaces(set);
  vtkNew<vtkCamera> camera;
  camera->SetPosition(0, 0, 3);
  std::vector<float> hdr;
  ASSERT_TRUE(pass->Render(camera, 16, 16, nullptr, nullptr, hdr));
  EXPECT_EQ(pass->GetNumberOfSurfaceUploads(), 1);
  const vtkMTimeType before = pass->GetMTime();
  for (int k = 0; k < 3; ++k)
  {
    camera->Azimuth(10);
    ASSERT_TRUE(pass->Render(camera, 16, 16, nullptr, nullptr, hdr));
  }
  EXPECT_EQ(pass->GetNumberOfSurfaceUploads(), 1) << "a camera move must not upload surfaces";
  EXPECT_EQ(pass->GetMTime(), before);
  // Moving the surface rebuilds and uploads it, and the pass reports a newer MTime (so the
  // pipeline renders again); the old irradiance still fits (same texel count).
  matrix->SetElement(2, 3, -0.2);
  EXPECT_GT(pass->GetMTime(), before);
  ASSERT_TRUE(pass->Render(camera, 16, 16, nullptr, nullptr, hdr));
  EXPECT_EQ(pass->GetNumberOfSurfaceUploads(), 2);
  // Removing the surfaces: the plane is gone, the background shows.
  pass->SetSurfaces(nullptr);
  ASSERT_TRUE(pass->Render(camera, 16, 16, nullptr, nullptr, hdr));
  EXPECT_EQ(hdr[4 * (8 + 16 * 8) + 3], 0.0f);
}

//------------------------------------------------------------------------------
TEST(ViewPassSurfaces, BadIrradianceIsAnErrorNamingTheArray)
{
  const double o0[3] = { -1, -1, -0.5 }, p1[3] = { 1, -1, -0.5 }, p2[3] = { -1, 1, -0.5 };
  vtkNew<vtkRefractaSurfaceSet> set;
  set->AddSurface(Plane(o0, p1, p2), Material(0.5, 0.5, 0.5));
  const double origin[3] = { 0, 0, 0 };
  auto medium = ClearMedium(8, 0.1, origin);
  auto lighting = Lighting(medium, set, [](const double*, double e[3]) { e[0] = e[1] = e[2] = 1; });
  vtkNew<vtkTest::ErrorObserver> errors;
  vtkNew<vtkRefractaViewPass> pass;
  pass->AddObserver(vtkCommand::ErrorEvent, errors);
  ASSERT_TRUE(pass->SetMedium(medium));
  vtkNew<vtkCamera> camera;
  camera->SetPosition(0, 0, 3);
  std::vector<float> hdr;

  // A NaN: refused by SetLighting.
  auto* e = vtkFloatArray::SafeDownCast(
    lighting->GetFieldData()->GetArray(vtkRefractaLightingVolume::SurfaceIrradianceName()));
  e->SetComponent(3, 1, std::nan(""));
  EXPECT_FALSE(pass->SetLighting(lighting));
  EXPECT_NE(errors->GetErrorMessage().find("SurfaceIrradiance"), std::string::npos);
  errors->Clear();

  // Too few tuples for the set's texels: Render refuses.
  e->SetComponent(3, 1, 1.0);
  e->SetNumberOfTuples(e->GetNumberOfTuples() - 1);
  ASSERT_TRUE(pass->SetLighting(lighting));
  pass->SetSurfaces(set);
  EXPECT_FALSE(pass->Render(camera, 8, 8, nullptr, nullptr, hdr));
  EXPECT_NE(errors->GetErrorMessage().find("texels"), std::string::npos);
  errors->Clear();

  // No irradiance at all: the surfaces are unlit (black) but still hide what is behind them.
  lighting->GetFieldData()->RemoveArray(vtkRefractaLightingVolume::SurfaceIrradianceName());
  lighting->Modified();
  ASSERT_TRUE(pass->SetLighting(lighting));
  pass->SetBackgroundColor(1, 1, 1);
  ASSERT_TRUE(pass->Render(camera, 8, 8, nullptr, nullptr, hdr));
  EXPECT_EQ(hdr[4 * (4 + 8 * 4)], 0.0f);
  EXPECT_EQ(hdr[4 * (4 + 8 * 4) + 3], 1.0f);
}

//------------------------------------------------------------------------------
// Through the render pipeline (vtkRefractaImageRenderer::SetSurfaces): the pipeline passes its set
// to the photon pass and the view pass, so the plane under a point light appears, opaque, with
// the inverse-square cosine falloff (ratio of 8 x 8 blocks at rho = 0 and rho = 3 against
// (h^2 / (h^2 + rho^2))^(3/2), within 5%: photon noise at the pipeline's 2^18 photons), and a
// camera move renders again without uploading the surfaces again.
TEST(ViewPassSurfaces, ThroughTheRenderPipeline)
{
  const double h = 5.0;
  auto medium = refracta_test::MakeGrid(8, 8, 8, 0.5);
  medium->SetOrigin(-1.75, -1.75, h - 1.75);
  refracta_test::AddConstant(medium, "Extinction", 3, 0, 0, 0);
  const double o0[3] = { -10, -10, 0 }, p1[3] = { 10, -10, 0 }, p2[3] = { -10, 10, 0 };
  vtkNew<vtkRefractaSurfaceSet> set;
  set->AddSurface(Plane(o0, p1, p2), Material(0.5, 0.5, 0.5));
  vtkNew<vtkLight> light;
  light->SetPositional(true);
  light->SetPosition(0, 0, h);
  light->SetFocalPoint(0, 0, 0);
  light->SetConeAngle(180);
  vtkNew<vtkCamera> camera;
  camera->SetPosition(0, 0, 12);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetViewUp(0, 1, 0);
  camera->ParallelProjectionOn();
  camera->SetParallelScale(6);
  vtkNew<vtkRefractaImageRenderer> renderer;
  renderer->SetInputData(medium);
  renderer->SetSurfaces(set);
  renderer->AddLight(light);
  renderer->SetCamera(camera);
  renderer->SetImageSize(96, 96);
  renderer->Update();
  auto* hdr = vtkFloatArray::SafeDownCast(renderer->GetOutput()->GetPointData()->GetArray("HDR"));
  ASSERT_NE(hdr, nullptr);
  auto block = [&](int ci, int cj)
  {
    double sum = 0;
    for (int j = cj - 4; j < cj + 4; ++j)
    {
      for (int i = ci - 4; i < ci + 4; ++i)
      {
        sum += hdr->GetComponent(i + 96 * j, 0) / 64;
        EXPECT_EQ(hdr->GetComponent(i + 96 * j, 3), 1.0) << "the plane is opaque";
      }
    }
    return sum;
  };
  const double centre = block(48, 48), off = block(48 + 24, 48); // rho = 0 and rho = 3
  EXPECT_GT(centre, 0.0);
  const double want = std::pow(h * h / (h * h + 9.0), 1.5);
  std::cout << "pipeline: L(rho = 3) / L(0) = " << off / centre << ", analytic " << want << "\n";
  EXPECT_NEAR(off / centre, want, 0.05 * want);
  vtkRefractaViewPass* pass = renderer->GetViewPass();
  EXPECT_EQ(pass->GetNumberOfSurfaceUploads(), 1);
  camera->Azimuth(20);
  renderer->Update();
  EXPECT_EQ(pass->GetNumberOfSurfaceUploads(), 1) << "a camera move must not upload surfaces";
}
