#include "vtkRefractaViewPass.h"

#include "vtkCommand.h"

#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMath.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkMediumValidator.h"
#include "vtkObjectFactory.h"
#include "vtkOpenCLContext.h"
#include "vtkOpenCLMemoryPlan.h"
#include "vtkPointData.h"
#include "vtkRefractaEnvironmentMap.h"
#include "vtkRefractaGridFrame.h"
#include "vtkRefractaLightingVolume.h"
#include "vtkRefractaMedium.h"
#include "vtkRefractaViewPassOccupancy.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>

vtkStandardNewMacro(vtkRefractaViewPass);

using namespace vtkRefractaViewPassDetail;

namespace
{
// Copies an array's values into floats, `comps` components per tuple (fast path for floats).
void FetchFloats(vtkDataArray* array, int comps, std::vector<float>& out)
{
  const vtkIdType n = array->GetNumberOfTuples();
  out.resize(static_cast<size_t>(n) * comps);
  if (auto* floats = vtkFloatArray::SafeDownCast(array))
  {
    std::copy(floats->GetPointer(0), floats->GetPointer(0) + out.size(), out.begin());
    return;
  }
  for (vtkIdType i = 0; i < n; ++i)
  {
    for (int c = 0; c < comps; ++c)
    {
      out[i * comps + c] = static_cast<float>(array->GetComponent(i, c));
    }
  }
}

// Rotates world-frame vectors (3 per tuple) into the grid-local frame.
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

cl_float4 Float4(const double v[3], double w = 0.0)
{
  cl_float4 r;
  r.s[0] = static_cast<float>(v[0]);
  r.s[1] = static_cast<float>(v[1]);
  r.s[2] = static_cast<float>(v[2]);
  r.s[3] = static_cast<float>(w);
  return r;
}
}

struct vtkRefractaViewPass::Internals
{
  vtkSmartPointer<vtkOpenCLContext> Context;
  vtkSmartPointer<vtkImageData> Environment;

  // Medium on the device.
  vtkImageData* Medium = nullptr;
  vtkMTimeType MediumTime = 0;
  int Dims[3] = { 0, 0, 0 };
  double Spacing[3] = { 1, 1, 1 };
  vtkNew<vtkRefractaGridFrame> Grid;
  bool HasEmission = false;
  bool Refractive = false;
  double UniformIndex = 1.0; // the index where it does not vary (sources then count 1 / n^2)
  vtkOpenCLBuffer Extinction, Emission, Anisotropy, Index, Gradient;

  // Lighting on the device.
  vtkImageData* Lighting = nullptr;
  vtkMTimeType LightingTime = 0;
  bool HasSingle = false;
  bool HasMultiple = false;
  vtkOpenCLBuffer Radiance, RadianceDirection, Multiple;

  // Environment on the device.
  vtkImageData* EnvironmentUploaded = nullptr;
  vtkMTimeType EnvironmentTime = 0;
  int EnvironmentSize[2] = { 0, 0 };
  vtkOpenCLBuffer EnvironmentBuffer;

  // Empty space: per-voxel flags of the medium and of the lighting volume (SourceFlag,
  // GradientFlag), and the macro-cell occupancy built from them when either changes.
  std::vector<uint8_t> MediumFlags, LightingFlags;
  bool OccupancyDirty = true;
  int OccupancyCellSize = 0;
  MacroCellGrid Cells; // the occupancy on the host, and its active cells
  vtkOpenCLBuffer Occupancy;
  double BuildSeconds = 0.0;

  vtkOpenCLBuffer Dummy;

  // Device bytes of each uploaded buffer (medium, lighting, environment, occupancy).
  std::vector<double> UploadedBytes() const
  {
    std::vector<double> sizes;
    for (const vtkOpenCLBuffer* b : { &this->Extinction, &this->Emission, &this->Anisotropy,
           &this->Index, &this->Gradient, &this->Radiance, &this->RadianceDirection,
           &this->Multiple, &this->EnvironmentBuffer, &this->Occupancy, &this->Dummy })
    {
      size_t size = 0;
      if (*b &&
        clGetMemObjectInfo(b->Get(), CL_MEM_SIZE, sizeof(size), &size, nullptr) == CL_SUCCESS)
      {
        sizes.push_back(static_cast<double>(size));
      }
    }
    return sizes;
  }

