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
#include "vtkLightCollection.h"
#include "vtkLightRaySingleScattering.h"
#include "vtkLatticeBoltzmannSolver.h"
#include "vtkDataArray.h"
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

namespace
{
vtkSmartPointer<vtkImageData> DenseBall()
{
  const int n = 20;
  const double h = 1.0 / n;
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(n, n, n);
  image->SetSpacing(h, h, h);
  image->SetOrigin(0.5 * h, 0.5 * h, 0.5 * h);
  vtkNew<vtkFloatArray> ext, alb;
  ext->SetName("Extinction");
  ext->SetNumberOfComponents(3);
  alb->SetName("Albedo");
  alb->SetNumberOfComponents(3);
  for (vtkIdType id = 0; id < image->GetNumberOfPoints(); ++id)
  {
    double p[3];
    image->GetPoint(id, p);
    const double r = std::sqrt((p[0] - 0.5) * (p[0] - 0.5) + (p[1] - 0.5) * (p[1] - 0.5) +
      (p[2] - 0.5) * (p[2] - 0.5));
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

double Sum(vtkRefractaRenderPipeline* p, const char* name)
{
  vtkDataArray* a = p->GetLighting()->GetPointData()->GetArray(name);
  double s = 0;
  for (vtkIdType i = 0; a && i < a->GetNumberOfValues(); ++i)
  {
    s += a->GetVariantValue(i).ToDouble();
  }
  return s;
}
}

TEST(PipelineSingleScattering, Measure)
{
  auto ball = DenseBall();
  for (int variant = 0; variant < 4; ++variant)
  {
    double s[2], m[2], img[2];
    std::vector<float> ims[2];
    for (int k = 0; k < 2; ++k)
    {
      auto p = Pipeline(ball, k == 0 ? vtkEffectPlan::LIGHT_RAYS : vtkEffectPlan::PHOTONS);
      vtkLight* sun = vtkLight::SafeDownCast(p->GetLights()->GetItemAsObject(0));
      sun->SetPosition(0.5, 3.0, 0.8);
      vtkCamera* cam = p->GetCamera();
      cam->SetPosition(0.5, 0.5, 3.0);
      cam->SetViewAngle(25);
      p->SetMultipleScattering(true);
      p->GetPhotonTracer()->SetNumberOfPhotons(variant == 0 ? 1 << 15 : 1 << 18);
      p->GetPhotonTracer()->SetSeed(3);
      p->GetLightRays()->SetVoxelAverage(getenv("AVG") != nullptr);
      p->GetPhotonTracer()->SetSmoothing(variant != 2);
      if (variant == 3)
        p->SetQuality(vtkEffectPlan::DRAFT);
      ASSERT_TRUE(p->Render(32, 32));
      s[k] = Sum(p, vtkRefractaLightingVolume::RadianceName());
      m[k] = Sum(p, vtkRefractaLightingVolume::MultipleScatteringName());
      img[k] = 0;
      ims[k] = p->GetImage();
      for (size_t q = 0; q < ims[k].size(); ++q)
        img[k] += q % 4 == 3 ? 0.0 : ims[k][q];
      vtkDataArray* it = p->GetLighting()->GetFieldData()->GetArray("LatticeBoltzmannIterations");
      std::cout << " averaged " << p->GetLightRays()->GetNumberOfAveragedVoxels() << " in "
                << p->GetLightRays()->GetAveragingSeconds() << " s of "
                << p->GetLightRays()->GetTotalSeconds() << " s; evaluated "
                << p->GetLightRays()->GetNumberOfEvaluatedPoints();
      std::cout << " iterations " << (it ? it->GetTuple1(0) : -1) << " tol "
                << p->GetLatticeSolver()->GetTolerance() << std::endl;
    }
    double d = 0, n = 0;
    for (size_t q = 0; q < ims[0].size(); ++q)
      if (q % 4 != 3)
      {
        d += (ims[0][q] - ims[1][q]) * (ims[0][q] - ims[1][q]);
        n += ims[1][q] * ims[1][q];
      }
    std::cout << "variant " << variant << " S1 " << s[0] << " " << s[1] << " MS " << m[0] << " "
              << m[1] << " img " << img[0] << " " << img[1] << " relL2 " << std::sqrt(d / n)
              << std::endl;
  }
}
