// Refracta.SingleScatteringAgainstReference (issue #15): single scattering by the render pipeline
// with S1 from per-voxel light rays, from Ren et al.'s interpolation and from photons, against
// the unbiased reference renderer restricted to one scattering event
// (vtkReferenceRenderer::MaximumScatteringDepth 1: camera ray, one scattering, the connection to
// a light; no further bounce), multiple scattering off everywhere.
//
// Scene: a heterogeneous cloud on 24^3 voxels in [0, 1]^3 (three overlapping soft blobs, sigma_t
// up to ~9 per unit length, albedo 0.9, g as the test says), lit by a directional light (angular
// radius 0.5 degrees in both renderers) and a point light (radius 0.01 in both: the reference
// cannot reach a delta light); a perspective camera, 32 x 32 pixels.
//
// Statistic (as Refracta.SurfacesAgainstReference): regions of 4 x 4 pixels; per region and
// channel the reference mean R has the standard error SE = sqrt(sum of the pixels' SE^2) / 16; a
// region value passes when |P - R| <= K_SIGMA SE + B max(R, RMS_R). K_SIGMA = 4 (a Gaussian mean
// exceeds it with probability 6e-5; the reference is seeded, so the run is reproducible). B is the
// pipeline's model error budget: the view pass's ray march (step of the default preset), S1 at
// voxel centres against the reference's continuous medium, the lights' extents. At most
// MAX_FAILED_REGIONS may fail. The light rays' image scaled by 1.1 (1.3 on the sharp-edged ball)
// must fail: the test sees a 10% error. The run takes ~10 s on the 2-core CPU.
//
// The measured numbers (printed by the run) and B are in the header of each test below.
#include "RefractaReferenceImages.h"
#include "RegionComparison.h"

#include "vtkCamera.h"
#include "vtkEffectPlan.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkLightRaySingleScattering.h"
#include "vtkNew.h"
#include "vtkPhotonTracer.h"
#include "vtkPointData.h"
#include "vtkReferenceRenderer.h"
#include "vtkRefractaImageRenderer.h"
#include "vtkRefractaMedium.h"
#include "vtkRefractaRenderPipeline.h"
#include "vtkSmartPointer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

