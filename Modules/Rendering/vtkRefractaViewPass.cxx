#include "vtkRefractaViewPass.h"

#include "vtkCommand.h"

#include "vtkCamera.h"
#include "vtkImageData.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkOpenCLContext.h"
#include "vtkOpenCLMemoryPlan.h"
#include "vtkRefractaEnvironmentMap.h"
#include "vtkRefractaGridFrame.h"
#include "vtkRefractaHostThreads.h"
#include "vtkRefractaSettings.h"
#include "vtkRefractaSurfaceSet.h"
#include "vtkRefractaViewPassFields.h"
#include "vtkRefractaViewPassInternals.h"
#include "vtkRefractaViewPassOccupancy.h"
#include "vtkRefractaViewPassSurfaces.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>

vtkStandardNewMacro(vtkRefractaViewPass);
vtkRefractaCxxSetClampMacro(vtkRefractaViewPass, StepSize, 0.01, 16.0);
vtkRefractaCxxSetClampMacro(vtkRefractaViewPass, TransmittanceCutoff, 0.0, 1.0);
vtkRefractaCxxSetClampMacro(vtkRefractaViewPass, CausticPhotonsPerFineTexel, 0.0, 1e30);
vtkRefractaCxxSetClampMacro(vtkRefractaViewPass, DielectricGrazingCosine, 0.0, 1.0);
vtkRefractaCxxSetClampMacro(vtkRefractaViewPass, TileSeconds, 0.0, 1e6);
vtkRefractaCxxSetVector3Macro(vtkRefractaViewPass, BackgroundColor);
vtkRefractaCxxSetVector3Macro(vtkRefractaViewPass, EnvironmentUp);
vtkRefractaCxxSetVector3Macro(vtkRefractaViewPass, EnvironmentRight);

using namespace vtkRefractaViewPassDetail;

