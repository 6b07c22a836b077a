#include "vtkRefractaPluginLighting.h"

#include "vtkCallbackCommand.h"
#include "vtkDoubleArray.h"
#include "vtkEffectPlan.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkLightCollection.h"
#include "vtkObjectFactory.h"
#include "vtkPhotonTracer.h"
#include "vtkPointData.h"
#include "vtkRefractaPluginInputCheck.h"
#include "vtkRefractaPluginLightList.h"
#include "vtkRefractaRenderPipeline.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>

vtkStandardNewMacro(vtkRefractaPluginLighting);

namespace
{
// Forwards the pipeline's progress to the filter and the filter's abort flag to the pipeline.
void ForwardProgress(vtkObject* caller, unsigned long, void* clientData, void* callData)
{
  auto* self = static_cast<vtkRefractaPluginLighting*>(clientData);
  self->UpdateProgress(*static_cast<double*>(callData));
  if (self->GetAbortExecute())
  {
    static_cast<vtkRefractaRenderPipeline*>(caller)->AbortRender();
  }
}
}

//------------------------------------------------------------------------------
vtkRefractaPluginLighting::vtkRefractaPluginLighting()
  : Pipeline(vtkSmartPointer<vtkRefractaRenderPipeline>::New())
  , Lights(vtkSmartPointer<vtkRefractaPluginLightList>::New())
{
  this->Pipeline->SetEventOwner(this);
  vtkNew<vtkCallbackCommand> progress;
  progress->SetCallback(ForwardProgress);
  progress->SetClientData(this);
  this->Pipeline->AddObserver(vtkCommand::ProgressEvent, progress);
  this->QualitySettings.ApplyTo(this->Pipeline);
}

//------------------------------------------------------------------------------
vtkRefractaPluginLighting::~vtkRefractaPluginLighting()
{
  this->Pipeline->SetEventOwner(nullptr);
}

//------------------------------------------------------------------------------
vtkRefractaRenderPipeline* vtkRefractaPluginLighting::GetPipeline()
{
  return this->Pipeline;
}

//------------------------------------------------------------------------------
void vtkRefractaPluginLighting::SetLight(int index, double type, double px, double py, double pz,
  double fx, double fy, double fz, double r, double g, double b, double intensity, double coneAngle)
{
  this->Lights->SetLight(index, type, px, py, pz, fx, fy, fz, r, g, b, intensity, coneAngle);
  this->Pipeline->SetLights(this->Lights->GetLights());
  this->Modified();
}

//------------------------------------------------------------------------------
void vtkRefractaPluginLighting::RemoveAllLights()
{
  this->Lights->RemoveAllLights();
  this->Pipeline->RemoveAllLights();
  this->Modified();
}

