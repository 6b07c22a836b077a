#include "RefractaPipeline.h"

#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkEffectPlan.h"
#include "vtkImageData.h"
#include "vtkLatticeBoltzmannSolver.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkPhotonTracer.h"
#include "vtkPointData.h"
#include "vtkRefractaImageRenderer.h"
#include "vtkRefractaRenderPipeline.h"
#include "vtkSceneAnalysis.h"

#include <algorithm>

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
  // The shipping pipeline, with the caller's plan settings (tolerance and per-effect modes).
  vtkNew<vtkRefractaImageRenderer> renderer;
  vtkRefractaRenderPipeline* pipeline = renderer->GetPipeline();
  vtkEffectPlan* own = pipeline->GetEffectPlan();
  own->SetTolerance(plan->GetTolerance());
  for (int e = 0; e < vtkEffectPlan::NUMBER_OF_EFFECTS; ++e)
  {
    own->SetEffectMode(e, plan->GetEffectMode(e));
  }
  for (const auto& light : scene.Lights)
  {
    renderer->AddLight(light);
  }
  vtkPhotonTracer* tracer = pipeline->GetPhotonTracer();
  tracer->SetLightRadius(scene.LightRadius);
  tracer->SetDirectionalLightAngularRadius(scene.LightAngularRadius);
  tracer->SetNumberOfPhotons(knobs.Photons);
  tracer->SetMinimumStep(knobs.PhotonMinimumStep);
  tracer->SetPrimaryTolerance(knobs.PrimaryTolerance);
  tracer->SetSecondaryTolerance(knobs.SecondaryTolerance);
  pipeline->GetLatticeSolver()->SetTolerance(knobs.LatticeTolerance);
  pipeline->GetLatticeSolver()->SetBlockSize(knobs.BlockSize);
  pipeline->SetLattice(knobs.Lattice);
  if (knobs.ScatteringOrders > -2)
  {
    const int k = knobs.ScatteringOrders;
    pipeline->SetMultipleScatteringMethod(k == 0
        ? vtkEffectPlan::LATTICE_ONLY
        : (k > 0 ? vtkEffectPlan::FIRST_COLLISION_SPLIT : vtkEffectPlan::PHOTONS_EVERY_ORDER));
    pipeline->SetScatteringOrders(std::max(k, 0));
  }
  renderer->SetInputData(scene.Medium);
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
