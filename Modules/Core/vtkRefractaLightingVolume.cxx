#include "vtkRefractaLightingVolume.h"

#include "vtkDataSet.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkRefractaMedium.h"
#include "vtkSMPTools.h"

#include <cmath>
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
    case MULTIPLE_SCATTERING_DIRECTION:
      return MultipleScatteringDirectionName();
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
const char* vtkRefractaLightingVolume::RadianceLobeName(int k)
{
  static const char* const names[MAXIMUM_RADIANCE_LOBES] = { "RadianceLobe0", "RadianceLobe1",
    "RadianceLobe2", "RadianceLobe3" };
  return k >= 0 && k < MAXIMUM_RADIANCE_LOBES ? names[k] : nullptr;
}

const char* vtkRefractaLightingVolume::RadianceLobeDirectionName(int k)
{
  static const char* const names[MAXIMUM_RADIANCE_LOBES] = { "RadianceLobeDirection0",
    "RadianceLobeDirection1", "RadianceLobeDirection2", "RadianceLobeDirection3" };
  return k >= 0 && k < MAXIMUM_RADIANCE_LOBES ? names[k] : nullptr;
}

int vtkRefractaLightingVolume::GetNumberOfRadianceLobes(vtkDataSet* lighting)
{
  vtkPointData* pd = lighting ? lighting->GetPointData() : nullptr;
  int k = 0;
  while (pd && k < MAXIMUM_RADIANCE_LOBES && pd->GetArray(RadianceLobeName(k)) &&
    pd->GetArray(RadianceLobeDirectionName(k)))
  {
    ++k;
  }
  return k >= 2 ? k : 0;
}

void vtkRefractaLightingVolume::PassSingleScattering(vtkDataSet* from, vtkDataSet* to)
{
  vtkPointData* in = from->GetPointData();
  vtkPointData* out = to->GetPointData();
  for (const char* name : { RadianceName(), RadianceDirectionName() })
  {
    if (vtkDataArray* a = in->GetArray(name))
    {
      out->AddArray(a);
    }
  }
  for (int k = 0; k < GetNumberOfRadianceLobes(from); ++k)
  {
    out->AddArray(in->GetArray(RadianceLobeName(k)));
    out->AddArray(in->GetArray(RadianceLobeDirectionName(k)));
  }
}

//------------------------------------------------------------------------------
int vtkRefractaLightingVolume::GetVolumeCausticSubdivision(vtkDataSet* lighting, vtkIdType* bricks)
{
  vtkFieldData* fd = lighting ? lighting->GetFieldData() : nullptr;
  vtkDataArray* map = fd ? fd->GetArray(VolumeCausticBricksName()) : nullptr;
  vtkDataArray* fine = fd ? fd->GetArray(VolumeCausticRadianceName()) : nullptr;
  vtkDataArray* direction = fd ? fd->GetArray(VolumeCausticRadianceDirectionName()) : nullptr;
  if (bricks)
  {
    *bricks = 0;
  }
  if (!map || !fine || !direction || map->GetNumberOfComponents() != 1 ||
    map->GetNumberOfTuples() != lighting->GetNumberOfPoints() || fine->GetNumberOfComponents() != 3 ||
    direction->GetNumberOfComponents() != 3 ||
    direction->GetNumberOfTuples() != fine->GetNumberOfTuples())
  {
    return 1;
  }
  const double largest = map->GetNumberOfTuples() > 0 ? map->GetRange(0)[1] : -1.0;
  const vtkIdType count = largest >= 0 && largest < VTK_INT_MAX ? vtkIdType(largest) + 1 : 0;
  const int c = count > 0
    ? static_cast<int>(std::lround(std::cbrt(double(fine->GetNumberOfTuples()) / double(count))))
    : 0;
  if (c < 2 || vtkIdType(c) * c * c * count != fine->GetNumberOfTuples())
  {
    return 1;
  }
  if (bricks)
  {
    *bricks = count;
  }
  return c;
}

