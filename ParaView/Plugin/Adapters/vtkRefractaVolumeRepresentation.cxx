#include "vtkRefractaVolumeRepresentation.h"

#include "vtkObjectFactory.h"
#include "vtkPVLODVolume.h"
#include "vtkRefractiveVolumeMapper.h"

vtkStandardNewMacro(vtkRefractaVolumeRepresentation);

//------------------------------------------------------------------------------
vtkRefractaVolumeRepresentation::vtkRefractaVolumeRepresentation()
{
  this->VolumeMapper = vtkSmartPointer<vtkRefractiveVolumeMapper>::New();
}

//------------------------------------------------------------------------------
vtkRefractaVolumeRepresentation::~vtkRefractaVolumeRepresentation() = default;

//------------------------------------------------------------------------------
vtkRefractiveVolumeMapper* vtkRefractaVolumeRepresentation::GetRefractiveMapper()
{
  return vtkRefractiveVolumeMapper::SafeDownCast(this->VolumeMapper);
}

//------------------------------------------------------------------------------
void vtkRefractaVolumeRepresentation::SetRefractaQuality(int quality)
{
  this->GetRefractiveMapper()->SetQuality(quality);
}

//------------------------------------------------------------------------------
void vtkRefractaVolumeRepresentation::SetRefractaExposure(double exposure)
{
  this->GetRefractiveMapper()->SetExposure(exposure);
}

//------------------------------------------------------------------------------
void vtkRefractaVolumeRepresentation::SetRefractaAutomaticExposure(bool on)
{
  this->GetRefractiveMapper()->SetAutomaticExposure(on);
}

//------------------------------------------------------------------------------
void vtkRefractaVolumeRepresentation::SetRefractaMultipleScattering(bool on)
{
  this->GetRefractiveMapper()->SetMultipleScattering(on);
}

//------------------------------------------------------------------------------
void vtkRefractaVolumeRepresentation::SetRefractaNumberOfPhotons(int photons)
{
  this->GetRefractiveMapper()->SetNumberOfPhotons(photons);
}

//------------------------------------------------------------------------------
void vtkRefractaVolumeRepresentation::UpdateMapperParameters()
{
  this->Superclass::UpdateMapperParameters();
  this->Actor->SetMapper(this->VolumeMapper);
  this->Actor->SetVisibility(this->GetVisibility());
}

//------------------------------------------------------------------------------
void vtkRefractaVolumeRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Mapper:\n";
  this->VolumeMapper->PrintSelf(os, indent.GetNextIndent());
}
