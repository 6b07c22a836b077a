// vtkRefractaRenderPipeline with opaque surfaces: a clear glass ball over a floor needs the photon
// pass only because of the floor (the plan turns SurfaceLighting on and says why; without the
// floor no light pass runs); moving the floor re-runs the light passes and the view, never the
// plan's medium stage; removing the surfaces re-plans and drops the photon pass again.
#include "vtkCamera.h"
#include "vtkEffectPlan.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPhotonTracer.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkRefractaLightingVolume.h"
#include "vtkRefractaRenderPipeline.h"
#include "vtkRefractaSurfaceSet.h"
#include "vtkSmartPointer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace
{
// A clear glass ball (n up to 1.5, nothing absorbs or scatters) in a 24^3 unit box.
vtkSmartPointer<vtkImageData> GlassBall()
{
  const int n = 24;
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(n, n, n);
  image->SetSpacing(1.0 / (n - 1), 1.0 / (n - 1), 1.0 / (n - 1));
  vtkNew<vtkFloatArray> idx;
  idx->SetName("RefractiveIndex");
  idx->SetNumberOfTuples(image->GetNumberOfPoints());
  for (vtkIdType id = 0; id < image->GetNumberOfPoints(); ++id)
  {
    double p[3];
    image->GetPoint(id, p);
    const double r = std::sqrt(
      (p[0] - 0.5) * (p[0] - 0.5) + (p[1] - 0.5) * (p[1] - 0.5) + (p[2] - 0.5) * (p[2] - 0.5));
    idx->SetValue(id, static_cast<float>(1.0 + 0.25 * (1.0 - std::tanh((r - 0.3) / 0.05))));
  }
  image->GetPointData()->AddArray(idx);
  return image;
}
}

TEST(PipelineSurfaces, FloorTurnsOnPhotonsAndMovingItKeepsThePlan)
{
  vtkNew<vtkRefractaRenderPipeline> pipeline;
  pipeline->SetMedium(GlassBall());
  vtkNew<vtkLight> sun;
  sun->SetLightTypeToSceneLight();
  sun->SetPositional(false);
  sun->SetPosition(0.5, 3.0, 0.5);
  sun->SetFocalPoint(0.5, 0.5, 0.5);
  pipeline->AddLight(sun);
  vtkNew<vtkCamera> camera;
  camera->SetPosition(0.5, 1.5, 3.0);
  camera->SetFocalPoint(0.5, 0.3, 0.5);
  pipeline->SetCamera(camera);
  pipeline->GetPhotonTracer()->SetNumberOfPhotons(1 << 14);

  // Without surfaces nothing scatters: no light pass.
  ASSERT_TRUE(pipeline->Render(32, 24));
  EXPECT_FALSE(pipeline->GetEffectPlan()->IsEnabled(vtkEffectPlan::SINGLE_SCATTERING));
  EXPECT_FALSE(pipeline->GetEffectPlan()->IsEnabled(vtkEffectPlan::SURFACE_LIGHTING));
  EXPECT_EQ(pipeline->GetNumberOfLightPassRuns(), 0);

  // A floor below the ball: the plan turns surface lighting on and says so; the photon pass runs.
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-1, -0.2, -1);
  plane->SetPoint1(2, -0.2, -1);
  plane->SetPoint2(-1, -0.2, 2);
  plane->Update();
  vtkNew<vtkMatrix4x4> placement;
  vtkNew<vtkRefractaSurfaceSet> surfaces;
  surfaces->AddSurface(plane->GetOutput(), nullptr, placement);
  pipeline->SetSurfaces(surfaces);
  ASSERT_TRUE(pipeline->Render(32, 24));
  vtkEffectPlan* plan = pipeline->GetEffectPlan();
  EXPECT_TRUE(plan->IsEnabled(vtkEffectPlan::SURFACE_LIGHTING));
  EXPECT_FALSE(plan->IsEnabled(vtkEffectPlan::SINGLE_SCATTERING));
  EXPECT_NE(std::string(plan->GetReason(vtkEffectPlan::SURFACE_LIGHTING)).find("1 surface(s)"),
    std::string::npos)
    << plan->GetReason(vtkEffectPlan::SURFACE_LIGHTING);
  EXPECT_NE(plan->GetSummary().find("SurfaceLighting on"), std::string::npos);
  EXPECT_EQ(pipeline->GetNumberOfLightPassRuns(), 1);
  EXPECT_TRUE(pipeline->GetPhotonTracer()->GetUsedSurfaces());
  vtkDataArray* irradiance = pipeline->GetPhotonTracer()->GetOutput()->GetFieldData()->GetArray(
    vtkRefractaLightingVolume::SurfaceIrradianceName());
  ASSERT_NE(irradiance, nullptr);
  EXPECT_EQ(irradiance->GetNumberOfTuples(), surfaces->GetNumberOfTexels());
  const int plans = pipeline->GetNumberOfPlanRuns();
  const int media = pipeline->GetNumberOfMediumUpdates();

  // Nothing changed: nothing re-runs but the image is returned.
  ASSERT_TRUE(pipeline->Render(32, 24));
  EXPECT_EQ(pipeline->GetNumberOfLightPassRuns(), 1);

  // Moving the floor: light passes again, same plan, same medium on the device.
  placement->SetElement(1, 3, -0.1);
  ASSERT_TRUE(pipeline->Render(32, 24));
  EXPECT_EQ(pipeline->GetNumberOfLightPassRuns(), 2);
  EXPECT_EQ(pipeline->GetNumberOfPlanRuns(), plans);
  EXPECT_EQ(pipeline->GetNumberOfMediumUpdates(), media);
  EXPECT_TRUE(pipeline->GetPhotonTracer()->GetLastRunReusedMedium());
  EXPECT_FALSE(pipeline->GetPhotonTracer()->GetLastRunReusedSurfaces());

  // Removing the surfaces re-plans: no light pass is needed any more.
  surfaces->RemoveAllSurfaces();
  ASSERT_TRUE(pipeline->Render(32, 24));
  EXPECT_EQ(pipeline->GetNumberOfPlanRuns(), plans + 1);
  EXPECT_FALSE(pipeline->GetEffectPlan()->IsEnabled(vtkEffectPlan::SURFACE_LIGHTING));
  EXPECT_EQ(pipeline->GetNumberOfLightPassRuns(), 2);
}