//------------------------------------------------------------------------------
void vtkRefractaLightingVolume::ReadLatticeSource(
  vtkImageData* lighting, std::vector<float>& source, std::vector<float>& direction)
{
  source = vtkRefractaMedium::ReadArray(lighting, LatticeSourceName(lighting), 3, 0.0f);
  direction = vtkRefractaMedium::ReadArray(lighting, LatticeSourceDirectionName(lighting), 3, 0.0f);
  vtkIdType count = 0;
  const int c = GetVolumeCausticSubdivision(lighting, &count);
  const vtkIdType voxels = static_cast<vtkIdType>(source.size() / 3);
  if (!LatticeSourceHasVolumeCaustic(lighting) || voxels != lighting->GetNumberOfPoints())
  {
    return;
  }
  vtkFieldData* fd = lighting->GetFieldData();
  vtkDataArray* bricks = fd->GetArray(VolumeCausticBricksName());
  vtkDataArray* fine = fd->GetArray(VolumeCausticRadianceName());
  vtkDataArray* fineDirection = fd->GetArray(VolumeCausticRadianceDirectionName());
  const vtkIdType c3 = vtkIdType(c) * c * c;
  for (vtkIdType v = 0; c3 > 0 && v < voxels; ++v)
  {
    const vtkIdType b = static_cast<vtkIdType>(bricks->GetComponent(v, 0));
    if (b < 0 || b >= count)
    {
      continue;
    }
    float* s = source.data() + 3 * v;
    float* d = direction.data() + 3 * v;
    double weighted[3];
    const double own = double(s[0]) + s[1] + s[2];
    for (int k = 0; k < 3; ++k)
    {
      weighted[k] = own * d[k];
    }
    for (vtkIdType f = b * c3; f < (b + 1) * c3; ++f)
    {
      double power = 0;
      for (int k = 0; k < 3; ++k)
      {
        const double value = fine->GetComponent(f, k) / double(c3);
        s[k] += static_cast<float>(value);
        power += value;
      }
      for (int k = 0; k < 3; ++k)
      {
        weighted[k] += power * fineDirection->GetComponent(f, k);
      }
    }
    const double length =
      std::sqrt(weighted[0] * weighted[0] + weighted[1] * weighted[1] + weighted[2] * weighted[2]);
    for (int k = 0; k < 3; ++k)
    {
      d[k] = length > 0 ? static_cast<float>(weighted[k] / length) : 0.0f;
    }
  }
}

//------------------------------------------------------------------------------
void vtkRefractaLightingVolume::AddPhotonMultipleScattering(vtkDataSet* lighting, vtkFloatArray* ms)
{
  vtkDataArray* photons =
    lighting ? lighting->GetPointData()->GetArray(MultipleScatteringName()) : nullptr;
  if (photons != ms)
  {
    AddValues(photons, ms);
  }
}

//------------------------------------------------------------------------------
bool vtkRefractaLightingVolume::LatticeSourceHasVolumeCaustic(vtkDataSet* lighting)
{
  return !HasPhotonMultipleScattering(lighting) && GetVolumeCausticSubdivision(lighting) >= 2;
}

//------------------------------------------------------------------------------
void vtkRefractaLightingVolume::AddValues(vtkDataArray* addend, vtkFloatArray* to)
{
  if (!addend || !to || addend->GetNumberOfComponents() != to->GetNumberOfComponents() ||
    addend->GetNumberOfTuples() != to->GetNumberOfTuples())
  {
    return;
  }
  std::vector<float> values;
  vtkRefractaMedium::ReadArray(
    addend, addend->GetNumberOfTuples(), addend->GetNumberOfComponents(), 0.0f, values);
  float* out = to->GetPointer(0);
  vtkSMPTools::For(0, static_cast<vtkIdType>(values.size()),
    [&](vtkIdType first, vtkIdType last)
    {
      for (vtkIdType i = first; i < last; ++i)
      {
        out[i] += values[i];
      }
    });
  to->Modified();
}

//------------------------------------------------------------------------------
double vtkRefractaLightingVolume::GetSurfaceSideValue(
  vtkDataArray* array, vtkIdType tuple, int side, int component, int perSide)
{
  if (!array || tuple < 0 || tuple >= array->GetNumberOfTuples() || side < 0 ||
    side >= NUMBER_OF_SURFACE_SIDES || component < 0 || component >= perSide)
  {
    return 0.0;
  }
  const int components = array->GetNumberOfComponents();
  if (components == NUMBER_OF_SURFACE_SIDES * perSide)
  {
    return array->GetComponent(tuple, side * perSide + component);
  }
  return components == perSide ? array->GetComponent(tuple, component) : 0.0;
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