  // Builds the macro-cell occupancy (BuildMacroCellGrid) when the flags or b changed, and
  // uploads it.
  bool BuildOccupancy(int b, vtkObject* owner)
  {
    if (!this->OccupancyDirty && this->OccupancyCellSize == b && this->Occupancy)
    {
      return true;
    }
    const auto start = std::chrono::steady_clock::now();
    this->Cells = BuildMacroCellGrid(this->Dims, b, this->MediumFlags, this->LightingFlags);
    this->Occupancy = this->GetContext()->CreateBuffer(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
      this->Cells.Cells.size(), this->Cells.Cells.data(), "empty-space occupancy", owner);
    if (!this->Occupancy)
    {
      return false;
    }
    this->OccupancyCellSize = b;
    this->OccupancyDirty = false;
    this->BuildSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return true;
  }

  vtkOpenCLContext* GetContext()
  {
    if (!this->Context)
    {
      this->Context = vtkOpenCLContext::GetDefault();
    }
    return this->Context;
  }
};

//------------------------------------------------------------------------------
vtkRefractaViewPass::vtkRefractaViewPass()
  : Internal(new Internals)
{
}

vtkRefractaViewPass::~vtkRefractaViewPass() = default;

//------------------------------------------------------------------------------
void vtkRefractaViewPass::SetContext(vtkOpenCLContext* context)
{
  if (this->Internal->Context != context)
  {
    // Buffers belong to a context: drop them so they are uploaded again to the new one.
    this->Internal.reset(new Internals);
    this->Internal->Context = context;
    this->Modified();
  }
}

vtkOpenCLContext* vtkRefractaViewPass::GetContext()
{
  return this->Internal->GetContext();
}

void vtkRefractaViewPass::SetEnvironmentMap(vtkImageData* image)
{
  if (this->Internal->Environment != image)
  {
    this->Internal->Environment = image;
    this->Modified();
  }
}

vtkImageData* vtkRefractaViewPass::GetEnvironmentMap()
{
  return this->Internal->Environment;
}

