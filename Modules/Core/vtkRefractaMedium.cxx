#include "vtkRefractaMedium.h"

#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>

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

//------------------------------------------------------------------------------
vtkSmartPointer<vtkFloatArray> vtkRefractaMedium::NewArrayOrNull(int id, vtkIdType tuples)
{
  const int components = GetNumberOfComponents(id);
  if (components <= 0 || tuples < 0)
  {
    return nullptr;
  }
  const size_t values = static_cast<size_t>(tuples) * components;
  std::unique_ptr<float, decltype(&std::free)> data(
    static_cast<float*>(std::malloc(std::max<size_t>(values, 1) * sizeof(float))), &std::free);
  if (!data)
  {
    return nullptr;
  }
  auto a = vtkSmartPointer<vtkFloatArray>::New();
  a->SetName(GetArrayName(id));
  a->SetNumberOfComponents(components);
  a->SetArray(
    data.release(), static_cast<vtkIdType>(values), 0, vtkAbstractArray::VTK_DATA_ARRAY_FREE);
  return a;
}

//------------------------------------------------------------------------------
vtkIdType vtkRefractaMedium::FillAlbedoWithoutExtinction(vtkImageData* medium)
{
  vtkDataArray* extinction = medium ? medium->GetPointData()->GetArray(ExtinctionName()) : nullptr;
  vtkDataArray* albedo = medium ? medium->GetPointData()->GetArray(AlbedoName()) : nullptr;
  const vtkIdType points = medium ? medium->GetNumberOfPoints() : 0;
  if (!extinction || !albedo || extinction->GetNumberOfComponents() != 3 ||
    albedo->GetNumberOfComponents() != 3 || extinction->GetNumberOfTuples() != points ||
    albedo->GetNumberOfTuples() != points)
  {
    return 0;
  }
  int dims[3];
  medium->GetDimensions(dims);
  std::vector<float> sigma, a;
  ReadArray(extinction, points, 3, 0.0f, sigma);
  ReadArray(albedo, points, 3, 1.0f, a);
  if (*std::max_element(sigma.begin(), sigma.end()) <= 0.0f)
  {
    return 0; // no extinction anywhere: albedo means nothing
  }
  // One sweep counts the voxel channels to fill (nothing is allocated when there are none); a
  // second writes them into the new array.
  auto index = [&dims](int i, int j, int k)
  { return i + static_cast<vtkIdType>(dims[0]) * (j + static_cast<vtkIdType>(dims[1]) * k); };
  auto sweep = [&](float* out)
  {
    std::atomic<vtkIdType> changed(0);
    vtkSMPTools::For(0, dims[2],
      [&](vtkIdType kBegin, vtkIdType kEnd)
      {
        vtkIdType local = 0;
        for (int k = static_cast<int>(kBegin); k < kEnd; ++k)
        {
          for (int j = 0; j < dims[1]; ++j)
          {
            for (int i = 0; i < dims[0]; ++i)
            {
              const vtkIdType v = index(i, j, k);
              for (int c = 0; c < 3; ++c)
              {
                if (sigma[3 * v + c] > 0.0f)
                {
                  continue;
                }
                double weight = 0.0, sum = 0.0;
                for (int z = std::max(k - 1, 0); z <= std::min(k + 1, dims[2] - 1); ++z)
                {
                  for (int y = std::max(j - 1, 0); y <= std::min(j + 1, dims[1] - 1); ++y)
                  {
                    for (int x = std::max(i - 1, 0); x <= std::min(i + 1, dims[0] - 1); ++x)
                    {
                      const vtkIdType n = index(x, y, z);
                      weight += sigma[3 * n + c];
                      sum += sigma[3 * n + c] * a[3 * n + c];
                    }
                  }
                }
                if (weight > 0.0 && static_cast<float>(sum / weight) != a[3 * v + c])
                {
                  ++local;
                  if (out)
                  {
                    out[3 * v + c] = static_cast<float>(sum / weight);
                  }
                }
              }
            }
          }
        }
        changed += local;
      });
    return static_cast<vtkIdType>(changed);
  };
  const vtkIdType count = sweep(nullptr);
  if (count > 0)
  {
    vtkNew<vtkFloatArray> copy;
    copy->SetName(AlbedoName());
    copy->SetNumberOfComponents(3);
    copy->SetNumberOfTuples(points);
    std::copy(a.begin(), a.end(), copy->GetPointer(0));
    sweep(copy->GetPointer(0));
    medium->GetPointData()->AddArray(copy); // replaces the array of the same name
  }
  return count;
}