namespace
{
using refracta::bench::Image;
using refracta::bench::ReadImage;
using refracta_test::Regions;
using refracta_test::Scaled;

constexpr int SIZE = 32;
constexpr int BLOCK = 4;
constexpr double K_SIGMA = 4.0;
constexpr int MAX_FAILED_REGIONS = 1;
constexpr double LIGHT_RADIUS = 0.01;
constexpr double ANGULAR_RADIUS = 0.5; // degrees

struct Scene
{
  vtkSmartPointer<vtkImageData> Medium;
  std::vector<vtkSmartPointer<vtkLight>> Lights;
  vtkSmartPointer<vtkCamera> Camera;
};

// Three soft blobs: sigma_t = sum_b peak_b (1 - (r / R_b)^2)^2 inside each, 0 outside.
vtkSmartPointer<vtkImageData> Cloud(double g)
{
  const int n = 24;
  const double h = 1.0 / n;
  auto medium = vtkSmartPointer<vtkImageData>::New();
  medium->SetDimensions(n, n, n);
  medium->SetSpacing(h, h, h);
  medium->SetOrigin(0.5 * h, 0.5 * h, 0.5 * h);
  struct Blob
  {
    double C[3], R, Peak;
  };
  const Blob blobs[] = { { { 0.45, 0.5, 0.5 }, 0.33, 6.0 }, { { 0.65, 0.6, 0.45 }, 0.22, 4.0 },
    { { 0.35, 0.35, 0.6 }, 0.18, 3.0 } };
  vtkNew<vtkFloatArray> ext, alb, ani;
  ext->SetName(vtkRefractaMedium::ExtinctionName());
  ext->SetNumberOfComponents(3);
  alb->SetName(vtkRefractaMedium::AlbedoName());
  alb->SetNumberOfComponents(3);
  ani->SetName(vtkRefractaMedium::AnisotropyName());
  for (vtkIdType id = 0; id < medium->GetNumberOfPoints(); ++id)
  {
    double p[3];
    medium->GetPoint(id, p);
    double sigma = 0;
    for (const Blob& b : blobs)
    {
      const double r2 =
        (std::pow(p[0] - b.C[0], 2) + std::pow(p[1] - b.C[1], 2) + std::pow(p[2] - b.C[2], 2)) /
        (b.R * b.R);
      sigma += r2 < 1 ? b.Peak * (1 - r2) * (1 - r2) : 0.0;
    }
    for (int c = 0; c < 3; ++c)
    {
      ext->InsertNextValue(static_cast<float>(sigma));
      alb->InsertNextValue(0.9f);
    }
    ani->InsertNextValue(static_cast<float>(g));
  }
  medium->GetPointData()->AddArray(ext);
  medium->GetPointData()->AddArray(alb);
  medium->GetPointData()->AddArray(ani);
  return medium;
}

// The cloud (anisotropy g) under the sun and, when `lamp`, a warm point light.
Scene LitCloud(double g, bool lamp = true)
{
  Scene s;
  s.Medium = Cloud(g);
  auto sun = vtkSmartPointer<vtkLight>::New();
  sun->SetLightTypeToSceneLight();
  sun->PositionalOff();
  sun->SetPosition(1.5, 3.0, 1.0);
  sun->SetFocalPoint(0.5, 0.5, 0.5);
  sun->SetIntensity(1.0);
  s.Lights.push_back(sun);
  auto lampLight = vtkSmartPointer<vtkLight>::New();
  lampLight->SetLightTypeToSceneLight();
  lampLight->PositionalOn();
  lampLight->SetConeAngle(90); // a point light
  lampLight->SetPosition(-0.4, 0.3, 0.9);
  lampLight->SetFocalPoint(0.5, 0.5, 0.5);
  lampLight->SetColor(1.0, 0.8, 0.6);
  lampLight->SetIntensity(0.6);
  if (lamp)
  {
    s.Lights.push_back(lampLight);
  }
  s.Camera = vtkSmartPointer<vtkCamera>::New();
  s.Camera->SetPosition(0.5, 0.7, 2.6);
  s.Camera->SetFocalPoint(0.5, 0.5, 0.5);
  s.Camera->SetViewUp(0, 1, 0);
  s.Camera->SetViewAngle(30);
  return s;
}

// The cloud's sun alone over a medium of sigma_t = shape(point) instead of the cloud (albedo 0.9,
// g = 0).
Scene SunlitShape(const std::function<double(const double[3])>& shape)
{
  Scene s = LitCloud(0.0, false);
  vtkFloatArray* ext = vtkFloatArray::SafeDownCast(
    s.Medium->GetPointData()->GetArray(vtkRefractaMedium::ExtinctionName()));
  for (vtkIdType id = 0; id < s.Medium->GetNumberOfPoints(); ++id)
  {
    double p[3];
    s.Medium->GetPoint(id, p);
    const double sigma = shape(p);
    for (int c = 0; c < 3; ++c)
    {
      ext->SetComponent(id, c, sigma);
    }
  }
  return s;
}

Image RenderReference(const Scene& s, int spp)
{
  vtkNew<vtkReferenceRenderer> r;
  r->SetInputData(s.Medium);
  r->SetCamera(s.Camera);
  for (const auto& light : s.Lights)
  {
    r->AddLight(light);
  }
  r->SetLightRadius(LIGHT_RADIUS);
  r->SetDirectionalLightAngularRadius(ANGULAR_RADIUS);
  r->SetMaximumScatteringDepth(1); // single scattering: one event, then the light
  r->SetImageSize(SIZE, SIZE);
  r->SetSamplesPerPixel(spp);
  r->SetSeed(7);
  r->Update();
  return ReadImage(r->GetOutput());
}

// The pipeline with multiple scattering off and S1 from `method` (vtkEffectPlan's
// LIGHT_RAYS, INTERPOLATED or PHOTONS; 2^18 photons, smoothed or not; the light rays' box means
// at sharp voxels on or off, their lobes at most `lobes`).
Image RenderPipeline(
  const Scene& s, int method, bool smoothing = true, bool boxMeans = true, int lobes = 2)
{
  vtkNew<vtkRefractaImageRenderer> renderer;
  vtkRefractaRenderPipeline* pipeline = renderer->GetPipeline();
  pipeline->GetLightRays()->SetSharpVoxelBoxMeans(boxMeans);
  pipeline->GetPhotonTracer()->SetMaximumRadianceLobes(lobes); // the light rays take it too
  pipeline->SetMultipleScattering(false);
  pipeline->SetSingleScatteringMethod(method);
  pipeline->GetPhotonTracer()->SetLightRadius(LIGHT_RADIUS);
  pipeline->GetPhotonTracer()->SetDirectionalLightAngularRadius(ANGULAR_RADIUS);
  pipeline->GetPhotonTracer()->SetNumberOfPhotons(1 << 18);
  pipeline->GetPhotonTracer()->SetSmoothing(smoothing);
  for (const auto& light : s.Lights)
  {
    renderer->AddLight(light);
  }
  renderer->SetInputData(s.Medium);
  renderer->SetCamera(s.Camera);
  renderer->SetImageSize(SIZE, SIZE);
  renderer->Update();
  return ReadImage(renderer->GetOutput());
}

Regions Pool(const Image& image)
{
  return refracta_test::Pool(image, SIZE, BLOCK);
}

int FailedRegions(const Image& image, const Regions& ref, double b, const std::string& what)
{
  return refracta_test::FailedRegions(Pool(image), ref, K_SIGMA, b, what);
}

// Budgets B per method (fractions of max(R, RMS_R)).
struct Budgets
{
  double LightRays, Interpolated, Photons;
  double Scale = 1.1; // the light rays' image times this must fail
};

// Renders the scene by the reference and by the pipeline with each S1 method, and checks each
// against its budget; the light rays' image x b.Scale must fail.
void CheckMethods(const Scene& scene, int spp, const Budgets& b)
{
  const Image reference = RenderReference(scene, spp);
  ASSERT_EQ(reference.Value.size(), 3u * SIZE * SIZE);
  const Regions ref = Pool(reference);
  std::cout << "reference " << reference.Seconds << " s (" << spp << " samples per pixel)"
            << std::endl;
  const Image rays = RenderPipeline(scene, vtkEffectPlan::LIGHT_RAYS);
  ASSERT_EQ(rays.Value.size(), reference.Value.size()) << "pipeline image has the wrong size";
  EXPECT_LE(FailedRegions(rays, ref, b.LightRays, "light rays"), MAX_FAILED_REGIONS);
  EXPECT_GT(
    FailedRegions(Scaled(rays, b.Scale), ref, b.LightRays, "light rays scaled"), MAX_FAILED_REGIONS)
    << "the light rays' image x " << b.Scale << " passes: the test cannot see that error";
  const Image interpolated = RenderPipeline(scene, vtkEffectPlan::INTERPOLATED);
  ASSERT_EQ(interpolated.Value.size(), reference.Value.size());
  EXPECT_LE(FailedRegions(interpolated, ref, b.Interpolated, "interpolation"), MAX_FAILED_REGIONS);
  const Image photons = RenderPipeline(scene, vtkEffectPlan::PHOTONS);
  ASSERT_EQ(photons.Value.size(), reference.Value.size());
  EXPECT_LE(FailedRegions(photons, ref, b.Photons, "photons (smoothed)"), MAX_FAILED_REGIONS);
  FailedRegions(
    RenderPipeline(scene, vtkEffectPlan::PHOTONS, false), ref, b.Photons, "photons (unsmoothed)");
}
} // namespace