bool vtkRefractaViewPass::GetMediumIsRefractive() const
{
  return this->Internal->Refractive;
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

  auto upload = [&](int id, const char* what, vtkOpenCLBuffer& buffer,
                  std::vector<float>* keep = nullptr) -> bool
  {
    const int comps = vtkRefractaMedium::GetNumberOfComponents(id);
    std::vector<float> values;
    if (vtkDataArray* array = pd->GetArray(vtkRefractaMedium::GetArrayName(id)))
    {
      FetchFloats(array, comps, values);
    }
    else
    {
      values.assign(n * comps, static_cast<float>(vtkRefractaMedium::GetDefaultValue(id)));
    }
    buffer = context->CreateBuffer(
      CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, values.size() * 4, values.data(), what, this);
    if (keep)
    {
      *keep = std::move(values);
    }
    return static_cast<bool>(buffer);
  };

  std::vector<float> kept;
  std::vector<uint8_t> flags(n, 0);
  if (!upload(vtkRefractaMedium::EXTINCTION, "Extinction", in.Extinction, &kept) ||
    !upload(vtkRefractaMedium::ANISOTROPY, "Anisotropy", in.Anisotropy))
  {
    return false;
  }
  MarkNonzero(kept, 3, SourceFlag, flags);
  in.HasEmission = pd->GetArray(vtkRefractaMedium::EmissionName()) != nullptr;
  if (in.HasEmission && !upload(vtkRefractaMedium::EMISSION, "Emission", in.Emission, &kept))
  {
    return false;
  }
  if (in.HasEmission)
  {
    MarkNonzero(kept, 3, SourceFlag, flags);
  }
  if (!in.HasEmission)
  {
    in.Emission.Reset();
  }

  // Refractive index: curved rays need n and grad n (grad n in the grid-local frame).
  in.Refractive = false;
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
      // Central differences (one-sided at the edges) along the grid axes.
      gradient.assign(n * 3, 0.0f);
      const int* dims = in.Dims;
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
              auto at = [&](const int* p)
              {
                return nValues[p[0] +
                  static_cast<size_t>(dims[0]) * (p[1] + static_cast<size_t>(dims[1]) * p[2])];
              };
              gradient[idx * 3 + a] =
                static_cast<float>((at(hi) - at(lo)) / ((hi[a] - lo[a]) * in.Spacing[a]));
            }
          }
        }
      }
    }
    // Curved rays are straight exactly where the grad n samples are zero (the integrator never
    // reads n itself except to scale |v|), so that is what the skipping test needs.
    MarkNonzero(gradient, 3, GradientFlag, flags);
    in.Gradient = context->CreateBuffer(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
      gradient.size() * 4, gradient.data(), "RefractiveIndexGradient", this);
    if (!in.Gradient)
    {
      return false;
    }
  }
  // A new medium invalidates the lighting volume's upload (it must match the grid).
  in.Lighting = nullptr;
  in.HasSingle = in.HasMultiple = false;
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
  if (!lighting)
  {
    if (in.Lighting || !in.LightingFlags.empty())
    {
      in.OccupancyDirty = true;
    }
    in.Lighting = nullptr;
    in.HasSingle = in.HasMultiple = false;
    in.Radiance.Reset();
    in.RadianceDirection.Reset();
    in.Multiple.Reset();
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
  const vtkIdType n = static_cast<vtkIdType>(dims[0]) * dims[1] * dims[2];
  auto check = [&](vtkDataArray* a, const char* name, bool nonNegative) -> bool
  {
    if (a->GetNumberOfComponents() != 3 || a->GetNumberOfTuples() != n)
    {
      vtkErrorMacro("The lighting volume's point array '"
        << name << "' has " << a->GetNumberOfComponents() << " components and "
        << a->GetNumberOfTuples() << " tuples; it needs 3 components and " << n << " tuples.");
      return false;
    }
    for (vtkIdType i = 0; i < n; ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        const double v = a->GetComponent(i, c);
        if (!std::isfinite(v) || (nonNegative && v < 0))
        {
          vtkErrorMacro("The lighting volume's point array '"
            << name << "' has the invalid value " << v << " at tuple " << i << " component " << c
            << "; values must be finite" << (nonNegative ? " and >= 0." : "."));
          return false;
        }
      }
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
  if ((radiance &&
        (!check(radiance, vtkRefractaLightingVolume::RadianceName(), true) ||
          !check(direction, vtkRefractaLightingVolume::RadianceDirectionName(), false))) ||
    (multiple && !check(multiple, vtkRefractaLightingVolume::MultipleScatteringName(), true)))
  {
    return false;
  }
  vtkOpenCLContext* context = in.GetContext();
  std::vector<float> values;
  in.HasSingle = radiance != nullptr;
  in.HasMultiple = multiple != nullptr;
  in.Radiance.Reset();
  in.RadianceDirection.Reset();
  in.Multiple.Reset();
  in.LightingFlags.assign(static_cast<size_t>(n), 0);
  in.OccupancyDirty = true;
  if (in.HasSingle)
  {
    FetchFloats(radiance, 3, values);
    MarkNonzero(values, 3, SourceFlag, in.LightingFlags);
    in.Radiance = context->CreateBuffer(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, values.size() * 4,
      values.data(), vtkRefractaLightingVolume::RadianceName(), this);
    // RadianceDirection is stored in the grid-local frame (vtkPhotonTracer, Physics.md).
    FetchFloats(direction, 3, values);
    in.RadianceDirection = context->CreateBuffer(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
      values.size() * 4, values.data(), vtkRefractaLightingVolume::RadianceDirectionName(), this);
    if (!in.Radiance || !in.RadianceDirection)
    {
      return false;
    }
  }
  if (in.HasMultiple)
  {
    FetchFloats(multiple, 3, values);
    MarkNonzero(values, 3, SourceFlag, in.LightingFlags);
    in.Multiple = context->CreateBuffer(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, values.size() * 4,
      values.data(), vtkRefractaLightingVolume::MultipleScatteringName(), this);
    if (!in.Multiple)
    {
      return false;
    }
  }
  in.Lighting = lighting;
  in.LightingTime = lighting->GetMTime();
  ++this->NumberOfUploads;
  return true;
}

//------------------------------------------------------------------------------
bool vtkRefractaViewPass::ComputeRayFrame(vtkCamera* camera, vtkImageData* medium,
  vtkMatrix4x4* propMatrix, int width, int height, RayFrame& frame)
{
  if (!camera || !medium || width < 1 || height < 1)
  {
    return false;
  }
  double pos[3], fp[3], up[3], w[3], r[3], u[3];
  camera->GetPosition(pos);
  camera->GetFocalPoint(fp);
  camera->GetViewUp(up);
  vtkMath::Subtract(fp, pos, w);
  if (vtkMath::Normalize(w) == 0.0)
  {
    return false;
  }
  vtkMath::Cross(w, up, r);
  if (vtkMath::Normalize(r) == 0.0)
  {
    return false;
  }
  vtkMath::Cross(r, w, u);
  const double aspect = static_cast<double>(width) / height;
  double halfW, halfH;
  frame.Parallel = camera->GetParallelProjection() != 0;
  if (frame.Parallel)
  {
    halfH = camera->GetParallelScale();
    halfW = halfH * aspect;
  }
  else
  {
    const double t = std::tan(vtkMath::RadiansFromDegrees(camera->GetViewAngle()) / 2.0);
    if (camera->GetUseHorizontalViewAngle())
    {
      halfW = t;
      halfH = t / aspect;
    }
    else
    {
      halfH = t;
      halfW = t * aspect;
    }
  }

  // World -> data (inverse prop matrix) -> grid-local (vtkRefractaGridFrame), all in double.
  vtkNew<vtkMatrix4x4> dataToLocal;
  {
    vtkNew<vtkRefractaGridFrame> grid;
    grid->SetImage(medium);
    grid->GetWorldToLocalMatrix(dataToLocal);
  }
  vtkNew<vtkMatrix4x4> worldToLocal;
  if (propMatrix)
  {
    vtkNew<vtkMatrix4x4> inverse;
    vtkMatrix4x4::Invert(propMatrix, inverse);
    vtkMatrix4x4::Multiply4x4(dataToLocal, inverse, worldToLocal);
  }
  else
  {
    worldToLocal->DeepCopy(dataToLocal);
  }
  for (int row = 0; row < 4; ++row)
  {
    for (int col = 0; col < 4; ++col)
    {
      frame.WorldToLocal[row][col] = worldToLocal->GetElement(row, col);
    }
  }
  auto point = [&](const double p[3], double out[3])
  {
    for (int row = 0; row < 3; ++row)
    {
      out[row] = frame.WorldToLocal[row][0] * p[0] + frame.WorldToLocal[row][1] * p[1] +
        frame.WorldToLocal[row][2] * p[2] + frame.WorldToLocal[row][3];
    }
  };
  auto vector = [&](const double v[3], double scale, double out[3])
  {
    for (int row = 0; row < 3; ++row)
    {
      out[row] = scale *
        (frame.WorldToLocal[row][0] * v[0] + frame.WorldToLocal[row][1] * v[1] +
          frame.WorldToLocal[row][2] * v[2]);
    }
  };
  point(pos, frame.Eye);
  vector(r, halfW, frame.U);
  vector(u, halfH, frame.V);
  vector(w, 1.0, frame.W);
  return true;
}

//------------------------------------------------------------------------------
bool vtkRefractaViewPass::Render(vtkCamera* camera, int width, int height, vtkMatrix4x4* propMatrix,
  const float* depthLimit, std::vector<float>& hdr, std::vector<float>* transmittance)
{
  this->LastRenderAborted = false;
  this->LastNumberOfTiles = 0;
  this->LastNumberOfBufferTiles = 0;
  Internals& in = *this->Internal;
  if (!in.Medium)
  {
    vtkErrorMacro("Render() needs a valid medium (SetMedium() failed or was not called).");
    return false;
  }
  if (!camera)
  {
    vtkErrorMacro("No camera: call SetCamera() with a vtkCamera.");
    return false;
  }
  if (width < 1 || height < 1)
  {
    vtkErrorMacro("Image size " << width << " x " << height << " is invalid; both must be >= 1.");
    return false;
  }
  RayFrame frame;
  if (!ComputeRayFrame(camera, in.Medium, propMatrix, width, height, frame))
  {
    vtkErrorMacro("The camera is degenerate (position equals focal point, or view-up parallel "
                  "to the view direction).");
    return false;
  }
  for (int c = 0; c < 3; ++c)
  {
    if (!std::isfinite(this->BackgroundColor[c]) || this->BackgroundColor[c] < 0)
    {
      vtkErrorMacro("BackgroundColor component " << c << " is " << this->BackgroundColor[c]
                                                 << "; it must be finite and >= 0.");
      return false;
    }
  }
  vtkOpenCLContext* context = in.GetContext();
  int bufferRows = height;
  if (!this->PlanImageMemory(
        context, width, height, depthLimit != nullptr, transmittance != nullptr, bufferRows))
  {
    return false;
  }

  // Environment map: upload when changed.
  vtkImageData* env = in.Environment;
  if (env && (in.EnvironmentUploaded != env || in.EnvironmentTime != env->GetMTime()))
  {
    int ed[3];
    env->GetDimensions(ed);
    vtkDataArray* scalars = env->GetPointData()->GetScalars();
    if (!scalars || ed[2] != 1 || ed[0] < 1 || ed[1] < 1 ||
      (scalars->GetNumberOfComponents() != 3 && scalars->GetNumberOfComponents() != 4))
    {
      vtkErrorMacro("The environment map must be a 2D vtkImageData (W x H x 1) with RGB or RGBA "
                    "point scalars; got "
        << ed[0] << " x " << ed[1] << " x " << ed[2] << " with "
        << (scalars ? scalars->GetNumberOfComponents() : 0) << " scalar components.");
      return false;
    }
    const bool bytes = scalars->GetDataType() == VTK_UNSIGNED_CHAR;
    const int comps = scalars->GetNumberOfComponents();
    std::vector<float> rgb(static_cast<size_t>(ed[0]) * ed[1] * 3);
    for (vtkIdType i = 0; i < static_cast<vtkIdType>(ed[0]) * ed[1]; ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        double v = scalars->GetComponent(i, c);
        v = bytes ? v / 255.0 : v;
        rgb[i * 3 + c] = std::isfinite(v) ? static_cast<float>(std::max(v, 0.0)) : 0.0f;
      }
    }
    (void)comps;
    in.EnvironmentBuffer = context->CreateBuffer(
      CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, rgb.size() * 4, rgb.data(), "environment map", this);
    if (!in.EnvironmentBuffer)
    {
      return false;
    }
    in.EnvironmentSize[0] = ed[0];
    in.EnvironmentSize[1] = ed[1];
    in.EnvironmentUploaded = env;
    in.EnvironmentTime = env->GetMTime();
  }

  const bool curved = this->RayMode == CURVED ? static_cast<bool>(in.Index)
                                              : (this->RayMode == AUTO && in.Refractive);
  if (this->RayMode == CURVED && !in.Index)
  {
    vtkDebugMacro("RayMode CURVED with a constant refractive index: rays are straight.");
  }
  std::string options;
  if (curved)
  {
    options += " -DREFRACTA_CURVED";
  }
  if (frame.Parallel)
  {
    options += " -DREFRACTA_PARALLEL";
  }
  // Sources count 1 / n^2 (basic radiance): per step where n varies, as a constant where it is
  // uniform and not 1.
  if (in.Index)
  {
    options += " -DREFRACTA_INDEX_WEIGHT";
  }
  else if (in.UniformIndex != 1.0)
  {
    std::ostringstream scale;
    scale.precision(9);
    scale << " -DREFRACTA_SOURCE_SCALE=" << 1.0 / (in.UniformIndex * in.UniformIndex) << "f";
    options += scale.str();
  }
  if (in.HasSingle)
  {
    options += " -DREFRACTA_HAS_SINGLE";
  }
  if (in.HasMultiple)
  {
    options += " -DREFRACTA_HAS_MULTIPLE";
  }
  if (in.HasEmission)
  {
    options += " -DREFRACTA_HAS_EMISSION";
  }
  if (env)
  {
    options += " -DREFRACTA_HAS_ENVIRONMENT";
  }
  if (depthLimit)
  {
    options += " -DREFRACTA_HAS_DEPTH_LIMIT";
  }
  // Empty-space skipping: only worth a kernel variant when some macro cell is empty for these
  // rays (straight rays ignore grad n).
  bool skipping = false;
  this->LastActiveCellFraction = 1.0;
  if (this->EmptySpaceSkipping)
  {
    if (!in.BuildOccupancy(this->MacroCellSize, this))
    {
      return false;
    }
    this->LastActiveCellFraction = in.Cells.ActiveFraction[curved ? 1 : 0];
    this->OccupancySeconds = in.BuildSeconds;
    skipping = this->LastActiveCellFraction < 1.0;
  }
  if (skipping)
  {
    options += " -DREFRACTA_SKIP";
  }
  cl_program program = context->GetProgram({ "refracta_common.cl", "view_pass.cl" }, options, this);
  if (!program)
  {
    return false;
  }
  vtkOpenCLKernel kernel = context->CreateKernel(program, "refracta_view_pass", this);
  if (!kernel)
  {
    return false;
  }
  if (!in.Dummy)
  {
    const float zero[4] = { 0, 0, 0, 0 };
    in.Dummy = context->CreateBuffer(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(zero), zero,
      "unbound kernel argument (optional array absent)", this);
    if (!in.Dummy)
    {
      return false;
    }
  }
  const size_t pixels = static_cast<size_t>(width) * height;
  auto buf = [&](const vtkOpenCLBuffer& b) { return b ? b.Get() : in.Dummy.Get(); };

  const double minSpacing = std::min({ in.Spacing[0], in.Spacing[1], in.Spacing[2] });
  const cl_int4 dims = { { in.Dims[0], in.Dims[1], in.Dims[2], 0 } };
  const cl_float4 spacing = Float4(in.Spacing);
  const cl_float stepLength = static_cast<float>(this->StepSize * minSpacing);
  const cl_int maxSteps = this->MaxSteps > 0
    ? this->MaxSteps
    : static_cast<cl_int>(std::ceil(4.0 * (in.Dims[0] + in.Dims[1] + in.Dims[2]) / this->StepSize));
  const cl_float cutoff = static_cast<float>(this->TransmittanceCutoff);
  const cl_float4 background = Float4(this->BackgroundColor);

  // Environment basis (vtkRefractaEnvironmentMap: right, up, front = up x right, in world),
  // then rotated to grid-local (prop and D), so the kernel's dot products are the world ones.
  double er[3], eu[3], ef[3];
  vtkRefractaEnvironmentMap::ComputeBasis(this->EnvironmentUp, this->EnvironmentRight, er, eu, ef);
  // A world direction x maps to local L x (L the linear part of WorldToLocal); dot(x, e) =
  // dot(L x, L^-T e); for the rigid transforms used here L^-T = L, so rotate e by L and
  // re-normalise.
  auto toLocal = [&](const double v[3])
  {
    double out[3];
    for (int row = 0; row < 3; ++row)
    {
      out[row] = frame.WorldToLocal[row][0] * v[0] + frame.WorldToLocal[row][1] * v[1] +
        frame.WorldToLocal[row][2] * v[2];
    }
    vtkMath::Normalize(out);
    return Float4(out);
  };
  const cl_float4 envRight = toLocal(er), envUp = toLocal(eu), envFront = toLocal(ef);
  const cl_int2 envSize = { { std::max(in.EnvironmentSize[0], 1),
    std::max(in.EnvironmentSize[1], 1) } };

  const cl_int4 cellDims = { { in.Cells.CellDims[0], in.Cells.CellDims[1], in.Cells.CellDims[2],
    in.OccupancyCellSize > 0 ? in.OccupancyCellSize : 1 } };
  const cl_uint skipMask = curved ? (SourceFlag | GradientFlag) : SourceFlag;
  const int m = curved ? 1 : 0;
  const bool anyActive = in.Cells.ActiveHi[m][0] >= 0;
  const cl_int4 activeLo = { { in.Cells.ActiveLo[m][0], in.Cells.ActiveLo[m][1],
    in.Cells.ActiveLo[m][2], anyActive ? 1 : 0 } };
  const cl_int4 activeHi = { { in.Cells.ActiveHi[m][0], in.Cells.ActiveHi[m][1],
    in.Cells.ActiveHi[m][2], 0 } };
  const auto start = std::chrono::steady_clock::now();
  // Rendered into local images, handed over at the end: an aborted render leaves the caller's
  // vectors untouched.
  std::vector<float> image(pixels * 4);
  std::vector<float> transmittanceImage(transmittance ? pixels * 4 : 0);
  std::vector<cl_uint> steps(pixels);
  int rowsPerTile = std::max(1, std::min(height, this->TilePixels / width));
  // Buffer tiles (PlanImageMemory): when the whole image's buffers exceed what one allocation
  // may hold, rows [row0, row0 + rows) are rendered as an image of their own, whose frame is
  // the slice of the full one (the kernel's pixel (i, j) of the slice is pixel (i, row0 + j)).
  for (int row0 = 0; row0 < height; row0 += bufferRows)
  {
    const int rows = std::min(bufferRows, height - row0);
    const size_t slice = static_cast<size_t>(width) * rows;
    vtkOpenCLBuffer hdrBuffer =
      context->CreateBuffer(CL_MEM_WRITE_ONLY, slice * 16, nullptr, "HDR image", this);
    vtkOpenCLBuffer stepBuffer =
      context->CreateBuffer(CL_MEM_WRITE_ONLY, slice * 4, nullptr, "step counts", this);
    vtkOpenCLBuffer transmittanceBuffer =
      context->CreateBuffer(CL_MEM_WRITE_ONLY, slice * 16, nullptr, "transmittance image", this);
    vtkOpenCLBuffer depthBuffer;
    if (depthLimit)
    {
      depthBuffer = context->CreateBuffer(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, slice * 4,
        depthLimit + static_cast<size_t>(width) * row0, "depth limits", this);
    }
    if (!hdrBuffer || !stepBuffer || !transmittanceBuffer || (depthLimit && !depthBuffer))
    {
      return false;
    }
    // The slice's frame: sy = 2 (j + 1/2) / height - 1 of the full image is
    // (rows / height) sy' + ((2 row0 + rows) / height - 1) in terms of the slice's own sy'.
    RayFrame part = frame;
    const double scaleV = static_cast<double>(rows) / height;
    const double shiftV = (2.0 * row0 + rows) / height - 1.0;
    for (int c = 0; c < 3; ++c)
    {
      if (frame.Parallel)
      {
        part.Eye[c] = frame.Eye[c] + shiftV * frame.V[c];
      }
      else
      {
        part.W[c] = frame.W[c] + shiftV * frame.V[c];
      }
      part.V[c] = scaleV * frame.V[c];
    }
    const cl_int w = width, h = rows;
    const cl_int status = vtkOpenCLSetKernelArgs(kernel.Get(), dims, spacing, buf(in.Extinction),
      buf(in.Emission), buf(in.Anisotropy), buf(in.Index), buf(in.Gradient), buf(in.Radiance),
      buf(in.RadianceDirection), buf(in.Multiple), Float4(part.Eye), Float4(part.U), Float4(part.V),
      Float4(part.W), w, h, stepLength, maxSteps, cutoff, background,
      env ? in.EnvironmentBuffer.Get() : in.Dummy.Get(), envSize, envRight, envUp, envFront,
      buf(depthBuffer), skipping ? in.Occupancy.Get() : in.Dummy.Get(), cellDims, activeLo,
      activeHi, skipMask, hdrBuffer.Get(), stepBuffer.Get(), transmittanceBuffer.Get());
    if (!context->Check(status, "clSetKernelArg (refracta_view_pass)", this) ||
      !this->RunTiles(context, kernel.Get(), width, rows, row0, height, rowsPerTile))
    {
      return false;
    }
    const size_t first = static_cast<size_t>(width) * row0;
    if (!context->ReadBuffer(hdrBuffer.Get(), slice * 16, image.data() + 4 * first, this) ||
      !context->ReadBuffer(stepBuffer.Get(), slice * 4, steps.data() + first, this) ||
      (transmittance &&
        !context->ReadBuffer(
          transmittanceBuffer.Get(), slice * 16, transmittanceImage.data() + 4 * first, this)))
    {
      return false;
    }
    ++this->LastNumberOfBufferTiles;
  }
  hdr.swap(image);
  if (transmittance)
  {
    transmittance->swap(transmittanceImage);
  }
  this->LastSeconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  double total = 0;
  for (cl_uint s : steps)
  {
    total += s;
  }
  this->LastTotalSteps = total;
  this->LastCurved = curved;
  this->LastSkipping = skipping;
  ++this->NumberOfRenders;
  return true;
}

