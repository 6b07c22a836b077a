// vtkRefractaViewPass: validation and upload of the inputs (medium, lighting volume).
#include "vtkRefractaViewPass.h"

#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkMediumValidator.h"
#include "vtkOpenCLContext.h"
#include "vtkOpenCLDeviceArrays.h"
#include "vtkPointData.h"
#include "vtkRefractaGridFrame.h"
#include "vtkRefractaLightingVolume.h"
#include "vtkRefractaMedium.h"
#include "vtkRefractaViewPassFields.h"
#include "vtkRefractaViewPassInternals.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

using namespace vtkRefractaViewPassDetail;

namespace
{
bool Finite3(const double v[3])
{
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

// Why the camera cannot make view rays (empty: it can): every ray would be NaN, or the image
// black, without a word.
std::string CameraProblem(vtkCamera* camera)
{
  double position[3], focal[3], up[3];
  camera->GetPosition(position);
  camera->GetFocalPoint(focal);
  camera->GetViewUp(up);
  if (!Finite3(position) || !Finite3(focal) || !Finite3(up) ||
    !Finite3(camera->GetDirectionOfProjection()))
  {
    return "its position, focal point and view up must be finite";
  }
  // (vtkCamera keeps the focal point off the position, and the direction unit.)
  const double* forward = camera->GetDirectionOfProjection();
  double side[3];
  vtkMath::Cross(forward, up, side);
  if (!(vtkMath::Norm(side) > 1e-12 * vtkMath::Norm(up)))
  {
    return "its view up is zero or parallel to the direction of view";
  }
  if (camera->GetParallelProjection())
  {
    const double scale = camera->GetParallelScale();
    if (!(std::isfinite(scale) && scale > 0.0))
    {
      return "its parallel scale must be finite and positive";
    }
  }
  else
  {
    const double angle = camera->GetViewAngle();
    if (!(angle > 0.0 && angle < 180.0))
    {
      return "its view angle must be in (0, 180) degrees";
    }
  }
  return {};
}

// Why the prop matrix cannot place the medium (empty: it can): its inverse takes world points
// into the medium's grid, so it must be finite and invertible.
std::string PropMatrixProblem(vtkMatrix4x4* matrix)
{
  for (int i = 0; i < 4; ++i)
  {
    for (int j = 0; j < 4; ++j)
    {
      if (!std::isfinite(matrix->GetElement(i, j)))
      {
        return "it has an element that is not finite";
      }
    }
  }
  double columns[3][3], largest = 0;
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      columns[j][i] = matrix->GetElement(i, j);
      largest = std::max(largest, std::fabs(columns[j][i]));
    }
  }
  const double det = vtkMath::Determinant3x3(columns[0], columns[1], columns[2]);
  if (!(std::fabs(det) > 1e-12 * largest * largest * largest))
  {
    return "its 3 x 3 part is singular (a zero scale, or axes in one plane), so world points "
           "have no place in the medium";
  }
  const double* last = matrix->GetData() + 12;
  if (last[0] != 0.0 || last[1] != 0.0 || last[2] != 0.0 || last[3] != 1.0)
  {
    return "its last row must be (0, 0, 0, 1): a vtkProp3D's matrix is affine";
  }
  return {};
}
}

//------------------------------------------------------------------------------
std::string vtkRefractaViewPass::GetPropMatrixProblem(vtkMatrix4x4* propMatrix)
{
  const std::string why = propMatrix ? PropMatrixProblem(propMatrix) : std::string();
  return why.empty() ? why
                     : "The prop matrix (the volume's placement in the world) cannot place the "
                       "medium: " +
      why + ".";
}

//------------------------------------------------------------------------------
std::string vtkRefractaViewPass::GetRayFrameProblem(vtkCamera* camera, vtkMatrix4x4* propMatrix)
{
  if (!camera)
  {
    return "No camera: call SetCamera() with a vtkCamera.";
  }
  const std::string why = CameraProblem(camera);
  return why.empty() ? GetPropMatrixProblem(propMatrix) : "The camera cannot render: " + why + ".";
}