// Measured (PoCL on the CPU; the smallest B with no region failed): light rays 0%, the
// interpolation 3.2%, photons 4.5% (2^18, smoothed; 0.1% unsmoothed: the smoothing's bias, not
// noise). B: 2%, 6%, 15%. Totals: light rays -0.9%, the interpolation -3.0%, photons +1.2%.
TEST(SingleScatteringAgainstReference, CloudUnderSunAndPointLight)
{
  CheckMethods(LitCloud(0.0), 2048, { 0.02, 0.06, 0.15 });
}

// Forward scattering (g = 0.5) under the sun alone: the view pass's phase function about
// RadianceDirection. Measured: light rays 0%, the interpolation 2.2%, photons 3.5% (smoothed;
// 1.1% unsmoothed). B: 2%, 6%, 15%.
TEST(SingleScatteringAgainstReference, ForwardScatteringCloudUnderSun)
{
  CheckMethods(LitCloud(0.5, false), 2048, { 0.02, 0.06, 0.15 });
}

// Forward scattering (g = 0.5) under the sun and the point light, from different sides: every
// method keeps each light's S1 and direction in a lobe of its own (MaximumRadianceLobes 2), which
// the view pass shades about its own direction (Documentation/Physics.md, "Lights from different
// sides"). Measured (smallest B, bias): light rays 0%, -0.7%; the interpolation 1.7%, -2.7%;
// photons 3.2%, +1.4% (smoothed; 0.1%, +0.8% unsmoothed). With one lobe (the mean direction of
// both lights) the light rays need 19.0% (bias -14.4%; photons 20.0%, -12.8%) and must fail B.
// B: 2%, 6%, 15%.
TEST(SingleScatteringAgainstReference, ForwardScatteringCloudUnderTwoLights)
{
  const Scene scene = LitCloud(0.5);
  CheckMethods(scene, 2048, { 0.02, 0.06, 0.15 });
  const Regions ref = Pool(RenderReference(scene, 2048));
  EXPECT_GT(FailedRegions(RenderPipeline(scene, vtkEffectPlan::LIGHT_RAYS, true, true, 1), ref,
              0.02, "light rays, one lobe"),
    MAX_FAILED_REGIONS)
    << "the light rays pass without lobes: the test cannot see the crossing lights";
}