//------------------------------------------------------------------------------
bool vtkRefractaViewPass::PlanImageMemory(
  vtkOpenCLContext* context, int width, int height, bool depth, bool transmittance, int& bufferRows)
{
  // Per pixel on the device: HDR (4 floats), transmittance (4 floats), step count, depth limit;
  // on the host: the HDR image, the step counts and (when asked for) the transmittance image.
  const double row = static_cast<double>(width);
  const double perAllocation = context->GetMaximumAllocationBytes();
  bufferRows = height;
  if (perAllocation > 0 && row * height * 16 > perAllocation)
  {
    // Buffer tiles of whole rows that each fit one allocation (the largest buffer is 16 bytes a
    // pixel); a single row that does not fit is reported below.
    bufferRows = static_cast<int>(std::max(1.0, std::floor(perAllocation / (row * 16))));
  }
  std::ostringstream subject;
  subject << "image " << width << " x " << height;
  if (bufferRows < height)
  {
    subject << " (in tiles of " << bufferRows << " rows)";
  }
  const double slice = row * bufferRows;
  vtkOpenCLMemoryPlan* plan = this->MemoryPlan;
  plan->Reset("view pass");
  plan->AddDeviceBuffer(subject.str(), "HDR buffer", slice * 16, "the image size");
  plan->AddDeviceBuffer(subject.str(), "transmittance buffer", slice * 16, "the image size");
  plan->AddDeviceBuffer(subject.str(), "step counts", slice * 4, "the image size");
  if (depth)
  {
    plan->AddDeviceBuffer(subject.str(), "depth limits", slice * 4, "the image size");
  }
  for (double bytes : this->Internal->UploadedBytes())
  {
    plan->AddResidentDeviceBuffer(
      "the uploaded arrays", "medium or lighting array", bytes, "the grid size");
  }
  const double pixels = row * height;
  plan->AddHostMemory(subject.str(), "HDR image", pixels * 16, "the image size");
  plan->AddHostMemory(subject.str(), "step counts", pixels * 4, "the image size");
  if (transmittance)
  {
    plan->AddHostMemory(subject.str(), "transmittance image", pixels * 16, "the image size");
  }
  this->PlannedDeviceMemoryBytes = plan->GetDeviceBytes();
  if (!plan->Fits(context))
  {
    vtkErrorMacro(<< plan->GetMessage());
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkRefractaViewPass::RunTiles(vtkOpenCLContext* context, cl_kernel kernel, int width,
  int height, int firstRow, int imageHeight, int& rowsPerTile)
{
  // Tiles of whole rows (a global offset on the same kernel: every pixel computes exactly what it
  // would in one launch), each waited for, so that progress is reported and an abort is seen
  // between them. The first tile has TilePixels pixels; later ones are sized from the measured
  // rate to take about TileSeconds (at most twice the previous tile, at least one row).
  for (int row = 0, rows = 0; row < height; row += rows)
  {
    rows = std::min(rowsPerTile, height - row);
    const auto tileStart = std::chrono::steady_clock::now();
    const size_t offset[2] = { 0, static_cast<size_t>(row) };
    const size_t global[2] = { static_cast<size_t>(width), static_cast<size_t>(rows) };
    if (!context->RunKernel(kernel, 2, global, nullptr, "refracta_view_pass", this, offset) ||
      !context->Finish(this))
    {
      return false;
    }
    ++this->LastNumberOfTiles;
    if (this->TileSeconds > 0)
    {
      const double seconds = std::max(
        1e-6, std::chrono::duration<double>(std::chrono::steady_clock::now() - tileStart).count());
      const double wanted = rows * this->TileSeconds / seconds;
      rowsPerTile = static_cast<int>(std::max(1.0, std::min(wanted, 2.0 * rows)));
    }
    const int done = firstRow + row + rows;
    double progress = static_cast<double>(done) / imageHeight;
    this->InvokeEvent(vtkCommand::ProgressEvent, &progress);
    if (this->AbortRender && done < imageHeight)
    {
      this->LastRenderAborted = true;
      return false;
    }
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkRefractaViewPass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "StepSize: " << this->StepSize << " voxels\n";
  os << indent << "RayMode: "
     << (this->RayMode == AUTO ? "AUTO" : (this->RayMode == STRAIGHT ? "STRAIGHT" : "CURVED"))
     << "\n";
  os << indent << "TransmittanceCutoff: " << this->TransmittanceCutoff << "\n";
  os << indent << "MaxSteps: " << this->MaxSteps << "\n";
  os << indent << "TilePixels: " << this->TilePixels << "\n";
  os << indent << "TileSeconds: " << this->TileSeconds << "\n";
  os << indent << "AbortRender: " << this->AbortRender << "\n";
  os << indent << "BackgroundColor: (" << this->BackgroundColor[0] << ", "
     << this->BackgroundColor[1] << ", " << this->BackgroundColor[2] << ")\n";
  os << indent << "EnvironmentMap: " << this->Internal->Environment.Get() << "\n";
  os << indent << "EnvironmentUp: (" << this->EnvironmentUp[0] << ", " << this->EnvironmentUp[1]
     << ", " << this->EnvironmentUp[2] << ")\n";
  os << indent << "EnvironmentRight: (" << this->EnvironmentRight[0] << ", "
     << this->EnvironmentRight[1] << ", " << this->EnvironmentRight[2] << ")\n";
  os << indent << "EmptySpaceSkipping: " << (this->EmptySpaceSkipping ? "on" : "off") << "\n";
  os << indent << "MacroCellSize: " << this->MacroCellSize << " voxels\n";
  os << indent << "LastSkipping: " << (this->LastSkipping ? "yes" : "no") << "\n";
  os << indent << "LastActiveCellFraction: " << this->LastActiveCellFraction << "\n";
  os << indent << "LastSeconds: " << this->LastSeconds << "\n";
  os << indent << "LastTotalSteps: " << this->LastTotalSteps << "\n";
  os << indent << "NumberOfUploads: " << this->NumberOfUploads << "\n";
  os << indent << "NumberOfRenders: " << this->NumberOfRenders << "\n";
  os << indent << "LastNumberOfBufferTiles: " << this->LastNumberOfBufferTiles << "\n";
  os << indent << "PlannedDeviceMemoryBytes: " << this->PlannedDeviceMemoryBytes << "\n";
}