//------------------------------------------------------------------------------
bool vtkRefractaViewPass::SetMedium(vtkImageData* medium)
{
  Internals& in = *this->Internal;
  vtkNew<vtkMediumValidator> validator;
  if (!validator->Validate(medium))
  {
    vtkErrorMacro(
      "The medium (input port 0) is not a valid Refracta medium: " << validator->GetErrorMessage());
    in.Medium = nullptr;
    return false;
  }
  if (in.Medium == medium && in.MediumTime == medium->GetMTime() && in.Extinction)
  {
    return true;
  }
  vtkOpenCLContext* context = in.GetContext();
  if (!context->Initialize())
  {
    vtkErrorMacro("No OpenCL device: " << context->GetLastErrorMessage());
    return false;
  }
  in.Medium = nullptr;
  medium->GetDimensions(in.Dims);
  medium->GetSpacing(in.Spacing);
  in.Grid->SetImage(medium);
  const size_t n = static_cast<size_t>(in.Dims[0]) * in.Dims[1] * in.Dims[2];
  vtkPointData* pd = medium->GetPointData();

  auto fetch = [&](int id, std::vector<float>& values)
  {
    const int comps = vtkRefractaMedium::GetNumberOfComponents(id);
    if (vtkDataArray* array = pd->GetArray(vtkRefractaMedium::GetArrayName(id)))
    {
      FetchFloats(array, comps, values);
    }
    else
    {
      values.assign(n * comps, static_cast<float>(vtkRefractaMedium::GetDefaultValue(id)));
    }
  };
  auto create = [&](const std::vector<float>& values, const char* what, vtkOpenCLBuffer& buffer)
  {
    buffer = context->CreateBuffer(
      CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, values.size() * 4, values.data(), what, this);
    return static_cast<bool>(buffer);
  };
  auto upload = [&](int id, const char* what, vtkOpenCLBuffer& buffer,
                  std::vector<float>* keep = nullptr) -> bool
  {
    std::vector<float> values;
    fetch(id, values);
    const bool created = create(values, what, buffer);
    if (keep)
    {
      *keep = std::move(values);
    }
    return created;
  };

  // Extinction and emission: one float4 per voxel (sigma, emission RGB) where there is emission
  // and the extinction is grey (the kernel's REFRACTA_PACKED_MEDIUM: one gather per step instead
  // of two), else one buffer each (without emission, packing would only add a float per voxel).
  std::vector<float> extinction, emission;
  std::vector<uint8_t> flags(n, 0);
  fetch(vtkRefractaMedium::EXTINCTION, extinction);
  MarkNonzero(extinction, 3, SourceFlag, flags);
  in.HasEmission = pd->GetArray(vtkRefractaMedium::EmissionName()) != nullptr;
  if (in.HasEmission)
  {
    fetch(vtkRefractaMedium::EMISSION, emission);
    MarkNonzero(emission, 3, SourceFlag, flags);
  }
  in.PackedMedium = in.HasEmission && vtkRefractaMedium::IsGrey(extinction);
  in.Emission.Reset();
  if (in.PackedMedium)
  {
    if (!create(
          PackGreyMedium(extinction, emission), "Extinction and Emission (packed)", in.Extinction))
    {
      return false;
    }
  }
  else if (!create(extinction, "Extinction", in.Extinction) ||
    (in.HasEmission && !create(emission, "Emission", in.Emission)))
  {
    return false;
  }
  if (!upload(vtkRefractaMedium::ANISOTROPY, "Anisotropy", in.Anisotropy))
  {
    return false;
  }

  // Refractive index: curved rays need n and grad n (grad n in the grid-local frame).
  in.Refractive = false;
  in.Bends = false;
  in.UniformIndex = 1.0;
  in.Index.Reset();
  in.Gradient.Reset();
  if (vtkDataArray* index = pd->GetArray(vtkRefractaMedium::RefractiveIndexName()))
  {
    double range[2];
    index->GetRange(range, 0);
    in.Refractive = range[1] - range[0] > 1e-6;
    in.UniformIndex = in.Refractive ? 1.0 : range[0];
  }
  if (in.Refractive)
  {
    std::vector<float> nValues;
    if (!upload(vtkRefractaMedium::REFRACTIVE_INDEX, "RefractiveIndex", in.Index, &nValues))
    {
      return false;
    }
    std::vector<float> gradient;
    if (vtkDataArray* g = pd->GetArray(vtkRefractaMedium::RefractiveIndexGradientName()))
    {
      FetchFloats(g, 3, gradient);
      RotateToLocal(in.Grid, gradient);
    }
    else
    {
      gradient = CentralDifferenceGradient(nValues, in.Dims, in.Spacing);
    }
    // Curved rays are straight exactly where the grad n samples are zero (the integrator never
    // reads n itself except to scale |v|), so that is what the skipping test needs.
    MarkNonzero(gradient, 3, GradientFlag, flags);
    in.Bends = std::any_of(gradient.begin(), gradient.end(), [](float g) { return g != 0.0f; });
    in.Gradient = context->CreateBuffer(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
      gradient.size() * 4, gradient.data(), "RefractiveIndexGradient", this);
    if (!in.Gradient)
    {
      return false;
    }
  }
  // A new medium invalidates the lighting volume's upload (it must match the grid).
  in.Lighting = nullptr;
  in.HasSingle = in.HasMultiple = in.HasMultipleDirection = false;
  in.RadianceLobes = 0;
  in.Radiance.Reset();
  in.RadianceDirection.Reset();
  in.Multiple.Reset();
  in.MediumFlags = std::move(flags);
  in.LightingFlags.clear();
  in.OccupancyDirty = true;
  in.Medium = medium;
  in.MediumTime = medium->GetMTime();
  ++this->NumberOfUploads;
  return true;
}

