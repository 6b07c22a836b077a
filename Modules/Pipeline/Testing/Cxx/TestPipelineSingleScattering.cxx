// The plan's choice of the single-scattering method in the pipeline (issue 15): straight light
// gets light rays (or the interpolation) and says why; refraction keeps the photons; a forced
// method runs; the light rays and the photons agree on the same scene.
#include "vtkAbstractArray.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkEffectPlan.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkLightRaySingleScattering.h"
#include "vtkNew.h"
#include "vtkPhotonTracer.h"
#include "vtkPointData.h"
#include "vtkRefractaLightingVolume.h"
#include "vtkRefractaMedium.h"
#include "vtkRefractaRenderPipeline.h"
#include "vtkSmartPointer.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

namespace
{
// A smooth scattering ball in a thin haze on 20^3 voxels; refractive when `refractive`.
vtkSmartPointer<vtkImageData> Haze(bool refractive)
{
  const int n = 20;
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(n, n, n);
  image->SetSpacing(0.05, 0.05, 0.05);
  vtkNew<vtkFloatArray> ext, alb, idx;
  ext->SetName("Extinction");
  ext->SetNumberOfComponents(3);
  alb->SetName("Albedo");
  alb->SetNumberOfComponents(3);
  idx->SetName("RefractiveIndex");
  for (vtkIdType id = 0; id < image->GetNumberOfPoints(); ++id)
  {
    double p[3];
    image->GetPoint(id, p);
    const double r2 = (p[0] - 0.475) * (p[0] - 0.475) + (p[1] - 0.475) * (p[1] - 0.475) +
      (p[2] - 0.475) * (p[2] - 0.475);
    const double ball = std::exp(-r2 / 0.06);
    for (int c = 0; c < 3; ++c)
    {
      ext->InsertNextValue(static_cast<float>(0.5 + 2.0 * ball));
      alb->InsertNextValue(0.8f);
    }
    idx->InsertNextValue(static_cast<float>(1.0 + 0.1 * ball));
  }
  image->GetPointData()->AddArray(ext);
  image->GetPointData()->AddArray(alb);
  if (refractive)
  {
    image->GetPointData()->AddArray(idx);
  }
  return image;
}

vtkSmartPointer<vtkRefractaRenderPipeline> Pipeline(vtkImageData* medium, int method)
{
  auto pipeline = vtkSmartPointer<vtkRefractaRenderPipeline>::New();
  pipeline->SetMedium(medium);
  vtkNew<vtkLight> sun;
  sun->SetPositional(false);
  sun->SetPosition(0.5, 3.0, 0.5);
  sun->SetFocalPoint(0.5, 0.0, 0.5);
  sun->SetIntensity(1.0);
  pipeline->AddLight(sun);
  vtkNew<vtkCamera> camera;
  camera->SetPosition(0.5, 0.5, 4.0);
  camera->SetFocalPoint(0.5, 0.5, 0.5);
  pipeline->SetCamera(camera);
  pipeline->SetMultipleScattering(false);
  pipeline->SetSingleScatteringMethod(method);
  pipeline->GetPhotonTracer()->SetNumberOfPhotons(1 << 16);
  return pipeline;
}

std::string Ran(vtkRefractaRenderPipeline* pipeline)
{
  vtkAbstractArray* a =
    pipeline->GetLighting()->GetFieldData()->GetAbstractArray("SingleScatteringMethod");
  return a ? a->GetVariantValue(0).ToString() : std::string("photons");
}
}

