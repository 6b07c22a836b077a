// vtkRefractiveVolumeMapper's settings: each forwards to the pipeline, the view pass, the photon
// tracer or the transfer-function mapping that owns it.
#include "vtkRefractiveVolumeMapper.h"
#include "vtkRefractiveVolumeMapperInternals.h"

#include "vtkEffectPlan.h"
#include "vtkLatticeBoltzmannSolver.h"
#include "vtkOpenCLContext.h"
#include "vtkPhotonTracer.h"
#include "vtkRefractaViewPass.h"
#include "vtkSceneAnalysis.h"

void vtkRefractiveVolumeMapper::SetRefractiveIndexFunction(vtkPiecewiseFunction* function)
{
  if (this->Internal->IndexFunction != function)
  {
    this->Internal->IndexFunction = function;
    this->Modified();
  }
}

vtkPiecewiseFunction* vtkRefractiveVolumeMapper::GetRefractiveIndexFunction()
{
  return this->Internal->IndexFunction;
}

void vtkRefractiveVolumeMapper::SetLightingData(vtkImageData* lighting)
{
  this->Internal->Pipeline->SetLightingData(lighting);
}

vtkImageData* vtkRefractiveVolumeMapper::GetLightingData()
{
  return this->Internal->Pipeline->GetLightingData();
}

void vtkRefractiveVolumeMapper::SetNumberOfPhotons(int photons)
{
  this->Internal->Pipeline->GetPhotonTracer()->SetNumberOfPhotons(photons);
}

int vtkRefractiveVolumeMapper::GetNumberOfPhotons()
{
  return this->Internal->Pipeline->GetPhotonTracer()->GetNumberOfPhotons();
}

void vtkRefractiveVolumeMapper::SetSeed(int seed)
{
  this->Internal->Pipeline->GetPhotonTracer()->SetSeed(static_cast<unsigned int>(seed));
}

int vtkRefractiveVolumeMapper::GetSeed()
{
  return static_cast<int>(this->Internal->Pipeline->GetPhotonTracer()->GetSeed());
}

void vtkRefractiveVolumeMapper::SetMultipleScattering(bool on)
{
  this->Internal->Pipeline->SetMultipleScattering(on);
}

bool vtkRefractiveVolumeMapper::GetMultipleScattering()
{
  return this->Internal->Pipeline->GetMultipleScattering();
}

void vtkRefractiveVolumeMapper::SetBackgroundIlluminates(bool on)
{
  if (this->Internal->Pipeline->GetBackgroundIlluminates() != on)
  {
    this->Internal->Pipeline->SetBackgroundIlluminates(on);
    this->Modified();
  }
}

bool vtkRefractiveVolumeMapper::GetBackgroundIlluminates()
{
  return this->Internal->Pipeline->GetBackgroundIlluminates();
}

void vtkRefractiveVolumeMapper::SetStepSize(double voxels)
{
  this->GetViewPass()->SetStepSize(voxels);
}

double vtkRefractiveVolumeMapper::GetStepSize()
{
  return this->GetViewPass()->GetStepSize();
}

void vtkRefractiveVolumeMapper::SetRayMode(int mode)
{
  this->GetViewPass()->SetRayMode(mode);
}

int vtkRefractiveVolumeMapper::GetRayMode()
{
  return this->GetViewPass()->GetRayMode();
}

void vtkRefractiveVolumeMapper::SetTransmittanceCutoff(double cutoff)
{
  this->GetViewPass()->SetTransmittanceCutoff(cutoff);
}

double vtkRefractiveVolumeMapper::GetTransmittanceCutoff()
{
  return this->GetViewPass()->GetTransmittanceCutoff();
}

void vtkRefractiveVolumeMapper::SetEmptySpaceSkipping(bool on)
{
  this->GetViewPass()->SetEmptySpaceSkipping(on);
}

