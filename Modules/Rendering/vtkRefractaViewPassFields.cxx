#include "vtkRefractaViewPassFields.h"

#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMath.h"
#include "vtkOpenCLContext.h"
#include "vtkPointData.h"
#include "vtkRefractaEnvironmentMap.h"
#include "vtkRefractaGridFrame.h"
#include "vtkRefractaMedium.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace vtkRefractaViewPassDetail
{
//------------------------------------------------------------------------------
void FetchFloats(vtkDataArray* array, int comps, std::vector<float>& out)
{
  vtkRefractaMedium::ReadArray(array, array->GetNumberOfTuples(), comps, 0.0f, out);
}

//------------------------------------------------------------------------------
std::vector<float> PackGreyMedium(
  const std::vector<float>& extinction, const std::vector<float>& emission)
{
  const size_t n = extinction.size() / 3;
  std::vector<float> packed(4 * n);
  for (size_t i = 0; i < n; ++i)
  {
    packed[4 * i] = extinction[3 * i];
    std::copy_n(emission.begin() + 3 * i, 3, packed.begin() + 4 * i + 1);
  }
  return packed;
}

//------------------------------------------------------------------------------
void RotateToLocal(const vtkRefractaGridFrame* grid, std::vector<float>& vectors)
{
  for (size_t i = 0; i + 2 < vectors.size(); i += 3)
  {
    const double world[3] = { vectors[i], vectors[i + 1], vectors[i + 2] };
    double local[3];
    grid->WorldToLocalVector(world, local);
    for (int c = 0; c < 3; ++c)
    {
      vectors[i + c] = static_cast<float>(local[c]);
    }
  }
}

//------------------------------------------------------------------------------
std::vector<float> CentralDifferenceGradient(
  const std::vector<float>& index, const int dims[3], const double spacing[3])
{
  const size_t n = static_cast<size_t>(dims[0]) * dims[1] * dims[2];
  std::vector<float> gradient(n * 3, 0.0f);
  auto at = [&](const int* p)
  {
    return index[p[0] +
      static_cast<size_t>(dims[0]) * (p[1] + static_cast<size_t>(dims[1]) * p[2])];
  };
  for (int k = 0; k < dims[2]; ++k)
  {
    for (int j = 0; j < dims[1]; ++j)
    {
      for (int i = 0; i < dims[0]; ++i)
      {
        const int ijk[3] = { i, j, k };
        const size_t idx =
          i + static_cast<size_t>(dims[0]) * (j + static_cast<size_t>(dims[1]) * k);
        for (int a = 0; a < 3; ++a)
        {
          if (dims[a] < 2)
          {
            continue;
          }
          int lo[3] = { i, j, k }, hi[3] = { i, j, k };
          lo[a] = std::max(ijk[a] - 1, 0);
          hi[a] = std::min(ijk[a] + 1, dims[a] - 1);
          gradient[idx * 3 + a] =
            static_cast<float>((at(hi) - at(lo)) / ((hi[a] - lo[a]) * spacing[a]));
        }
      }
    }
  }
  return gradient;
}

//------------------------------------------------------------------------------
bool EnvironmentToRGB(
  vtkImageData* image, std::vector<float>& rgb, int size[2], bool& checker, std::string& error)
{
  double color1[3], color2[3];
  checker = vtkRefractaEnvironmentMap::GetChecker(image, size, color1, color2);
  if (checker)
  {
    rgb.assign(color1, color1 + 3);
    rgb.insert(rgb.end(), color2, color2 + 3);
    return true;
  }
  std::vector<double> radiance;
  if (!vtkRefractaEnvironmentMap::ReadRadiance(image, radiance, size, error))
  {
    return false;
  }
  rgb.assign(radiance.begin(), radiance.end());
  return true;
}

//------------------------------------------------------------------------------
bool CheckLightingArray(
  vtkDataArray* array, const char* name, vtkIdType tuples, bool nonNegative, std::string& error)
{
  if (array->GetNumberOfComponents() != 3 || array->GetNumberOfTuples() != tuples)
  {
    std::ostringstream msg;
    msg << "The lighting volume's point array '" << name << "' has "
        << array->GetNumberOfComponents() << " components and " << array->GetNumberOfTuples()
        << " tuples; it needs 3 components and " << tuples << " tuples.";
    error = msg.str();
    return false;
  }
  auto invalid = [nonNegative](double v) { return !std::isfinite(v) || (nonNegative && v < 0); };
  const vtkIdType values = 3 * tuples;
  vtkIdType first = -1;
  if (vtkFloatArray* floats = vtkFloatArray::FastDownCast(array))
  {
    // The passes' own output: read the memory directly (a virtual call per value costs more
    // than the rest of a camera move at 128^3).
    const float* p = floats->GetPointer(0);
    first = std::find_if(p, p + values, invalid) - p;
  }
  else
  {
    first = 0;
    while (first < values && !invalid(array->GetComponent(first / 3, first % 3)))
    {
      ++first;
    }
  }
  if (first >= values)
  {
    return true;
  }
  std::ostringstream msg;
  msg << "The lighting volume's point array '" << name << "' has the invalid value "
      << array->GetComponent(first / 3, first % 3) << " at tuple " << first / 3 << " component "
      << first % 3 << "; values must be finite" << (nonNegative ? " and >= 0." : ".");
  error = msg.str();
  return false;
}

//------------------------------------------------------------------------------
std::string KernelOptions(const KernelVariant& v)
{
  std::string options;
  auto flag = [&](bool on, const char* name)
  {
    if (on)
    {
      options += std::string(" -D") + name;
    }
  };
  flag(v.Curved, "REFRACTA_CURVED");
  flag(v.Parallel, "REFRACTA_PARALLEL");
  // Sources count 1 / n^2 (basic radiance): per step where n varies, as a constant where it is
  // uniform and not 1.
  flag(v.IndexVaries, "REFRACTA_INDEX_WEIGHT");
  if (!v.IndexVaries && v.UniformIndex != 1.0)
  {
    options += " -DREFRACTA_SOURCE_SCALE=" +
      vtkOpenCLContext::FloatLiteral(1.0 / (v.UniformIndex * v.UniformIndex));
  }
  flag(v.Single, "REFRACTA_HAS_SINGLE");
  if (v.Single && v.RadianceLobes >= 2)
  {
    options += " -DREFRACTA_RADIANCE_LOBES=" + std::to_string(v.RadianceLobes);
  }
  flag(v.Multiple, "REFRACTA_HAS_MULTIPLE");
  flag(v.Multiple && v.MultipleDirection, "REFRACTA_MULTIPLE_DIRECTION");
  flag(v.Emission, "REFRACTA_HAS_EMISSION");
  flag(v.Packed, "REFRACTA_PACKED_MEDIUM");
  flag(v.Environment, "REFRACTA_HAS_ENVIRONMENT");
  flag(v.Environment && v.Checker, "REFRACTA_CHECKER_ENVIRONMENT");
  flag(v.DepthLimit, "REFRACTA_HAS_DEPTH_LIMIT");
  flag(v.Skip, "REFRACTA_SKIP");
  flag(v.LaneMarching, "REFRACTA_VIEW_LANES");
  flag(v.Surfaces, "REFRACTA_HAS_SURFACES");
  flag(v.Surfaces && v.NearestTexel, "REFRACTA_SURFACE_NEAREST");
  flag(v.Surfaces && v.Dielectric, "REFRACTA_DIELECTRIC");
  flag(v.Surfaces && v.Sided, "REFRACTA_SIDED_LOOKUPS");
  if (v.Surfaces && v.Dielectric)
  {
    options += " -DREFRACTA_SPLIT_DEPTH=" + std::to_string(v.SplitDepth);
  }
  if (v.Surfaces && v.Caustic > 1)
  {
    options += " -DREFRACTA_CAUSTIC_SUBDIVISION=" + std::to_string(v.Caustic) +
      " -DREFRACTA_CAUSTIC_OFFSET=" + std::to_string(v.CausticOffset);
  }
  return options;
}

//------------------------------------------------------------------------------
bool LaneMarchingApplies(const KernelVariant& v, bool gpu, vtkIdType voxels)
{
  return !gpu && !v.Surfaces && voxels <= std::numeric_limits<int>::max();
}

//------------------------------------------------------------------------------
void EnvironmentBasisLocal(
  const double up[3], const double right[3], const double worldToLocal[4][4], double out[3][3])
{
  double basis[3][3];
  vtkRefractaEnvironmentMap::ComputeBasis(up, right, basis[0], basis[1], basis[2]);
  // A world direction x maps to local L x (L the linear part of WorldToLocal); dot(x, e) =
  // dot(L x, L^-T e); for the rigid transforms used here L^-T = L, so rotate e by L and
  // re-normalise.
  for (int b = 0; b < 3; ++b)
  {
    for (int row = 0; row < 3; ++row)
    {
      out[b][row] = worldToLocal[row][0] * basis[b][0] + worldToLocal[row][1] * basis[b][1] +
        worldToLocal[row][2] * basis[b][2];
    }
    vtkMath::Normalize(out[b]);
  }
}

}