namespace
{
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

//------------------------------------------------------------------------------
vtkRefractaViewPass::vtkRefractaViewPass()
  : Internal(new Internals)
{
  vtkRefractaHostThreads::UseThreadedBackend();
}

vtkRefractaViewPass::~vtkRefractaViewPass() = default;

//------------------------------------------------------------------------------
void vtkRefractaViewPass::SetContext(vtkOpenCLContext* context)
{
  if (this->Internal->Context != context)
  {
    // Buffers belong to a context: drop them so they are uploaded again to the new one.
    vtkSmartPointer<vtkRefractaSurfaceSet> surfaces = this->Internal->SurfaceSet;
    this->Internal.reset(new Internals);
    this->Internal->Context = context;
    this->Internal->SurfaceSet = surfaces;
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

void vtkRefractaViewPass::SetSurfaces(vtkRefractaSurfaceSet* surfaces)
{
  if (this->Internal->SurfaceSet != surfaces)
  {
    this->Internal->SurfaceSet = surfaces;
    this->Modified();
  }
}

vtkRefractaSurfaceSet* vtkRefractaViewPass::GetSurfaces()
{
  return this->Internal->SurfaceSet;
}

int vtkRefractaViewPass::GetNumberOfSurfaceUploads()
{
  return this->Internal->Surfaces.GetNumberOfUploads();
}

vtkMTimeType vtkRefractaViewPass::GetMTime()
{
  vtkMTimeType time = this->Superclass::GetMTime();
  if (vtkRefractaSurfaceSet* surfaces = this->Internal->SurfaceSet)
  {
    time = std::max(time, surfaces->GetMTime());
  }
  return time;
}

bool vtkRefractaViewPass::GetMediumIsRefractive() const
{
  return this->Internal->Refractive;
}

//------------------------------------------------------------------------------
bool vtkRefractaViewPass::ComputeRayFrame(vtkCamera* camera, vtkImageData* medium,
  vtkMatrix4x4* propMatrix, int width, int height, RayFrame& frame)
{
  if (!medium || width < 1 || height < 1 || !GetRayFrameProblem(camera, propMatrix).empty())
  {
    return false;
  }
  double pos[3], fp[3], up[3], w[3], r[3], u[3];
  camera->GetPosition(pos);
  camera->GetFocalPoint(fp);
  camera->GetViewUp(up);
  vtkMath::Subtract(fp, pos, w);
  vtkMath::Normalize(w);
  vtkMath::Cross(w, up, r);
  vtkMath::Normalize(r);
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
  // The window centre (vtkCamera::SetWindowCenter; tiled rendering, vtkRenderLargeImage) shifts
  // the frustum: pixel (sx, sy) of the view looks where (sx + cx, sy + cy) of the centred one
  // would, so the shift moves the eye (parallel) or the central direction (perspective).
  const double* centre = camera->GetWindowCenter();
  double* shifted = frame.Parallel ? frame.Eye : frame.W;
  for (int a = 0; a < 3; ++a)
  {
    shifted[a] += centre[0] * frame.U[a] + centre[1] * frame.V[a];
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkRefractaViewPass::Render(vtkCamera* camera, int width, int height, vtkMatrix4x4* propMatrix,
  const float* depthLimit, std::vector<float>& hdr, std::vector<float>* transmittance,
  std::vector<float>* surfaceDepth, std::vector<float>* background)
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
  if (width < 1 || height < 1)
  {
    vtkErrorMacro("Image size " << width << " x " << height << " is invalid; both must be >= 1.");
    return false;
  }
  const std::string why = GetRayFrameProblem(camera, propMatrix);
  if (!why.empty())
  {
    vtkErrorMacro(<< why);
    return false;
  }
  RayFrame frame;
  ComputeRayFrame(camera, in.Medium, propMatrix, width, height, frame);
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
  const int hostImages = (transmittance ? 1 : 0) + (background ? 1 : 0); // of RGBA floats
  if (!this->PlanImageMemory(context, width, height, depthLimit != nullptr, hostImages, bufferRows))
  {
    return false;
  }

  // Environment map: upload when changed.
  vtkImageData* env = in.Environment;
  if (env && (in.EnvironmentUploaded != env || in.EnvironmentTime != env->GetMTime()))
  {
    std::vector<float> rgb;
    std::string error;
    if (!EnvironmentToRGB(env, rgb, in.EnvironmentSize, in.EnvironmentIsChecker, error))
    {
      vtkErrorMacro(<< error);
      return false;
    }
    in.EnvironmentBuffer = context->CreateBuffer(
      CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, rgb.size() * 4, rgb.data(), "environment map", this);
    if (!in.EnvironmentBuffer)
    {
      return false;
    }
    in.EnvironmentUploaded = env;
    in.EnvironmentTime = env->GetMTime();
  }

  // Surfaces: built and uploaded when the set's build is new, the irradiance when it changed.
  SurfaceBuffers& surf = in.Surfaces;
  if (!surf.Update(in.SurfaceSet, context, this) ||
    (surf.Active() && !surf.PrepareIrradiance(context, this->CausticPhotonsPerFineTexel, this)) ||
    !surf.UpdateCuts(in.Dims, in.Spacing, frame.WorldToLocal, context, this))
  {
    return false;
  }

  const bool curved =
    this->RayMode == CURVED ? static_cast<bool>(in.Index) : (this->RayMode == AUTO && in.Bends);
  if (this->RayMode == CURVED && !in.Index)
  {
    vtkDebugMacro("RayMode CURVED with a constant refractive index: rays are straight.");
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
  KernelVariant variant;
  variant.Curved = curved;
  variant.Parallel = frame.Parallel;
  variant.IndexVaries = static_cast<bool>(in.Index);
  variant.UniformIndex = in.UniformIndex;
  variant.Single = in.HasSingle;
  variant.RadianceLobes = in.RadianceLobes;
  variant.Multiple = in.HasMultiple;
  variant.MultipleDirection = in.HasMultipleDirection;
  variant.Emission = in.HasEmission;
  variant.Packed = in.PackedMedium;
  variant.Environment = env != nullptr;
  variant.Checker = env != nullptr && in.EnvironmentIsChecker;
  variant.DepthLimit = depthLimit != nullptr;
  variant.Skip = skipping;
  variant.Surfaces = surf.Active();
  variant.NearestTexel = this->SurfaceFilter == NEAREST_TEXEL;
  variant.Dielectric = surf.HasDielectric();
  variant.SplitDepth = this->DielectricSplitDepth;
  variant.Sided = surf.HasCuts() && (in.HasSingle || in.HasMultiple);
  variant.Caustic = surf.GetCausticSubdivision();
  variant.CausticOffset = surf.GetNumberOfTexels();
  variant.LaneMarching = this->LaneMarching &&
    LaneMarchingApplies(
      variant, context->GetIsGPU(), static_cast<vtkIdType>(in.Dims[0]) * in.Dims[1] * in.Dims[2]);
  this->LastLaneMarching = variant.LaneMarching;
  cl_program program = context->GetProgram(
    { "refracta_common.cl", "refracta_surfaces.cl", "view_surfaces.cl", "view_skipping.cl",
      "view_caustic.cl", "view_pass.cl", "view_pixel.cl", "view_lanes.cl" },
    KernelOptions(variant), this);
  if (!program)
  {
    return false;
  }
  vtkRefractaViewLaunch launch;
  if (variant.LaneMarching)
  {
    launch.Name = "refracta_view_pass_lanes";
    launch.PixelsPerItem = 8;
  }
  vtkOpenCLKernel kernel = context->CreateKernel(program, launch.Name, this);
  if (!kernel)
  {
    return false;
  }
  launch.Kernel = kernel.Get();
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
  // Work-groups of side x side pixels, 8 x 8 where the kernel may run 64 work-items: neighbouring
  // rays share the medium's cache lines, and one shape means one work-group function (PoCL
  // compiles one per local size, and a size left to the driver follows each tile's height). The
  // lane kernel's groups are 1 x 8 items of 8 pixels each (its required work-group size).
  while (launch.PixelsPerItem == 1 && launch.GroupSide > 1 &&
    static_cast<size_t>(launch.GroupSide * launch.GroupSide) >
      context->GetKernelWorkGroupSize(kernel.Get()))
  {
    launch.GroupSide /= 2;
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
  const cl_float4 backgroundColor = Float4(this->BackgroundColor);

  // Environment basis (vtkRefractaEnvironmentMap) in the grid-local frame.
  double basis[3][3];
  EnvironmentBasisLocal(this->EnvironmentUp, this->EnvironmentRight, frame.WorldToLocal, basis);
  const cl_float4 envRight = Float4(basis[0]), envUp = Float4(basis[1]),
                  envFront = Float4(basis[2]);
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
  cl_float4 toSurface[3] = {};
  if (surf.Active())
  {
    surf.ComputeLocalToSurface(frame.WorldToLocal, toSurface);
  }
  const cl_int nodeCount = surf.GetNodeCount();
  const auto start = std::chrono::steady_clock::now();
  // Rendered into local images, handed over at the end: an aborted render leaves the caller's
  // vectors untouched.
  // (every pixel of every buffer is written by the kernel, so reused memory need not be cleared)
  std::vector<float>& image = in.ImageScratch;
  std::vector<float>& transmittanceImage = in.TransmittanceScratch;
  std::vector<float>& backgroundImage = in.BackgroundScratch;
  std::vector<float>& surfaceDepthImage = in.SurfaceDepthScratch;
  std::vector<cl_uint>& steps = in.StepScratch;
  image.resize(pixels * 4);
  transmittanceImage.resize(transmittance ? pixels * 4 : 0);
  backgroundImage.resize(background ? pixels * 4 : 0);
  surfaceDepthImage.resize(surfaceDepth ? pixels : 0);
  steps.resize(pixels);
  int rowsPerTile = std::max(1, std::min(height, this->TilePixels / width));
  cl_int supersampledPixels = 0;
  vtkOpenCLBuffer supersampledBuffer =
    context->CreateBuffer(CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, sizeof(cl_int),
      &supersampledPixels, "supersampled pixel count", this);
  if (!supersampledBuffer)
  {
    return false;
  }
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
    vtkOpenCLBuffer backgroundBuffer =
      context->CreateBuffer(CL_MEM_WRITE_ONLY, slice * 16, nullptr, "background image", this);
    vtkOpenCLBuffer surfaceDepthBuffer =
      context->CreateBuffer(CL_MEM_WRITE_ONLY, slice * 4, nullptr, "surface depth", this);
    vtkOpenCLBuffer depthBuffer;
    if (depthLimit)
    {
      depthBuffer = context->CreateBuffer(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, slice * 4,
        depthLimit + static_cast<size_t>(width) * row0, "depth limits", this);
    }
    if (!hdrBuffer || !stepBuffer || !transmittanceBuffer || !backgroundBuffer ||
      !surfaceDepthBuffer || (depthLimit && !depthBuffer))
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
    const cl_int w = width, h = rows, causticSub = in.VolumeCausticSub,
                 supersampling = this->DielectricSupersampling;
    const cl_float grazingCosine = static_cast<cl_float>(this->DielectricGrazingCosine);
    const cl_int status = vtkOpenCLSetKernelArgs(kernel.Get(), dims, spacing, buf(in.Extinction),
      buf(in.Emission), buf(in.Anisotropy), buf(in.Index), buf(in.Gradient), buf(in.Radiance),
      buf(in.RadianceDirection), buf(in.Multiple), Float4(part.Eye), Float4(part.U), Float4(part.V),
      Float4(part.W), w, h, stepLength, maxSteps, cutoff, backgroundColor,
      env ? in.EnvironmentBuffer.Get() : in.Dummy.Get(), envSize, envRight, envUp, envFront,
      buf(depthBuffer), skipping ? in.Occupancy.Get() : in.Dummy.Get(), cellDims, activeLo,
      activeHi, skipMask, buf(surf.Nodes), nodeCount, buf(surf.Triangles), buf(surf.TriangleInfo),
      buf(surf.Albedo), buf(surf.Irradiance), buf(surf.Corners), buf(surf.Normals),
      buf(surf.Interfaces), toSurface[0], toSurface[1], toSurface[2], hdrBuffer.Get(),
      stepBuffer.Get(), transmittanceBuffer.Get(), backgroundBuffer.Get(), surfaceDepthBuffer.Get(),
      buf(surf.Bodies), buf(in.CausticBricks), buf(in.CausticRadiance), buf(in.CausticDirection),
      causticSub, supersampling, grazingCosine, supersampledBuffer.Get(), buf(surf.CutLinks));
    if (!context->Check(status, "clSetKernelArg (refracta_view_pass)", this) ||
      !this->RunTiles(context, launch, width, rows, row0, height, rowsPerTile))
    {
      return false;
    }
    const size_t first = static_cast<size_t>(width) * row0;
    if (!context->ReadBuffer(hdrBuffer.Get(), slice * 16, image.data() + 4 * first, this) ||
      !context->ReadBuffer(stepBuffer.Get(), slice * 4, steps.data() + first, this) ||
      (transmittance &&
        !context->ReadBuffer(
          transmittanceBuffer.Get(), slice * 16, transmittanceImage.data() + 4 * first, this)) ||
      (background &&
        !context->ReadBuffer(
          backgroundBuffer.Get(), slice * 16, backgroundImage.data() + 4 * first, this)) ||
      (surfaceDepth &&
        !context->ReadBuffer(
          surfaceDepthBuffer.Get(), slice * 4, surfaceDepthImage.data() + first, this)))
    {
      return false;
    }
    ++this->LastNumberOfBufferTiles;
  }
  if (!context->ReadBuffer(supersampledBuffer.Get(), sizeof(cl_int), &supersampledPixels, this))
  {
    return false;
  }
  this->LastNumberOfSupersampledPixels = supersampledPixels;
  hdr.swap(image);
  if (transmittance)
  {
    transmittance->swap(transmittanceImage);
  }
  if (surfaceDepth)
  {
    surfaceDepth->swap(surfaceDepthImage);
  }
  if (background)
  {
    background->swap(backgroundImage);
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
  vtkOpenCLContext* context, int width, int height, bool depth, int hostImages, int& bufferRows)
{
  // Per pixel on the device: HDR, transmittance and background (4 floats each), step count,
  // surface depth, depth limit; on the host: the HDR image, the step counts and `hostImages`
  // RGBA float images asked for (transmittance, background).
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
  plan->AddDeviceBuffer(subject.str(), "background buffer", slice * 16, "the image size");
  plan->AddDeviceBuffer(subject.str(), "step counts", slice * 4, "the image size");
  plan->AddDeviceBuffer(subject.str(), "surface depth", slice * 4, "the image size");
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
  if (hostImages > 0)
  {
    plan->AddHostMemory(subject.str(), "transmittance and background images",
      hostImages * pixels * 16, "the image size");
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
bool vtkRefractaViewPass::RunTiles(vtkOpenCLContext* context, const vtkRefractaViewLaunch& launch,
  int width, int height, int firstRow, int imageHeight, int& rowsPerTile)
{
  // Tiles of whole rows (a global offset on the same kernel: every pixel computes exactly what it
  // would in one launch), each waited for, so that progress is reported and an abort is seen
  // between them. The first tile has TilePixels pixels; later ones are sized from the measured
  // rate to take about TileSeconds (at most twice the previous tile, at least one row). Tiles
  // are whole work-groups of groupSide rows (the last one padded: the kernel skips pixels past
  // the image).
  const int groupSide = launch.GroupSide;
  const size_t local[2] = { static_cast<size_t>(launch.PixelsPerItem > 1 ? 1 : groupSide),
    static_cast<size_t>(groupSide) };
  for (int row = 0, rows = 0; row < height; row += rows)
  {
    rowsPerTile = (rowsPerTile + groupSide - 1) / groupSide * groupSide;
    rows = std::min(rowsPerTile, height - row);
    const auto tileStart = std::chrono::steady_clock::now();
    const size_t offset[2] = { 0, static_cast<size_t>(row) };
    const size_t global[2] = { static_cast<size_t>(
                                 (width + launch.PixelsPerItem - 1) / launch.PixelsPerItem),
      static_cast<size_t>(rows) };
    if (!context->RunKernel(launch.Kernel, 2, global, local, launch.Name, this, offset) ||
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
vtkIdType vtkRefractaViewPass::GetLastNumberOfFineCausticTexels() const
{
  return this->Internal->Surfaces.GetNumberOfFineCausticTexels();
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
  os << indent << "LaneMarching: " << this->LaneMarching << "\n";
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
  os << indent << "Surfaces: " << this->Internal->SurfaceSet.Get() << "\n";
  os << indent << "DielectricSplitDepth: " << this->DielectricSplitDepth << "\n";
  os << indent << "DielectricSupersampling: " << this->DielectricSupersampling << "\n";
  os << indent << "DielectricGrazingCosine: " << this->DielectricGrazingCosine << "\n";
  os << indent << "LastNumberOfSupersampledPixels: " << this->LastNumberOfSupersampledPixels
     << "\n";
  os << indent << "SurfaceFilter: "
     << (this->SurfaceFilter == NEAREST_TEXEL ? "NEAREST_TEXEL" : "LINEAR_TEXEL") << "\n";
  os << indent << "CausticPhotonsPerFineTexel: " << this->CausticPhotonsPerFineTexel << "\n";
  os << indent << "NumberOfSurfaceUploads: " << this->Internal->Surfaces.GetNumberOfUploads()
     << "\n";
  os << indent << "MediumIsPacked: " << (this->GetMediumIsPacked() ? "yes" : "no") << "\n";
  os << indent << "LastSkipping: " << (this->LastSkipping ? "yes" : "no") << "\n";
  os << indent << "LastActiveCellFraction: " << this->LastActiveCellFraction << "\n";
  os << indent << "LastSeconds: " << this->LastSeconds << "\n";
  os << indent << "LastTotalSteps: " << this->LastTotalSteps << "\n";
  os << indent << "NumberOfUploads: " << this->NumberOfUploads << "\n";
  os << indent << "NumberOfRenders: " << this->NumberOfRenders << "\n";
  os << indent << "LastNumberOfBufferTiles: " << this->LastNumberOfBufferTiles << "\n";
  os << indent << "PlannedDeviceMemoryBytes: " << this->PlannedDeviceMemoryBytes << "\n";
}
