// The plan's choice of the single-scattering method in the pipeline (issue 15): straight light
// gets light rays (or the interpolation) and says why; refraction keeps the photons; a forced
// method runs; the light rays and the photons agree on the same scene.
#include "vtkAbstractArray.h"
#include "vtkCamera.h"
#include "vtkEffectPlan.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkPhotonTracer.h"
#include "vtkPointData.h"
#include "vtkRefractaLightingVolume.h"
#include "vtkRefractaRenderPipeline.h"
#include "vtkSmartPointer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

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