TEST(PipelineSingleScattering, PlanChoosesAndReports)
{
  auto straight = Haze(false);
  auto automatic = Pipeline(straight, vtkEffectPlan::AUTOMATIC_METHOD);
  ASSERT_TRUE(automatic->UpdateLighting());
  vtkEffectPlan* plan = automatic->GetEffectPlan();
  EXPECT_EQ(plan->GetChosenSingleScatteringMethod(), vtkEffectPlan::LIGHT_RAYS);
  EXPECT_NE(
    std::string(plan->GetSingleScatteringMethodReason()).find("straight"), std::string::npos)
    << plan->GetSingleScatteringMethodReason();
  EXPECT_EQ(Ran(automatic), "light_rays");
  vtkAbstractArray* recorded =
    automatic->GetPlannedMedium()->GetFieldData()->GetAbstractArray("PlanSingleScatteringMethod");
  ASSERT_NE(recorded, nullptr);
  EXPECT_EQ(recorded->GetVariantValue(0).ToString(), "light_rays");

  auto interpolated = Pipeline(straight, vtkEffectPlan::INTERPOLATED);
  ASSERT_TRUE(interpolated->UpdateLighting());
  EXPECT_EQ(Ran(interpolated), "interpolated");
  EXPECT_NE(
    std::string(interpolated->GetEffectPlan()->GetSingleScatteringMethodReason()).find("forced"),
    std::string::npos);

  auto curved = Pipeline(Haze(true), vtkEffectPlan::AUTOMATIC_METHOD);
  ASSERT_TRUE(curved->UpdateLighting());
  EXPECT_EQ(curved->GetEffectPlan()->GetChosenSingleScatteringMethod(), vtkEffectPlan::PHOTONS);
  EXPECT_EQ(Ran(curved), "photons");
}

// The same S1 from the light rays and from 2^16 photons: RMS within 4% (photon noise and the
// voxel average against the centre value).
TEST(PipelineSingleScattering, LightRaysAgreeWithPhotons)
{
  auto straight = Haze(false);
  auto rays = Pipeline(straight, vtkEffectPlan::LIGHT_RAYS);
  auto photons = Pipeline(straight, vtkEffectPlan::PHOTONS);
  ASSERT_TRUE(rays->UpdateLighting());
  ASSERT_TRUE(photons->UpdateLighting());
  auto radiance = [](vtkRefractaRenderPipeline* p)
  {
    return vtkFloatArray::SafeDownCast(
      p->GetLighting()->GetPointData()->GetArray(vtkRefractaLightingVolume::RadianceName()));
  };
  vtkFloatArray* a = radiance(rays);
  vtkFloatArray* b = radiance(photons);
  ASSERT_NE(a, nullptr);
  ASSERT_NE(b, nullptr);
  double diff = 0, ref = 0;
  for (vtkIdType i = 0; i < a->GetNumberOfValues(); ++i)
  {
    diff += std::pow(a->GetValue(i) - b->GetValue(i), 2);
    ref += std::pow(a->GetValue(i), 2);
  }
  EXPECT_LT(std::sqrt(diff / ref), 0.04);
}

