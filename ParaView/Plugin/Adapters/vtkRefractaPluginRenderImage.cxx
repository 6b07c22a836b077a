#include "vtkRefractaPluginRenderImage.h"

#include "vtkCamera.h"
#include "vtkEffectPlan.h"
#include "vtkImageData.h"
#include "vtkLightCollection.h"
#include "vtkObjectFactory.h"
#include "vtkPhotonTracer.h"
#include "vtkRefractaPluginInputCheck.h"
#include "vtkRefractaPluginLightList.h"
#include "vtkRefractaRenderPipeline.h"
#include "vtkRefractaViewPass.h"

#include <algorithm>

vtkStandardNewMacro(vtkRefractaPluginRenderImage);

//------------------------------------------------------------------------------
vtkRefractaPluginRenderImage::vtkRefractaPluginRenderImage()
  : Lights(vtkSmartPointer<vtkRefractaPluginLightList>::New())
{
  vtkNew<vtkCamera> camera;
  camera->SetPosition(0, 0, 1);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetViewUp(0, 1, 0);
  camera->SetViewAngle(30);
  this->SetCamera(camera);
  this->QualitySettings.ApplyTo(this->GetPipeline());
}

//------------------------------------------------------------------------------
vtkRefractaPluginRenderImage::~vtkRefractaPluginRenderImage() = default;

//------------------------------------------------------------------------------
void vtkRefractaPluginRenderImage::SetCameraPosition(double x, double y, double z)
{
  this->GetCamera()->SetPosition(x, y, z);
}

//------------------------------------------------------------------------------
void vtkRefractaPluginRenderImage::SetCameraFocalPoint(double x, double y, double z)
{
  this->GetCamera()->SetFocalPoint(x, y, z);
}

//------------------------------------------------------------------------------
void vtkRefractaPluginRenderImage::SetCameraViewUp(double x, double y, double z)
{
  this->GetCamera()->SetViewUp(x, y, z);
}

//------------------------------------------------------------------------------
void vtkRefractaPluginRenderImage::SetCameraViewAngle(double degrees)
{
  this->GetCamera()->SetViewAngle(std::min(std::max(degrees, 0.01), 179.0));
}

//------------------------------------------------------------------------------
void vtkRefractaPluginRenderImage::SetLight(int index, double type, double px, double py, double pz,
  double fx, double fy, double fz, double r, double g, double b, double intensity, double coneAngle)
{
  this->Lights->SetLight(index, type, px, py, pz, fx, fy, fz, r, g, b, intensity, coneAngle);
  this->GetPipeline()->SetLights(this->Lights->GetLights());
  this->Modified();
}

//------------------------------------------------------------------------------
void vtkRefractaPluginRenderImage::RemoveAllPluginLights()
{
  this->Lights->RemoveAllLights();
  this->RemoveAllLights();
}

//------------------------------------------------------------------------------
void vtkRefractaPluginRenderImage::SetQuality(int quality)
{
  if (this->QualitySettings.SetQuality(quality, this->GetPipeline()))
  {
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkRefractaPluginRenderImage::SetNumberOfPhotons(int photons)
{
  if (this->QualitySettings.SetNumberOfPhotons(photons, this->GetPipeline()))
  {
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkRefractaPluginRenderImage::SetSeed(int seed)
{
  this->GetPipeline()->GetPhotonTracer()->SetSeed(static_cast<unsigned int>(seed));
  this->Modified();
}

//------------------------------------------------------------------------------
void vtkRefractaPluginRenderImage::SetVolumeCausticSubdivision(int subdivision)
{
  this->GetPipeline()->GetPhotonTracer()->SetVolumeCausticSubdivision(subdivision);
  this->Modified();
}

//------------------------------------------------------------------------------
void vtkRefractaPluginRenderImage::SetGlassSupersampling(int samples)
{
  this->GetViewPass()->SetDielectricSupersampling(samples);
  this->Modified();
}

//------------------------------------------------------------------------------
void vtkRefractaPluginRenderImage::SetMultipleScattering(bool on)
{
  this->GetPipeline()->SetMultipleScattering(on);
  this->Modified();
}

//------------------------------------------------------------------------------
int vtkRefractaPluginRenderImage::FillInputPortInformation(int port, vtkInformation* info)
{
  // Any data object: a wrong type is reported once by RequestInformation (see
  // vtkRefractaPluginInputCheck.h) instead of by every pipeline pass.
  this->Superclass::FillInputPortInformation(port, info);
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataObject");
  return 1;
}

//------------------------------------------------------------------------------
int vtkRefractaPluginRenderImage::RequestInformation(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  const char* valid[2] = { "a Refracta medium (vtkImageData), e.g. from Refracta Mesh Voxelizer",
    "a lighting volume (vtkImageData) from Refracta Lighting" };
  for (int port = 0; port < 2; ++port)
  {
    const std::string wrong =
      refracta_plugin::CheckImageInput(inputVector, port, "Refracta Render Image", valid[port]);
    if (!wrong.empty())
    {
      vtkErrorMacro(<< wrong);
      return refracta_plugin::EmptyInformation(outputVector);
    }
  }
  return this->Superclass::RequestInformation(request, inputVector, outputVector);
}

//------------------------------------------------------------------------------
int vtkRefractaPluginRenderImage::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  if (!refracta_plugin::CheckImageInput(inputVector, 0, "", "").empty() ||
    !refracta_plugin::CheckImageInput(inputVector, 1, "", "").empty())
  {
    vtkImageData::GetData(outputVector, 0)->Initialize();
    return 1; // a wrong input type, reported by RequestInformation
  }
  if (!this->Superclass::RequestData(request, inputVector, outputVector))
  {
    // Reported by the render pipeline (once per distinct message); an empty output that stays
    // until something changes, so ParaView does not re-run the filter on every render.
    vtkImageData::GetData(outputVector, 0)->Initialize();
  }
  return 1;
}

//------------------------------------------------------------------------------
void vtkRefractaPluginRenderImage::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Quality: " << this->QualitySettings.Quality << "\n";
  os << indent << "NumberOfPhotons: " << this->QualitySettings.NumberOfPhotons << "\n";
  os << indent << "VolumeCausticSubdivision: "
     << this->GetPipeline()->GetPhotonTracer()->GetVolumeCausticSubdivision() << "\n";
  os << indent << "GlassSupersampling: " << this->GetViewPass()->GetDielectricSupersampling()
     << "\n";
  os << indent << "Lights:\n";
  this->Lights->PrintSelf(os, indent.GetNextIndent());
}
