// The analog-scattering stage of vtkPhotonTracer (AnalogScattering with surfaces): the medium's
// anisotropy and the S_ms accumulators on the device, and S_ms resolved (and smoothed like
// Radiance) into the MultipleScattering point array. The marching itself is in photon_trace.cl
// (REFRACTA_ANALOG).
#include "vtkPhotonTracer.h"
#include "vtkPhotonTracerInternals.h"

#include "vtkFloatArray.h"
#include "vtkRefractaLightingVolume.h"

using namespace vtkPhotonTracerDetail;

//------------------------------------------------------------------------------
bool vtkPhotonTracer::UploadAnalogScattering(Internals& run)
{
  Allocator& alloc = run.Alloc;
  this->UsedAnalogScattering = run.Analog;
  if (!run.Analog)
  {
    // The kernels take the arguments whatever the variant: placeholders.
    run.AnisotropyBuffer = alloc.Make(CL_MEM_READ_ONLY, 16, nullptr, "anisotropy (none)");
    run.MultipleFixed = alloc.Make(CL_MEM_READ_WRITE, 16, nullptr, "S_ms accumulator (none)");
    return run.AnisotropyBuffer && run.MultipleFixed;
  }
  const size_t voxels = run.M.Voxels;
  std::vector<float>& g = run.M.Anisotropy;
  g.resize(voxels, 0.0f); // a medium kept from a run before this member existed has none
  run.AnisotropyBuffer = alloc.Make(
    CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, voxels * sizeof(float), g.data(), "anisotropy");
  run.MultipleFixed =
    alloc.Make(CL_MEM_READ_WRITE, voxels * 3 * sizeof(cl_long), nullptr, "S_ms accumulator");
  return run.AnisotropyBuffer && run.MultipleFixed &&
    run.Context->ZeroBuffer(run.MultipleFixed.Get(), voxels * 3 * sizeof(cl_long), this);
}

//------------------------------------------------------------------------------
bool vtkPhotonTracer::ResolveMultipleScattering(Internals& run)
{
  if (!run.Analog)
  {
    return true;
  }
  vtkOpenCLContext* ctx = run.Context;
  Allocator& alloc = run.Alloc;
  const size_t voxels = run.M.Voxels;
  const cl_uint voxelCount = static_cast<cl_uint>(voxels);
  const cl_int4 dims = Int4(run.M.Dims);
  cl_program smooth = ctx->GetProgram({ "refracta_common.cl", "radiance_smooth.cl" }, "", this);
  const size_t bytes = voxels * 3 * sizeof(float);
  vtkOpenCLBuffer a = alloc.Make(CL_MEM_READ_WRITE, bytes, nullptr, "S_ms");
  vtkOpenCLBuffer scratch = alloc.Make(CL_MEM_READ_WRITE, bytes, nullptr, "direction (unused)");
  vtkOpenCLBuffer b;
  if (this->Smoothing)
  {
    b = alloc.Make(CL_MEM_READ_WRITE, bytes, nullptr, "S_ms smoothed");
  }
  if (!smooth || !a || !scratch || (this->Smoothing && !b))
  {
    return false;
  }
  vtkOpenCLKernel resolve = ctx->CreateKernel(smooth, "radiance_resolve", this);
  vtkOpenCLKernel filter = ctx->CreateKernel(smooth, "radiance_smooth", this);
  if (!resolve || !filter)
  {
    return false;
  }
  // The same units as Radiance: deposited power / voxel volume (power per unit volume).
  const cl_float factor = static_cast<cl_float>(
    1.0 / (run.Scale * run.M.Spacing[0] * run.M.Spacing[1] * run.M.Spacing[2]));
  const cl_float directionFactor = 0.0f;
  if (!ctx->Check(vtkOpenCLSetKernelArgs(resolve.Get(), run.MultipleFixed.Get(), run.DirFixed.Get(),
                    factor, directionFactor, a.Get(), scratch.Get(), voxelCount),
        "clSetKernelArg(radiance_resolve)", this) ||
    !Run1D(ctx, resolve.Get(), voxels, "radiance_resolve", this))
  {
    return false;
  }
  cl_mem out = a.Get();
  if (this->Smoothing)
  {
    if (!ctx->Check(vtkOpenCLSetKernelArgs(filter.Get(), a.Get(), dims, b.Get(), voxelCount),
          "clSetKernelArg(radiance_smooth)", this) ||
      !Run1D(ctx, filter.Get(), voxels, "radiance_smooth", this))
    {
      return false;
    }
    out = b.Get();
  }
  vtkFloatArray* multiple = run.Multiple;
  multiple->SetName(vtkRefractaLightingVolume::MultipleScatteringName());
  multiple->SetNumberOfComponents(3);
  multiple->SetNumberOfTuples(static_cast<vtkIdType>(voxels));
  return ctx->ReadBuffer(out, bytes, multiple->GetPointer(0), this);
}
