#include "vtkRefractaPluginRenderImage.h"

#include "vtkCamera.h"
#include "vtkEffectPlan.h"
#include "vtkLightCollection.h"
#include "vtkObjectFactory.h"
#include "vtkPhotonTracer.h"
#include "vtkRefractaPluginLightList.h"
#include "vtkRefractaRenderPipeline.h"

#include <algorithm>

vtkStandardNewMacro(vtkRefractaPluginRenderImage);

//------------------------------------------------------------------------------
vtkRefractaPluginRenderImage::vtkRefractaPluginRenderImage()
  : Lights(vtkSmartPointer<vtkRefractaPluginLightList>::New())
  , Quality(vtkEffectPlan::INTERACTIVE)
{
  vtkNew<vtkCamera> camera;
  camera->SetPosition(0, 0, 1);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetViewUp(0, 1, 0);
  camera->SetViewAngle(30);
  this->SetCamera(camera);
  this->ApplyQuality();
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
void vtkRefractaPluginRenderImage::SetLight(int index, double type, double px, double py,
  double pz, double fx, double fy, double fz, double r, double g, double b, double intensity,
  double coneAngle)
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
void vtkRefractaPluginRenderImage::ApplyQuality()
{
  this->GetPipeline()->SetQuality(this->Quality);
  if (this->NumberOfPhotons > 0)
  {
    this->GetPipeline()->GetPhotonTracer()->SetNumberOfPhotons(this->NumberOfPhotons);
  }
}

//------------------------------------------------------------------------------
void vtkRefractaPluginRenderImage::SetQuality(int quality)
{
  quality = std::min(std::max(quality, static_cast<int>(vtkEffectPlan::DRAFT)),
    static_cast<int>(vtkEffectPlan::PRODUCTION));
  if (quality != this->Quality)
  {
    this->Quality = quality;
    this->ApplyQuality();
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkRefractaPluginRenderImage::SetNumberOfPhotons(int photons)
{
  photons = std::max(photons, 0);
  if (photons != this->NumberOfPhotons)
  {
    this->NumberOfPhotons = photons;
    this->ApplyQuality();
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
void vtkRefractaPluginRenderImage::SetMultipleScattering(bool on)
{
  this->GetPipeline()->SetMultipleScattering(on);
  this->Modified();
}

//------------------------------------------------------------------------------
void vtkRefractaPluginRenderImage::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Quality: " << this->Quality << "\n";
  os << indent << "NumberOfPhotons: " << this->NumberOfPhotons << "\n";
  os << indent << "Lights:\n";
  this->Lights->PrintSelf(os, indent.GetNextIndent());
}
