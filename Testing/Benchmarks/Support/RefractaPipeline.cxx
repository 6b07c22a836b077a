#include "RefractaPipeline.h"

#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkEffectPlan.h"
#include "vtkImageData.h"
#include "vtkLatticeBoltzmannLighting.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkPhotonTracer.h"
#include "vtkPointData.h"
#include "vtkRefractaImageRenderer.h"
#include "vtkSceneAnalysis.h"

namespace refracta
{
namespace bench
{
bool PlanScene(const scenes::Scene& scene, vtkEffectPlan* plan)
{
  vtkNew<vtkSceneAnalysis> analysis;
  analysis->SetMedium(scene.Medium);
  for (const auto& light : scene.Lights)
  {
    analysis->AddLight(light);
  }
  if (!analysis->Analyze())
  {
    return false;
  }
  plan->Decide(analysis);
  return true;
}

std::vector<double> RenderPipeline(
  const scenes::Scene& scene, vtkEffectPlan* plan, const PipelineKnobs& knobs)
{
  vtkNew<vtkImageData> medium;
  plan->ApplyToMedium(scene.Medium, medium);
  vtkNew<vtkRefractaImageRenderer> renderer;
  vtkNew<vtkPhotonTracer> tracer;
  vtkNew<vtkLatticeBoltzmannLighting> lattice;
  if (!scene.Lights.empty() && plan->IsEnabled(vtkEffectPlan::SINGLE_SCATTERING))
  {
    tracer->SetInputData(medium);
    for (const auto& light : scene.Lights)
    {
      tracer->AddLight(light);
    }
    tracer->SetLightRadius(scene.LightRadius);
    tracer->SetDirectionalLightAngularRadius(scene.LightAngularRadius);
    tracer->SetNumberOfPhotons(knobs.Photons);
    tracer->SetMinimumStep(knobs.PhotonMinimumStep);
    tracer->SetPrimaryTolerance(knobs.PrimaryTolerance);
    tracer->SetSecondaryTolerance(knobs.SecondaryTolerance);
    tracer->Update();
    vtkImageData* lighting = tracer->GetOutput();
    if (plan->IsEnabled(vtkEffectPlan::MULTIPLE_SCATTERING))
    {
      lattice->SetInputData(medium);
      lattice->SetLightingData(lighting);
      lattice->SetTolerance(knobs.LatticeTolerance);
      lattice->SetBlockSize(knobs.BlockSize);
      lattice->Update();
      lighting = lattice->GetOutput();
    }
    renderer->SetLightingData(lighting);
  }
  renderer->SetInputData(medium);
  renderer->SetCamera(scene.Camera);
  renderer->SetImageSize(knobs.ImageWidth, knobs.ImageHeight);
  renderer->SetBackgroundColor(scene.Background[0], scene.Background[1], scene.Background[2]);
  renderer->SetStepSize(knobs.ViewStep);
  renderer->Update();
  std::vector<double> rgb;
  if (vtkDataArray* hdr = renderer->GetOutput()->GetPointData()->GetArray("HDR"))
  {
    rgb.reserve(3 * hdr->GetNumberOfTuples());
    for (vtkIdType p = 0; p < hdr->GetNumberOfTuples(); ++p)
    {
      for (int c = 0; c < 3; ++c)
      {
        rgb.push_back(hdr->GetComponent(p, c));
      }
    }
  }
  return rgb;
}
}
}
