#include "vtkRefractaMedium.h"

#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

vtkStandardNewMacro(vtkRefractaMedium);

namespace
{
struct ArrayConvention
{
  const char* Name;
  int Components;
  double Default;
  double Min;
  double Max;
  const char* RangeDescription;
};

constexpr double Inf = std::numeric_limits<double>::infinity();

// One row per vtkRefractaMedium::ArrayId, in enum order.
const ArrayConvention Conventions[vtkRefractaMedium::NUMBER_OF_ARRAYS] = {
  { "RefractiveIndex", 1, 1.0, 1.0, vtkRefractaMedium::MaximumRefractiveIndex, "in [1, 100]" },
  { "RefractiveIndexGradient", 3, 0.0, -Inf, Inf, "finite" },
  { "Extinction", 3, 0.0, 0.0, Inf, "finite and >= 0" },
  { "Albedo", 3, 0.0, 0.0, 1.0, "in [0, 1]" },
  { "Anisotropy", 1, 0.0, -1.0, 1.0, "in (-1, 1) (Henyey-Greenstein g)" },
  { "Emission", 3, 0.0, 0.0, Inf, "finite and >= 0" },
  { "Occupancy", 1, 1.0, 0.0, 1.0, "in [0, 1]" },
};

bool IsValidId(int id)
{
  return id >= 0 && id < vtkRefractaMedium::NUMBER_OF_ARRAYS;
}
}

//------------------------------------------------------------------------------
const char* vtkRefractaMedium::GetArrayName(int id)
{
  return IsValidId(id) ? Conventions[id].Name : nullptr;
}

//------------------------------------------------------------------------------
int vtkRefractaMedium::GetArrayId(const char* name)
{
  if (!name)
  {
    return -1;
  }
  for (int id = 0; id < NUMBER_OF_ARRAYS; ++id)
  {
    if (std::strcmp(name, Conventions[id].Name) == 0)
    {
      return id;
    }
  }
  return -1;
}

//------------------------------------------------------------------------------
int vtkRefractaMedium::GetNumberOfComponents(int id)
{
  return IsValidId(id) ? Conventions[id].Components : 0;
}

//------------------------------------------------------------------------------
double vtkRefractaMedium::GetDefaultValue(int id)
{
  return IsValidId(id) ? Conventions[id].Default : 0.0;
}

//------------------------------------------------------------------------------
void vtkRefractaMedium::GetValidRange(int id, double range[2])
{
  range[0] = IsValidId(id) ? Conventions[id].Min : 0.0;
  range[1] = IsValidId(id) ? Conventions[id].Max : 0.0;
}

//------------------------------------------------------------------------------
bool vtkRefractaMedium::IsValueValid(int id, double value)
{
  if (!IsValidId(id) || !std::isfinite(value))
  {
    return false;
  }
  const ArrayConvention& c = Conventions[id];
  if (id == ANISOTROPY)
  {
    // The Henyey-Greenstein phase function is a delta (g = +-1), not a density, at the ends.
    return value > c.Min && value < c.Max;
  }
  return value >= c.Min && value <= c.Max;
}

//------------------------------------------------------------------------------
const char* vtkRefractaMedium::GetValidRangeDescription(int id)
{
  return IsValidId(id) ? Conventions[id].RangeDescription : "not a medium array";
}

//------------------------------------------------------------------------------
std::vector<float> vtkRefractaMedium::ReadArray(
  vtkImageData* image, const char* name, int components, float fallback)
{
  std::vector<float> values;
  ReadArray(image ? image->GetPointData()->GetArray(name) : nullptr,
    image ? image->GetNumberOfPoints() : 0, components, fallback, values);
  return values;
}

//------------------------------------------------------------------------------
bool vtkRefractaMedium::IsGrey(const std::vector<float>& rgb)
{
  for (size_t i = 0; i + 2 < rgb.size(); i += 3)
  {
    if (rgb[i] != rgb[i + 1] || rgb[i] != rgb[i + 2])
    {
      return false;
    }
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkRefractaMedium::ReadArray(
  vtkDataArray* array, vtkIdType tuples, int components, float fallback, std::vector<float>& out)
{
  const size_t count = static_cast<size_t>(tuples) * components;
  if (!array || array->GetNumberOfComponents() != components ||
    array->GetNumberOfTuples() != tuples)
  {
    out.assign(count, fallback);
    return;
  }
  out.resize(count);
  if (vtkFloatArray* floats = vtkFloatArray::FastDownCast(array))
  {
    std::copy_n(floats->GetPointer(0), count, out.begin());
    return;
  }
  vtkSMPTools::For(0, tuples,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType t = begin; t < end; ++t)
      {
        for (int c = 0; c < components; ++c)
        {
          out[t * components + c] = static_cast<float>(array->GetComponent(t, c));
        }
      }
    });
}

//------------------------------------------------------------------------------
std::vector<float> vtkRefractaMedium::ReadArray(vtkImageData* image, int id)
{
  return ReadArray(
    image, GetArrayName(id), GetNumberOfComponents(id), static_cast<float>(GetDefaultValue(id)));
}

//------------------------------------------------------------------------------
void vtkRefractaMedium::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  for (int id = 0; id < NUMBER_OF_ARRAYS; ++id)
  {
    os << indent << Conventions[id].Name << ": " << Conventions[id].Components << " component(s), "
       << Conventions[id].RangeDescription << ", default " << Conventions[id].Default << "\n";
  }
}
