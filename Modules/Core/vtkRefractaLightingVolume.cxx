#include "vtkRefractaLightingVolume.h"

#include "vtkDataSet.h"
#include "vtkFloatArray.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkRefractaMedium.h"
#include "vtkSMPTools.h"

#include <cstring>
#include <vector>

vtkStandardNewMacro(vtkRefractaLightingVolume);

//------------------------------------------------------------------------------
const char* vtkRefractaLightingVolume::GetArrayName(int id)
{
  switch (id)
  {
    case RADIANCE:
      return RadianceName();
    case RADIANCE_DIRECTION:
      return RadianceDirectionName();
    case MULTIPLE_SCATTERING:
      return MultipleScatteringName();
    case MULTIPLE_SCATTERING_SOURCE:
      return MultipleScatteringSourceName();
    case MULTIPLE_SCATTERING_SOURCE_DIRECTION:
      return MultipleScatteringSourceDirectionName();
    default:
      return nullptr;
  }
}

//------------------------------------------------------------------------------
int vtkRefractaLightingVolume::GetArrayId(const char* name)
{
  for (int id = 0; name && id < NUMBER_OF_ARRAYS; ++id)
  {
    if (std::strcmp(name, GetArrayName(id)) == 0)
    {
      return id;
    }
  }
  return -1;
}

//------------------------------------------------------------------------------
int vtkRefractaLightingVolume::GetNumberOfComponents(int id)
{
  return id >= 0 && id < NUMBER_OF_ARRAYS ? 3 : 0;
}

//------------------------------------------------------------------------------
bool vtkRefractaLightingVolume::HasPhotonMultipleScattering(vtkDataSet* lighting)
{
  return lighting && lighting->GetPointData()->GetArray(MultipleScatteringSourceName());
}

const char* vtkRefractaLightingVolume::LatticeSourceName(vtkDataSet* lighting)
{
  return HasPhotonMultipleScattering(lighting) ? MultipleScatteringSourceName() : RadianceName();
}

const char* vtkRefractaLightingVolume::LatticeSourceDirectionName(vtkDataSet* lighting)
{
  return HasPhotonMultipleScattering(lighting) ? MultipleScatteringSourceDirectionName()
                                               : RadianceDirectionName();
}

//------------------------------------------------------------------------------
void vtkRefractaLightingVolume::AddPhotonMultipleScattering(vtkDataSet* lighting, vtkFloatArray* ms)
{
  vtkDataArray* photons =
    lighting ? lighting->GetPointData()->GetArray(MultipleScatteringName()) : nullptr;
  if (!photons || !ms || photons == ms || photons->GetNumberOfComponents() != 3 ||
    ms->GetNumberOfComponents() != 3 || photons->GetNumberOfTuples() != ms->GetNumberOfTuples())
  {
    return;
  }
  std::vector<float> values;
  vtkRefractaMedium::ReadArray(photons, photons->GetNumberOfTuples(), 3, 0.0f, values);
  float* out = ms->GetPointer(0);
  vtkSMPTools::For(0, static_cast<vtkIdType>(values.size()),
    [&](vtkIdType first, vtkIdType last)
    {
      for (vtkIdType i = first; i < last; ++i)
      {
        out[i] += values[i];
      }
    });
}

//------------------------------------------------------------------------------
void vtkRefractaLightingVolume::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  for (int id = 0; id < NUMBER_OF_ARRAYS; ++id)
  {
    os << indent << GetArrayName(id) << ": " << GetNumberOfComponents(id) << " components\n";
  }
}