//------------------------------------------------------------------------------
bool vtkRefractaViewPass::SetLighting(vtkImageData* lighting)
{
  Internals& in = *this->Internal;
  if (!in.Surfaces.SetLighting(lighting, this))
  {
    return false;
  }
  if (!lighting)
  {
    if (in.Lighting || !in.LightingFlags.empty())
    {
      in.OccupancyDirty = true;
    }
    in.Lighting = nullptr;
    in.HasSingle = in.HasMultiple = in.HasMultipleDirection = false;
    in.RadianceLobes = 0;
    in.Radiance.Reset();
    in.RadianceDirection.Reset();
    in.Multiple.Reset();
    in.VolumeCausticSub = 1;
    in.CausticBricks.Reset();
    in.CausticRadiance.Reset();
    in.CausticDirection.Reset();
    in.LightingFlags.clear();
    return true;
  }
  if (!in.Medium)
  {
    vtkErrorMacro("SetLighting() needs a valid medium first.");
    return false;
  }
  if (in.Lighting == lighting && in.LightingTime == lighting->GetMTime())
  {
    return true;
  }
  int dims[3];
  lighting->GetDimensions(dims);
  if (!vtkRefractaGridFrame::SameGrid(lighting, in.Medium))
  {
    vtkErrorMacro("The lighting volume (input port 1) has "
      << vtkRefractaGridFrame::DescribeGrid(lighting) << " but the medium has "
      << vtkRefractaGridFrame::DescribeGrid(in.Medium)
      << "; it must be computed on the medium's grid.");
    return false;
  }
  vtkPointData* pd = lighting->GetPointData();
  vtkDataArray* radiance = pd->GetArray(vtkRefractaLightingVolume::RadianceName());
  vtkDataArray* direction = pd->GetArray(vtkRefractaLightingVolume::RadianceDirectionName());
  vtkDataArray* multiple = pd->GetArray(vtkRefractaLightingVolume::MultipleScatteringName());
  vtkDataArray* multipleDirection =
    multiple ? pd->GetArray(vtkRefractaLightingVolume::MultipleScatteringDirectionName()) : nullptr;
  const vtkIdType n = static_cast<vtkIdType>(dims[0]) * dims[1] * dims[2];
  auto check = [&](vtkDataArray* a, const char* name, bool nonNegative) -> bool
  {
    std::string error;
    if (!CheckLightingArray(a, name, n, nonNegative, error))
    {
      vtkErrorMacro(<< error);
      return false;
    }
    return true;
  };
  if (!radiance && !multiple)
  {
    vtkErrorMacro("The lighting volume (input port 1) has neither a 'Radiance' nor a "
                  "'MultipleScattering' point array; a lighting volume from vtkPhotonTracer or "
                  "vtkLatticeBoltzmannLighting carries at least one of them.");
    return false;
  }
  if (radiance && !direction)
  {
    vtkErrorMacro("The lighting volume has 'Radiance' but no 'RadianceDirection' point array "
                  "(the mean travel direction of the light, 3 components).");
    return false;
  }
  // S1 in lobes: each lobe's S1 and direction (the view pass then reads those, not the sum), in
  // complete pairs 0 .. K - 1, K >= 2; any other lobe array would be dropped from the image.
  const int lobeCount = vtkRefractaLightingVolume::GetNumberOfRadianceLobes(lighting);
  for (int k = lobeCount; k < vtkRefractaLightingVolume::MAXIMUM_RADIANCE_LOBES; ++k)
  {
    for (const char* name : { vtkRefractaLightingVolume::RadianceLobeName(k),
           vtkRefractaLightingVolume::RadianceLobeDirectionName(k) })
    {
      if (pd->GetArray(name))
      {
        vtkErrorMacro("The lighting volume has '"
          << name << "' but " << (lobeCount > 0 ? "only " : "not ") << lobeCount
          << " complete lobes: S1's lobes come as pairs 'RadianceLobe<k>' and "
             "'RadianceLobeDirection<k>' for k = 0 .. K - 1, K >= 2 (at most "
          << static_cast<int>(vtkRefractaLightingVolume::MAXIMUM_RADIANCE_LOBES)
          << "), or not at all.");
        return false;
      }
    }
  }
  std::vector<vtkDataArray*> lobes, lobeDirections;
  for (int k = 0; radiance && k < lobeCount; ++k)
  {
    const char* name = vtkRefractaLightingVolume::RadianceLobeName(k);
    const char* directionName = vtkRefractaLightingVolume::RadianceLobeDirectionName(k);
    lobes.push_back(pd->GetArray(name));
    lobeDirections.push_back(pd->GetArray(directionName));
    if (!check(lobes.back(), name, true) || !check(lobeDirections.back(), directionName, false))
    {
      return false;
    }
  }
  if ((radiance &&
        (!check(radiance, vtkRefractaLightingVolume::RadianceName(), true) ||
          !check(direction, vtkRefractaLightingVolume::RadianceDirectionName(), false))) ||
    (multiple && !check(multiple, vtkRefractaLightingVolume::MultipleScatteringName(), true)) ||
    (multipleDirection &&
      !check(
        multipleDirection, vtkRefractaLightingVolume::MultipleScatteringDirectionName(), false)))
  {
    return false;
  }
  vtkOpenCLContext* context = in.GetContext();
  in.HasSingle = radiance != nullptr;
  in.HasMultiple = multiple != nullptr;
  in.HasMultipleDirection = multipleDirection != nullptr;
  in.RadianceLobes = static_cast<int>(lobes.size());
  in.Radiance.Reset();
  in.RadianceDirection.Reset();
  in.Multiple.Reset();
  in.LightingFlags.assign(static_cast<size_t>(n), 0);
  in.OccupancyDirty = true;
  this->LastLightingArraysShared = 0;
  // Fields on the device in one buffer, one after the other (3 floats per voxel each): a single
  // field's copy that a light pass kept there, else an upload; several fields gathered into one
  // buffer, each copied on the device from its copy there or uploaded. The first `marked` fields'
  // nonzero voxels are sources for the skipping. Two: MultipleScattering and its direction,
  // which the kernel reads in one buffer with REFRACTA_MULTIPLE_DIRECTION.
  std::vector<float> values, next;
  const size_t fieldBytes = 3 * static_cast<size_t>(n) * sizeof(float);
  auto fields = [&](
                  const std::vector<vtkDataArray*>& arrays, size_t marked, vtkOpenCLBuffer& buffer)
  {
    std::vector<vtkOpenCLBuffer> copies; // only float arrays have device copies
    for (vtkDataArray* a : arrays)
    {
      copies.push_back(context->GetDeviceArrays()->Share(a));
    }
    const bool taken = copies.size() == 1 && copies[0]; // the one field's copy is the buffer
    buffer = taken ? std::move(copies[0])
                   : context->CreateBuffer(CL_MEM_READ_ONLY, fieldBytes * arrays.size(), nullptr,
                       arrays[0]->GetName(), this);
    if (!buffer)
    {
      return false;
    }
    for (size_t f = 0; f < arrays.size(); ++f)
    {
      const bool onDevice = taken || copies[f];
      const float* host = nullptr;
      if (onDevice)
      {
        ++this->LastLightingArraysShared;
        host = vtkFloatArray::FastDownCast(arrays[f])->GetPointer(0);
      }
      else
      {
        FetchFloats(arrays[f], 3, next);
        host = next.data();
      }
      const bool placed = taken ||
        (onDevice
            ? context->CopyBuffer(copies[f].Get(), buffer.Get(), fieldBytes, this, f * fieldBytes)
            : context->WriteBuffer(buffer.Get(), fieldBytes, host, this, f * fieldBytes));
      if (!placed)
      {
        return false;
      }
      if (f < marked)
      {
        MarkNonzero(host, 3, SourceFlag, in.LightingFlags);
      }
    }
    return true;
  };
  // S1 in lobes: one buffer holding each voxel's lobes one after the other, each its S1 and its
  // direction (6 floats), so that the kernel reads a corner's lobes from one cache line instead
  // of one per field (REFRACTA_RADIANCE_LOBES).
  auto interleavedLobes = [&]()
  {
    const size_t count = lobes.size();
    values.assign(6 * count * static_cast<size_t>(n), 0.0f);
    for (size_t lobe = 0; lobe < count; ++lobe)
    {
      for (int part = 0; part < 2; ++part)
      {
        FetchFloats(part == 0 ? lobes[lobe] : lobeDirections[lobe], 3, next);
        if (part == 0)
        {
          MarkNonzero(next, 3, SourceFlag, in.LightingFlags);
        }
        for (vtkIdType v = 0; v < n; ++v)
        {
          std::copy_n(&next[3 * v], 3, &values[6 * (v * count + lobe) + 3 * part]);
        }
      }
    }
    in.Radiance = context->CreateBuffer(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, values.size() * 4,
      values.data(), "RadianceLobes", this);
    return static_cast<bool>(in.Radiance);
  };
  // RadianceDirection and MultipleScatteringDirection are stored in the grid-local frame
  // (vtkPhotonTracer, Physics.md).
  if ((in.HasSingle && !lobes.empty() && !interleavedLobes()) ||
    (in.HasSingle && lobes.empty() &&
      (!fields({ radiance }, 1, in.Radiance) || !fields({ direction }, 0, in.RadianceDirection))) ||
    (in.HasMultiple &&
      !fields(multipleDirection ? std::vector<vtkDataArray*>{ multiple, multipleDirection }
                                : std::vector<vtkDataArray*>{ multiple },
        1, in.Multiple)))
  {
    return false;
  }
  if (!this->SetVolumeCaustic(lighting, n))
  {
    return false;
  }
  in.Lighting = lighting;
  in.LightingTime = lighting->GetMTime();
  ++this->NumberOfUploads;
  return true;
}