namespace
{
// The scene of Refracta.EffectPlanHonesty's multiple-scattering case: a ball of radius 0.35 with
// a sharp edge (sigma_t 8 inside, 0 outside, albedo 0.9) on 20^3 voxels, lit obliquely by the sun.
vtkSmartPointer<vtkImageData> DenseBall()
{
  const int n = 20;
  const double h = 1.0 / n;
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(n, n, n);
  image->SetSpacing(h, h, h);
  image->SetOrigin(0.5 * h, 0.5 * h, 0.5 * h);
  vtkNew<vtkFloatArray> ext, alb;
  ext->SetName(vtkRefractaMedium::ExtinctionName());
  ext->SetNumberOfComponents(3);
  alb->SetName(vtkRefractaMedium::AlbedoName());
  alb->SetNumberOfComponents(3);
  for (vtkIdType id = 0; id < image->GetNumberOfPoints(); ++id)
  {
    double p[3];
    image->GetPoint(id, p);
    const double r = std::sqrt(
      (p[0] - 0.5) * (p[0] - 0.5) + (p[1] - 0.5) * (p[1] - 0.5) + (p[2] - 0.5) * (p[2] - 0.5));
    for (int c = 0; c < 3; ++c)
    {
      ext->InsertNextValue(r < 0.35 ? 8.0f : 0.0f);
      alb->InsertNextValue(0.9f);
    }
  }
  image->GetPointData()->AddArray(ext);
  image->GetPointData()->AddArray(alb);
  return image;
}

struct Lit
{
  std::vector<double> S1, Multiple, Image; // Radiance, MultipleScattering, image RGB
};

std::vector<double> Values(vtkRefractaRenderPipeline* p, const char* name)
{
  std::vector<double> out;
  vtkDataArray* a = p->GetLighting()->GetPointData()->GetArray(name);
  for (vtkIdType i = 0; a && i < a->GetNumberOfValues(); ++i)
  {
    out.push_back(a->GetVariantValue(i).ToDouble());
  }
  return out;
}

// The ball lit with multiple scattering on: S1 from `method` (light rays: the lattice on their
// output; photons: the photon/diffusion schedule), 32 x 32 pixels.
Lit RenderBall(vtkImageData* ball, int method, bool smoothing)
{
  auto p = Pipeline(ball, method);
  vtkLight* sun = vtkLight::SafeDownCast(p->GetLights()->GetItemAsObject(0));
  sun->SetPosition(0.5, 3.0, 0.8);
  p->GetCamera()->SetPosition(0.5, 0.5, 3.0);
  p->GetCamera()->SetViewAngle(25);
  p->SetMultipleScattering(true);
  p->GetPhotonTracer()->SetNumberOfPhotons(1 << 18);
  p->GetPhotonTracer()->SetSeed(3);
  p->GetPhotonTracer()->SetSmoothing(smoothing);
  Lit lit;
  if (!p->Render(32, 32))
  {
    ADD_FAILURE() << "render failed";
    return lit;
  }
  EXPECT_EQ(Ran(p), method == vtkEffectPlan::PHOTONS ? "photons" : "light_rays");
  lit.S1 = Values(p, vtkRefractaLightingVolume::RadianceName());
  lit.Multiple = Values(p, vtkRefractaLightingVolume::MultipleScatteringName());
  const std::vector<float>& image = p->GetImage();
  for (size_t q = 0; q < image.size(); ++q)
  {
    if (q % 4 != 3)
    {
      lit.Image.push_back(image[q]);
    }
  }
  return lit;
}

double Total(const std::vector<double>& v)
{
  double sum = 0;
  for (double x : v)
  {
    sum += x;
  }
  return sum;
}

// sqrt(sum (a - b)^2 / sum b^2), a scaled by `scale`.
double RelativeL2(const std::vector<double>& a, const std::vector<double>& b, double scale = 1.0)
{
  double d = 0, n = 0;
  for (size_t i = 0; i < a.size() && i < b.size(); ++i)
  {
    d += (scale * a[i] - b[i]) * (scale * a[i] - b[i]);
    n += b[i] * b[i];
  }
  return n > 0 ? std::sqrt(d / n) : 0.0;
}
}