// A ball with a sharp edge (sigma_t 8 inside r = 0.35, 0 outside, on 24^3 voxels): S1 at voxel
// centres, interpolated trilinearly by the view pass, misses light in the edge voxels (where
// sigma_s phi bends within a voxel; at 0.33 per voxel below the box means' threshold). Measured:
// light rays 11.7% (bias -7.3%), the interpolation 22.9% (bias -7.9%), photons 13.3% smoothed
// (bias +2.5%) and 13.3% unsmoothed (bias +3.1%). B: 15%, 30%, 45%: a guard against
// regressions, with the known edge error stated (Documentation/Physics.md, "Voxel centre or voxel
// mean"); the light rays' image x 1.3 must fail.
TEST(SingleScatteringAgainstReference, SharpEdgedBall)
{
  Scene s = SunlitShape(
    [](const double p[3])
    {
      const double r = std::sqrt(
        (p[0] - 0.5) * (p[0] - 0.5) + (p[1] - 0.5) * (p[1] - 0.5) + (p[2] - 0.5) * (p[2] - 0.5));
      return r < 0.35 ? 8.0 : 0.0;
    });
  CheckMethods(s, 2048, { 0.15, 0.30, 0.45, 1.3 });
}

// A dense slab (sigma_t 24 below y = 0.5, 0 above, albedo 0.9, on 24^3 voxels: an optical depth
// of 1 per voxel) under the sun, seen from above: the light scatters in the trilinear ramp
// between the last empty centre and the first dense one, which S1 at the centres misses (the
// empty centre does not scatter, the dense one is already in the slab's shadow).
// Measured (smallest B with no region failed, bias): light rays with box means at the sharp
// voxels 22.6%, -4.2%; at the centres (SharpVoxelBoxMeans off) 45.1%, -26.0%; the interpolation
// 22.6%, -3.7%; photons 21.9%, -5.6% smoothed and 21.6%, -5.4% unsmoothed. Every method's
// largest region error is 27-28%: the voxel model's limit at this resolution, not the S1 method.
// B 25% for all; the light rays at their centres must fail it.
TEST(SingleScatteringAgainstReference, DenseSlabFace)
{
  Scene s = SunlitShape([](const double p[3]) { return p[1] < 0.5 ? 24.0 : 0.0; });
  s.Camera->SetPosition(0.5, 2.0, 2.2);
  s.Camera->SetFocalPoint(0.5, 0.45, 0.5);
  const Regions ref = Pool(RenderReference(s, 1024));
  const double bRays = 0.25, bInterpolated = 0.25, bPhotons = 0.25;
  const Image rays = RenderPipeline(s, vtkEffectPlan::LIGHT_RAYS);
  EXPECT_LE(FailedRegions(rays, ref, bRays, "light rays"), MAX_FAILED_REGIONS);
  EXPECT_GT(FailedRegions(RenderPipeline(s, vtkEffectPlan::LIGHT_RAYS, true, false), ref, bRays,
              "light rays at centres"),
    MAX_FAILED_REGIONS)
    << "the light rays' centre values pass: the test cannot see the loss at the face";
  EXPECT_LE(FailedRegions(
              RenderPipeline(s, vtkEffectPlan::INTERPOLATED), ref, bInterpolated, "interpolation"),
    MAX_FAILED_REGIONS);
  EXPECT_LE(
    FailedRegions(RenderPipeline(s, vtkEffectPlan::PHOTONS), ref, bPhotons, "photons (smoothed)"),
    MAX_FAILED_REGIONS);
  FailedRegions(
    RenderPipeline(s, vtkEffectPlan::PHOTONS, false), ref, bPhotons, "photons (unsmoothed)");
}