//------------------------------------------------------------------------------
bool vtkRefractaViewPass::SetVolumeCaustic(vtkImageData* lighting, vtkIdType voxels)
{
  Internals& in = *this->Internal;
  in.VolumeCausticSub = 1;
  in.CausticBricks.Reset();
  in.CausticRadiance.Reset();
  in.CausticDirection.Reset();
  vtkFieldData* fd = lighting->GetFieldData();
  const char* bricksName = vtkRefractaLightingVolume::VolumeCausticBricksName();
  const char* fineName = vtkRefractaLightingVolume::VolumeCausticRadianceName();
  const char* directionName = vtkRefractaLightingVolume::VolumeCausticRadianceDirectionName();
  vtkDataArray* bricks = fd->GetArray(bricksName);
  vtkDataArray* fine = fd->GetArray(fineName);
  vtkDataArray* direction = fd->GetArray(directionName);
  if (!bricks && !fine && !direction)
  {
    return true;
  }
  if (!bricks || !fine || !direction)
  {
    vtkErrorMacro("The lighting volume has some of the volume caustic's field arrays '"
      << bricksName << "', '" << fineName << "' and '" << directionName
      << "' but not all three (vtkPhotonTracer writes them together).");
    return false;
  }
  if (!in.HasSingle)
  {
    vtkErrorMacro(
      "The lighting volume has a volume caustic ('" << fineName << "') but no 'Radiance'.");
    return false;
  }
  if (bricks->GetNumberOfComponents() != 1 || bricks->GetNumberOfTuples() != voxels)
  {
    vtkErrorMacro("The field array '" << bricksName << "' has " << bricks->GetNumberOfTuples()
                                      << " tuples of " << bricks->GetNumberOfComponents()
                                      << " components; it must have one integer per voxel ("
                                      << voxels << ").");
    return false;
  }
  std::vector<int> map(static_cast<size_t>(voxels));
  for (vtkIdType v = 0; v < voxels; ++v)
  {
    const double b = bricks->GetComponent(v, 0);
    if (!(b >= -1.0 && b < double(VTK_INT_MAX)) || b != std::floor(b))
    {
      vtkErrorMacro("The field array '" << bricksName << "' has " << b << " at voxel " << v
                                        << "; each entry must be -1 (no brick) or a brick index.");
      return false;
    }
    map[static_cast<size_t>(v)] = static_cast<int>(b);
  }
  const vtkIdType tuples = fine->GetNumberOfTuples();
  std::string error;
  if (!CheckLightingArray(fine, fineName, tuples, true, error) ||
    !CheckLightingArray(direction, directionName, tuples, false, error))
  {
    vtkErrorMacro(<< error);
    return false;
  }
  vtkIdType count = 0;
  const int c = vtkRefractaLightingVolume::GetVolumeCausticSubdivision(lighting, &count);
  if (c < 2)
  {
    vtkErrorMacro("The field array '" << fineName << "' has " << tuples << " tuples for "
                                      << bricks->GetRange(0)[1] + 1
                                      << " bricks; it must have c^3 per brick, c >= 2.");
    return false;
  }
  vtkOpenCLContext* context = in.GetContext();
  const cl_mem_flags flags = CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR;
  in.CausticBricks =
    context->CreateBuffer(flags, map.size() * sizeof(int), map.data(), bricksName, this);
  std::vector<float> values;
  FetchFloats(fine, 3, values);
  in.CausticRadiance =
    context->CreateBuffer(flags, values.size() * 4, values.data(), fineName, this);
  FetchFloats(direction, 3, values);
  in.CausticDirection =
    context->CreateBuffer(flags, values.size() * 4, values.data(), directionName, this);
  if (!in.CausticBricks || !in.CausticRadiance || !in.CausticDirection)
  {
    return false;
  }
  // A voxel with a brick has light to show even where its Radiance is 0: not empty space.
  for (size_t v = 0; v < map.size(); ++v)
  {
    if (map[v] >= 0)
    {
      in.LightingFlags[v] |= SourceFlag;
    }
  }
  in.VolumeCausticSub = c;
  return true;
}

//------------------------------------------------------------------------------
int vtkRefractaViewPass::GetLightingVolumeCausticSubdivision() const
{
  return this->Internal->VolumeCausticSub;
}

//------------------------------------------------------------------------------
bool vtkRefractaViewPass::GetMediumIsPacked() const
{
  return this->Internal->PackedMedium;
}
