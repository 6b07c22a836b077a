#include "vtkRefractaLightingVolume.h"

#include "vtkObjectFactory.h"

#include <cstring>

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
void vtkRefractaLightingVolume::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  for (int id = 0; id < NUMBER_OF_ARRAYS; ++id)
  {
    os << indent << GetArrayName(id) << ": " << GetNumberOfComponents(id) << " components\n";
  }
}
