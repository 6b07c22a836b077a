// The analog-scattering stage of vtkPhotonTracer (AnalogScattering with surfaces, and the
// first-collision split of ScatteringOrders): the medium's anisotropy and the accumulators on the
// device, and S_ms (with its flux over its fluence, or the split's lattice source) resolved and
// smoothed like Radiance into point arrays. The marching itself is in photon_trace.cl
// (REFRACTA_ANALOG).
#include "vtkPhotonTracer.h"
#include "vtkPhotonTracerInternals.h"

#include "vtkFloatArray.h"
#include "vtkOpenCLDeviceArrays.h"
#include "vtkRefractaLightingVolume.h"
#include "vtkSMPTools.h"

#include <cmath>

using namespace vtkPhotonTracerDetail;

namespace
{
// S_ms's direction sums (per photon scale) into F / phi_ms: over the channel sum of S_ms times
// the voxel's volume (the deposits' weight), at most unit length (rounding), zero where none.
void FluxOverFluence(vtkFloatArray* multiple, vtkFloatArray* direction, double volume)
{
  const float* ms = multiple->GetPointer(0);
  float* d = direction->GetPointer(0);
  vtkSMPTools::For(0, multiple->GetNumberOfTuples(),
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType v = begin; v < end; ++v)
      {
        const double weight = volume * (double(ms[3 * v]) + ms[3 * v + 1] + ms[3 * v + 2]);
        double f[3] = { 0, 0, 0 };
        if (weight > 0)
        {
          for (int c = 0; c < 3; ++c)
          {
            f[c] = d[3 * v + c] / weight;
          }
          const double length = std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
          const double shrink = length > 1.0 ? 1.0 / length : 1.0;
          for (double& x : f)
          {
            x = std::isfinite(x) ? x * shrink : 0.0;
          }
        }
        for (int c = 0; c < 3; ++c)
        {
          d[3 * v + c] = static_cast<float>(f[c]);
        }
      }
    });
  direction->Modified();
}
}

//------------------------------------------------------------------------------
bool vtkPhotonTracer::UploadAnalogScattering(Internals& run)
{
  Allocator& alloc = run.Alloc;
  this->UsedAnalogScattering = run.Analog;
  this->UsedScatteringOrders =
    !run.Analog ? 0 : (run.SplitOrders > 0 ? run.SplitOrders : EVERY_ORDER);
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
  const size_t bytes = voxels * MultipleAccumulatorsPerVoxel(run.SplitOrders) * sizeof(cl_long);
  run.MultipleFixed = alloc.Make(CL_MEM_READ_WRITE, bytes, nullptr, "S_ms accumulator");
  run.MultipleBytes = bytes;
  return run.AnisotropyBuffer && run.MultipleFixed &&
    run.Context->ZeroBuffer(run.MultipleFixed.Get(), bytes, this);
}

//------------------------------------------------------------------------------
bool vtkPhotonTracer::ResolveMultipleScattering(Internals& run)
{
  if (!run.Analog)
  {
    return true;
  }
  const size_t voxels = run.M.Voxels;
  // S_ms with its flux over its fluence (the orders the photons carried).
  run.Multiple->SetName(vtkRefractaLightingVolume::MultipleScatteringName());
  run.MultipleDirection->SetName(vtkRefractaLightingVolume::MultipleScatteringDirectionName());
  if (!this->ResolveDeposits(run, run.MultipleFixed.Get(), 0, run.MultipleFixed.Get(), 3, 6,
        run.Multiple, run.MultipleDirection, false))
  {
    return false;
  }
  FluxOverFluence(
    run.Multiple, run.MultipleDirection, run.M.Spacing[0] * run.M.Spacing[1] * run.M.Spacing[2]);
  // The device holds the raw sums: no copy of the array to hand on.
  run.Context->GetDeviceArrays()->Forget(run.MultipleDirection);
  if (run.SplitOrders == 0)
  {
    return true;
  }
  run.LatticeSource->SetName(vtkRefractaLightingVolume::MultipleScatteringSourceName());
  run.LatticeSourceDirection->SetName(
    vtkRefractaLightingVolume::MultipleScatteringSourceDirectionName());
  return this->ResolveDeposits(run, run.MultipleFixed.Get(), 6 * voxels, run.MultipleFixed.Get(),
    9 * voxels, 3, run.LatticeSource, run.LatticeSourceDirection);
}