// Light rays + the lattice (vtkLatticeBoltzmannLighting) against photons + the photon/diffusion
// schedule on the same scene, multiple scattering on: the scene where the two were found to differ
// by 15% (relative L2 of the image). Measured (2^18 photons, PoCL on the CPU):
//   photons smoothed (the default): image 15.2%, MultipleScattering total +2.1%, S1 total -3.8%;
//   photons unsmoothed:             image  6.6%, MultipleScattering total -0.5% (per voxel 2.2%
//                                   relative L2), S1 total -3.8%
// (light rays against photons). The lattice is not the cause: both paths run the same solver
// settings (104 iterations each, tolerance 1e-4, block 4) and, given the same source, the same
// result. The causes are the S1 each gives the lattice and the view pass:
// - the photon pass's 3x3x3 smoothing spreads S1 one voxel across the ball's sharp edge into
//   voxels that do not scatter (the view pass then shows a glow around the ball, and the
//   lattice, whose medium is piecewise constant, loses the source put there): against the
//   reference restricted to one scattering event (Refracta.SingleScatteringAgainstReference,
//   DenseBall) the smoothed photons are +6.7% biased with region errors up to 42%, unsmoothed
//   +1.4% and 12%;
// - S1 at voxel centres (light rays) against voxel means (photons): 3.8% less scattered power in
//   the edge voxels (Documentation/Physics.md, "Voxel centre or voxel mean").
// Bounds (against the unsmoothed photons, 1.5 to 4 times the measured): MultipleScattering totals
// within 2% and per voxel within 4% relative L2, S1 totals within 6%, image within 10%. A lattice
// source normalised differently in one path (the suspected cause) fails: the light rays'
// MultipleScattering x 1.1 must break the 2% bound.
TEST(PipelineSingleScattering, MultipleScatteringAgreesWithPhotons)
{
  auto ball = DenseBall();
  const Lit rays = RenderBall(ball, vtkEffectPlan::LIGHT_RAYS, false);
  const Lit photons = RenderBall(ball, vtkEffectPlan::PHOTONS, false);
  const Lit smoothed = RenderBall(ball, vtkEffectPlan::PHOTONS, true);
  ASSERT_FALSE(rays.Multiple.empty());
  ASSERT_EQ(rays.Multiple.size(), photons.Multiple.size());
  ASSERT_EQ(rays.Image.size(), photons.Image.size());
  const double msTotal = Total(rays.Multiple) / Total(photons.Multiple) - 1;
  const double s1Total = Total(rays.S1) / Total(photons.S1) - 1;
  const double msL2 = RelativeL2(rays.Multiple, photons.Multiple);
  const double image = RelativeL2(rays.Image, photons.Image);
  std::cout << "light rays against unsmoothed photons: MultipleScattering total " << 100 * msTotal
            << "%, relative L2 " << 100 * msL2 << "%; S1 total " << 100 * s1Total
            << "%; image relative L2 " << 100 * image << "%\n"
            << "against smoothed photons: MultipleScattering total "
            << 100 * (Total(rays.Multiple) / Total(smoothed.Multiple) - 1) << "%, image "
            << 100 * RelativeL2(rays.Image, smoothed.Image) << "%" << std::endl;
  EXPECT_LT(std::abs(msTotal), 0.02);
  EXPECT_LT(msL2, 0.04);
  EXPECT_LT(std::abs(s1Total), 0.06);
  EXPECT_LT(image, 0.10);
  EXPECT_GT(std::abs(1.1 * Total(rays.Multiple) / Total(photons.Multiple) - 1), 0.02)
    << "a 10% error in the lattice's source passes: the test cannot see it";
}