bool vtkRefractiveVolumeMapper::GetEmptySpaceSkipping()
{
  return this->GetViewPass()->GetEmptySpaceSkipping();
}

void vtkRefractiveVolumeMapper::SetContext(vtkOpenCLContext* context)
{
  this->Internal->Pipeline->SetContext(context);
}

vtkOpenCLContext* vtkRefractiveVolumeMapper::GetContext()
{
  return this->Internal->Pipeline->GetContext();
}

vtkImageData* vtkRefractiveVolumeMapper::GetMedium()
{
  return this->Internal->Pipeline->GetPlannedMedium();
}

vtkImageData* vtkRefractiveVolumeMapper::GetLighting()
{
  return this->Internal->Pipeline->GetLighting();
}

vtkRefractaViewPass* vtkRefractiveVolumeMapper::GetViewPass()
{
  return this->Internal->Pipeline->GetViewPass();
}

vtkRefractaActorSurfaces* vtkRefractiveVolumeMapper::GetActorSurfaceCollector()
{
  return this->Internal->Actors;
}

vtkRefractaRendererBackground* vtkRefractiveVolumeMapper::GetBackgroundConverter()
{
  return this->Internal->Background;
}

vtkRefractaRenderPipeline* vtkRefractiveVolumeMapper::GetPipeline()
{
  return this->Internal->Pipeline;
}

vtkEffectPlan* vtkRefractiveVolumeMapper::GetEffectPlan()
{
  return this->Internal->Pipeline->GetEffectPlan();
}

vtkSceneAnalysis* vtkRefractiveVolumeMapper::GetSceneAnalysis()
{
  return this->Internal->Pipeline->GetSceneAnalysis();
}

int vtkRefractiveVolumeMapper::GetNumberOfMediumBuilds()
{
  return this->Internal->Pipeline->GetNumberOfMediumUpdates();
}

int vtkRefractiveVolumeMapper::GetNumberOfLightPassRuns()
{
  return this->Internal->Pipeline->GetNumberOfLightPassRuns();
}

int vtkRefractiveVolumeMapper::GetNumberOfViewPassRuns()
{
  return this->Internal->Pipeline->GetNumberOfViewPassRuns();
}

bool vtkRefractiveVolumeMapper::HasLightPasses()
{
  return true;
}

void vtkRefractiveVolumeMapper::SetQuality(int quality)
{
  this->Internal->Pipeline->SetQuality(quality);
}

void vtkRefractiveVolumeMapper::SetSingleScatteringMethod(int method)
{
  this->Internal->Pipeline->SetSingleScatteringMethod(method);
  this->Modified();
}

int vtkRefractiveVolumeMapper::GetSingleScatteringMethod()
{
  return this->Internal->Pipeline->GetSingleScatteringMethod();
}

void vtkRefractiveVolumeMapper::SetMultipleScatteringMethod(int method)
{
  this->Internal->Pipeline->SetMultipleScatteringMethod(method);
  this->Modified();
}

int vtkRefractiveVolumeMapper::GetMultipleScatteringMethod()
{
  return this->Internal->Pipeline->GetMultipleScatteringMethod();
}

void vtkRefractiveVolumeMapper::SetScatteringOrders(int orders)
{
  this->Internal->Pipeline->SetScatteringOrders(orders);
  this->Modified();
}

int vtkRefractiveVolumeMapper::GetScatteringOrders()
{
  return this->Internal->Pipeline->GetScatteringOrders();
}

void vtkRefractiveVolumeMapper::SetLattice(int directions)
{
  this->Internal->Pipeline->SetLattice(directions);
  this->Modified();
}

int vtkRefractiveVolumeMapper::GetLattice()
{
  return this->Internal->Pipeline->GetLattice();
}

void vtkRefractiveVolumeMapper::ReleaseGraphicsResources(vtkWindow*)
{
  // The image is drawn through the window's own pixel path; nothing of ours lives in GL.
}
