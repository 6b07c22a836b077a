#include "vtkRefractaVolumeRepresentation.h"

#include "vtkCellData.h"
#include "vtkDataSet.h"
#include "vtkObjectFactory.h"
#include "vtkPVLODVolume.h"
#include "vtkPhotonTracer.h"
#include "vtkPointData.h"
#include "vtkRefractaMedium.h"
#include "vtkRefractaRenderPipeline.h"
#include "vtkRefractaViewPass.h"
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
void vtkRefractaVolumeRepresentation::SetRefractaVolumeCausticSubdivision(int subdivision)
{
  this->GetRefractiveMapper()->GetPipeline()->GetPhotonTracer()->SetVolumeCausticSubdivision(
    subdivision);
}

//------------------------------------------------------------------------------
void vtkRefractaVolumeRepresentation::SetRefractaGlassSupersampling(int samples)
{
  this->GetRefractiveMapper()->GetViewPass()->SetDielectricSupersampling(samples);
}

//------------------------------------------------------------------------------
void vtkRefractaVolumeRepresentation::UpdateMapperParameters()
{
  this->Superclass::UpdateMapperParameters();
  // ParaView's volume (vtkPVLODVolume::CanRender) draws only when the mapper's selected scalars
  // exist. A medium needs no colour array (the mapper reads its arrays by their names), so when
  // none is chosen, one of the medium's own arrays is selected: the mapper then sees a medium
  // and ignores the selection.
  vtkDataSet* input = this->VolumeMapper->GetInput();
  const char* selected = this->VolumeMapper->GetArrayName();
  const bool hasSelection = selected && selected[0] && input &&
    (input->GetPointData()->GetAbstractArray(selected) ||
      input->GetCellData()->GetAbstractArray(selected)); // cell data: at the cells' centres
  if (input && !hasSelection)
  {
    for (int id = 0; id < vtkRefractaMedium::NUMBER_OF_ARRAYS; ++id)
    {
      const char* name = vtkRefractaMedium::GetArrayName(id);
      if (input->GetPointData()->GetArray(name))
      {
        this->VolumeMapper->SelectScalarArray(name);
        this->VolumeMapper->SetScalarMode(VTK_SCALAR_MODE_USE_POINT_FIELD_DATA);
        break;
      }
    }
  }
  this->Actor->SetMapper(this->VolumeMapper);
  this->Actor->SetVisibility(this->GetVisibility());
}

//------------------------------------------------------------------------------
void vtkRefractaVolumeRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  vtkRefractiveVolumeMapper* mapper = this->GetRefractiveMapper();
  os << indent << "RefractaVolumeCausticSubdivision: "
     << mapper->GetPipeline()->GetPhotonTracer()->GetVolumeCausticSubdivision() << "\n";
  os << indent << "RefractaGlassSupersampling: "
     << mapper->GetViewPass()->GetDielectricSupersampling() << "\n";
  os << indent << "Mapper:\n";
  this->VolumeMapper->PrintSelf(os, indent.GetNextIndent());
}