// The light rays and the lattice on their output report the pipeline's lighting progress (half
// each, monotone) and honour AbortRender(): an abort while the light rays run stops the render
// without an error, and the next render gives the image of a pipeline never aborted.
TEST(PipelineSingleScattering, LightRaysReportProgressAndAbort)
{
  auto straight = Haze(false);
  auto reference = Pipeline(straight, vtkEffectPlan::LIGHT_RAYS);
  reference->SetMultipleScattering(true);
  ASSERT_TRUE(reference->Render(24, 24));

  auto pipeline = Pipeline(straight, vtkEffectPlan::LIGHT_RAYS);
  pipeline->SetMultipleScattering(true);
  struct Log
  {
    vtkRefractaRenderPipeline* Pipeline = nullptr;
    std::vector<double> Progress;
    double AbortAbove = 2.0;
    int Errors = 0;
  } log;
  log.Pipeline = pipeline;
  vtkNew<vtkCallbackCommand> onProgress;
  onProgress->SetClientData(&log);
  onProgress->SetCallback(
    [](vtkObject*, unsigned long, void* client, void* call)
    {
      auto* l = static_cast<Log*>(client);
      const double p = *static_cast<double*>(call);
      l->Progress.push_back(p);
      if (p > l->AbortAbove)
      {
        l->AbortAbove = 2.0;
        l->Pipeline->AbortRender();
      }
    });
  vtkNew<vtkCallbackCommand> onError;
  onError->SetClientData(&log);
  onError->SetCallback(
    [](vtkObject*, unsigned long, void* client, void*) { ++static_cast<Log*>(client)->Errors; });
  vtkNew<vtkObject> owner;
  owner->AddObserver(vtkCommand::ErrorEvent, onError);
  pipeline->SetEventOwner(owner);
  pipeline->AddObserver(vtkCommand::ProgressEvent, onProgress);

  // The lighting stage starts after the plan's small share: abort a little into it.
  log.AbortAbove = 0.05;
  EXPECT_FALSE(pipeline->Render(24, 24));
  EXPECT_TRUE(pipeline->GetLastRenderAborted());
  EXPECT_TRUE(pipeline->GetLightRays()->GetLastRunAborted())
    << "the abort did not reach the light rays";
  EXPECT_EQ(pipeline->GetNumberOfViewPassRuns(), 0);
  EXPECT_EQ(log.Errors, 0) << "an abort is not an error";

  log.Progress.clear();
  ASSERT_TRUE(pipeline->Render(24, 24));
  EXPECT_FALSE(pipeline->GetLastRenderAborted());
  EXPECT_EQ(log.Errors, 0);
  EXPECT_EQ(pipeline->GetImage(), reference->GetImage()) << "same scene: same image";
  ASSERT_GE(log.Progress.size(), 8u) << "the light passes report progress";
  for (size_t i = 1; i < log.Progress.size(); ++i)
  {
    EXPECT_GE(log.Progress[i], log.Progress[i - 1]) << "at event " << i;
  }
  EXPECT_DOUBLE_EQ(log.Progress.back(), 1.0);
}

// The first-collision split with light rays for single scattering (issue 14): the photons still
// carry their k orders (vtkLatticeBoltzmannLighting's port 2) and the lattice the rest, so the
// multiple scattering is the split's on photons alone (the orders above S1 do not depend on where
// S1 comes from: the same photons, the same source) while S1 is the light rays'; with photons
// carrying every order no lattice runs and the field agrees with the split's (RMS within 5%).
TEST(PipelineSingleScattering, FirstCollisionSplitWorksWithLightRays)
{
  auto straight = Haze(false);
  auto multiple = [&](int single, int method)
  {
    auto p = Pipeline(straight, single);
    p->SetMultipleScattering(true);
    p->SetMultipleScatteringMethod(method);
    p->SetScatteringOrders(method == vtkEffectPlan::FIRST_COLLISION_SPLIT ? 3 : 0);
    p->GetPhotonTracer()->SetNumberOfPhotons(1 << 17);
    EXPECT_TRUE(p->UpdateLighting());
    return p;
  };
  auto rays = multiple(vtkEffectPlan::LIGHT_RAYS, vtkEffectPlan::FIRST_COLLISION_SPLIT);
  auto photons = multiple(vtkEffectPlan::PHOTONS, vtkEffectPlan::FIRST_COLLISION_SPLIT);
  auto every = multiple(vtkEffectPlan::LIGHT_RAYS, vtkEffectPlan::PHOTONS_EVERY_ORDER);
  EXPECT_EQ(Ran(rays), "light_rays");
  EXPECT_EQ(rays->GetPhotonTracer()->GetUsedScatteringOrders(), 3);
  EXPECT_EQ(every->GetPhotonTracer()->GetUsedScatteringOrders(), vtkPhotonTracer::EVERY_ORDER);
  vtkDataArray* iterations =
    every->GetLighting()->GetFieldData()->GetArray("LatticeBoltzmannIterations");
  ASSERT_NE(iterations, nullptr);
  EXPECT_EQ(iterations->GetTuple1(0), 0.0) << "every order by photons: no lattice";
  auto rms = [](vtkRefractaRenderPipeline* a, vtkRefractaRenderPipeline* b)
  {
    const char* name = vtkRefractaLightingVolume::MultipleScatteringName();
    vtkDataArray* x = a->GetLighting()->GetPointData()->GetArray(name);
    vtkDataArray* y = b->GetLighting()->GetPointData()->GetArray(name);
    double diff = 0, ref = 0;
    for (vtkIdType i = 0; x && y && i < x->GetNumberOfValues(); ++i)
    {
      diff += std::pow(x->GetVariantValue(i).ToDouble() - y->GetVariantValue(i).ToDouble(), 2);
      ref += std::pow(y->GetVariantValue(i).ToDouble(), 2);
    }
    return ref > 0 ? std::sqrt(diff / ref) : 1.0;
  };
  const double splitDifference = rms(rays, photons);
  const double everyDifference = rms(every, photons);
  std::cout << "MultipleScattering RMS difference: split with light rays vs photons "
            << splitDifference << ", every order vs split " << everyDifference << "\n";
  EXPECT_LT(splitDifference, 1e-6);
  EXPECT_LT(everyDifference, 0.05);
  vtkDataArray* s1Rays =
    rays->GetLighting()->GetPointData()->GetArray(vtkRefractaLightingVolume::RadianceName());
  vtkDataArray* s1Photons =
    photons->GetLighting()->GetPointData()->GetArray(vtkRefractaLightingVolume::RadianceName());
  ASSERT_TRUE(s1Rays && s1Photons);
  double differs = 0;
  for (vtkIdType i = 0; i < s1Rays->GetNumberOfValues(); ++i)
  {
    differs +=
      std::fabs(s1Rays->GetVariantValue(i).ToDouble() - s1Photons->GetVariantValue(i).ToDouble());
  }
  EXPECT_GT(differs, 0.0) << "S1 comes from the light rays, not the photons";
}