//------------------------------------------------------------------------------
void vtkRefractaPluginLighting::SetQuality(int quality)
{
  if (this->QualitySettings.SetQuality(quality, this->Pipeline))
  {
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkRefractaPluginLighting::SetNumberOfPhotons(int photons)
{
  if (this->QualitySettings.SetNumberOfPhotons(photons, this->Pipeline))
  {
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkRefractaPluginLighting::SetVolumeCausticSubdivision(int subdivision)
{
  this->Pipeline->GetPhotonTracer()->SetVolumeCausticSubdivision(subdivision);
  this->Modified();
}

int vtkRefractaPluginLighting::GetVolumeCausticSubdivision()
{
  return this->Pipeline->GetPhotonTracer()->GetVolumeCausticSubdivision();
}

//------------------------------------------------------------------------------
void vtkRefractaPluginLighting::SetSeed(int seed)
{
  this->Pipeline->GetPhotonTracer()->SetSeed(static_cast<unsigned int>(seed));
  this->Modified();
}

//------------------------------------------------------------------------------
int vtkRefractaPluginLighting::GetSeed()
{
  return static_cast<int>(this->Pipeline->GetPhotonTracer()->GetSeed());
}

//------------------------------------------------------------------------------
void vtkRefractaPluginLighting::SetMultipleScattering(bool on)
{
  this->Pipeline->SetMultipleScattering(on);
  this->Modified();
}

//------------------------------------------------------------------------------
bool vtkRefractaPluginLighting::GetMultipleScattering()
{
  return this->Pipeline->GetMultipleScattering();
}

//------------------------------------------------------------------------------
void vtkRefractaPluginLighting::SetSingleScatteringMethod(int method)
{
  this->Pipeline->SetSingleScatteringMethod(method);
  this->Modified();
}

int vtkRefractaPluginLighting::GetSingleScatteringMethod()
{
  return this->Pipeline->GetSingleScatteringMethod();
}

void vtkRefractaPluginLighting::SetMultipleScatteringMethod(int method)
{
  this->Pipeline->SetMultipleScatteringMethod(method);
  this->Modified();
}

int vtkRefractaPluginLighting::GetMultipleScatteringMethod()
{
  return this->Pipeline->GetMultipleScatteringMethod();
}

void vtkRefractaPluginLighting::SetLattice(int directions)
{
  this->Pipeline->SetLattice(directions);
  this->Modified();
}

int vtkRefractaPluginLighting::GetLattice()
{
  return this->Pipeline->GetLattice();
}

void vtkRefractaPluginLighting::SetScatteringOrders(int orders)
{
  this->Pipeline->SetScatteringOrders(orders);
  this->Modified();
}

int vtkRefractaPluginLighting::GetScatteringOrders()
{
  return this->Pipeline->GetScatteringOrders();
}

//------------------------------------------------------------------------------
vtkMTimeType vtkRefractaPluginLighting::GetMTime()
{
  return std::max(this->Superclass::GetMTime(), this->Pipeline->GetInputsMTime());
}

//------------------------------------------------------------------------------
int vtkRefractaPluginLighting::FillInputPortInformation(int port, vtkInformation* info)
{
  // Any data object: a wrong type is reported once by RequestInformation (see
  // vtkRefractaPluginInputCheck.h) instead of by every pipeline pass.
  this->Superclass::FillInputPortInformation(port, info);
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataObject");
  return 1;
}

//------------------------------------------------------------------------------
int vtkRefractaPluginLighting::RequestInformation(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  const std::string wrong0 = refracta_plugin::CheckImageInput(inputVector, 0, "Refracta Lighting",
    "a Refracta medium (vtkImageData), e.g. from Refracta Mesh Voxelizer or Refracta Transfer "
    "Function Medium");
  if (!wrong0.empty())
  {
    vtkErrorMacro(<< wrong0);
    return refracta_plugin::EmptyInformation(outputVector);
  }
  return this->Superclass::RequestInformation(request, inputVector, outputVector);
}

//------------------------------------------------------------------------------
int vtkRefractaPluginLighting::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  return refracta_plugin::RequestWholeExtent(inputVector, 0); // the whole grid
}

//------------------------------------------------------------------------------
int vtkRefractaPluginLighting::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* medium = vtkImageData::GetData(inputVector[0], 0);
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  output->Initialize();
  if (!medium)
  {
    return 1; // a wrong input type, reported by RequestInformation
  }
  this->Pipeline->SetMedium(medium);
  if (!this->Pipeline->UpdateLighting())
  {
    // The pipeline said why (once); an empty output that stays until something changes, so
    // ParaView does not re-run the filter on every render.
    return 1;
  }
  vtkNew<vtkFieldData> fieldData;
  if (vtkImageData* lighting = this->Pipeline->GetLighting())
  {
    output->CopyStructure(lighting);
    output->GetPointData()->ShallowCopy(lighting->GetPointData());
    fieldData->ShallowCopy(lighting->GetFieldData());
  }
  else
  {
    output->CopyStructure(medium);
    vtkWarningMacro("No light pass ran: " << this->Pipeline->GetEffectPlan()->GetSummary()
                                          << " (a light must be on and the medium must scatter).");
  }
  this->Pipeline->GetEffectPlan()->RecordInFieldData(fieldData);
  for (int stage : { vtkRefractaRenderPipeline::PLAN, vtkRefractaRenderPipeline::LIGHTING })
  {
    vtkNew<vtkDoubleArray> seconds;
    seconds->SetName(stage == vtkRefractaRenderPipeline::PLAN ? "PlanSeconds" : "LightingSeconds");
    seconds->InsertNextValue(this->Pipeline->GetStageSeconds(stage));
    fieldData->AddArray(seconds);
  }
  output->SetFieldData(fieldData);
  return 1;
}

//------------------------------------------------------------------------------
void vtkRefractaPluginLighting::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Quality: " << this->QualitySettings.Quality << "\n";
  os << indent << "NumberOfPhotons: " << this->QualitySettings.NumberOfPhotons << "\n";
  os << indent << "VolumeCausticSubdivision: "
     << this->Pipeline->GetPhotonTracer()->GetVolumeCausticSubdivision() << "\n";
  os << indent << "MultipleScatteringMethod: " << this->GetMultipleScatteringMethod()
     << ", ScatteringOrders: " << this->GetScatteringOrders() << ", Lattice: " << this->GetLattice()
     << "\n";
  os << indent << "Lights:\n";
  this->Lights->PrintSelf(os, indent.GetNextIndent());
}