// A white fog (albedo 1) around a clear ball (no extinction, albedo 0 as a voxelized glass body
// has it): nothing can absorb, so the photons must book no absorption. Interpolating the albedo
// between the ball's 0 and the fog's 1 made the fog's rim absorb 0.3% of the power before the
// pipeline gave clear voxels their neighbours' albedo (vtkRefractaMedium::
// FillAlbedoWithoutExtinction; outside review).
TEST(PipelineSingleScattering, AWhiteFogAroundClearGlassAbsorbsNothing)
{
  auto medium = Haze(false);
  auto* ext = vtkFloatArray::SafeDownCast(medium->GetPointData()->GetArray("Extinction"));
  auto* alb = vtkFloatArray::SafeDownCast(medium->GetPointData()->GetArray("Albedo"));
  for (vtkIdType id = 0; id < medium->GetNumberOfPoints(); ++id)
  {
    double p[3];
    medium->GetPoint(id, p);
    const double r = std::sqrt((p[0] - 0.475) * (p[0] - 0.475) + (p[1] - 0.475) * (p[1] - 0.475) +
      (p[2] - 0.475) * (p[2] - 0.475));
    const bool ball = r < 0.25;
    for (int c = 0; c < 3; ++c)
    {
      ext->SetComponent(id, c, ball ? 0.0 : 4.0);
      alb->SetComponent(id, c, ball ? 0.0 : 1.0);
    }
  }
  auto pipeline = Pipeline(medium, vtkEffectPlan::PHOTONS);
  ASSERT_TRUE(pipeline->Render(16, 16));
  vtkImageData* photons = pipeline->GetPhotonTracer()->GetOutput();
  vtkDataArray* emitted = photons->GetFieldData()->GetArray("EnergyEmitted");
  vtkDataArray* absorbed = photons->GetFieldData()->GetArray("EnergyAbsorbed");
  ASSERT_TRUE(emitted && absorbed);
  std::cout << "absorbed / emitted " << absorbed->GetComponent(0, 0) / emitted->GetComponent(0, 0)
            << "\n";
  EXPECT_GT(emitted->GetComponent(0, 0), 0.0);
  EXPECT_LT(absorbed->GetComponent(0, 0), 1e-6 * emitted->GetComponent(0, 0));
  // The input's albedo is not written.
  EXPECT_EQ(
    alb->GetComponent(medium->ComputePointId(std::array<int, 3>{ 9, 9, 9 }.data()), 0), 0.0);
}
