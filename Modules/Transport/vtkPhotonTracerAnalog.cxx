// The analog-scattering stage of vtkPhotonTracer (AnalogScattering with surfaces, and the
// first-collision split of ScatteringOrders): the medium's anisotropy and the accumulators on the
// device, and S_ms (and the split's lattice source) resolved and smoothed like Radiance into point
// arrays. The marching itself is in photon_trace.cl (REFRACTA_ANALOG).
#include "vtkPhotonTracer.h"
#include "vtkPhotonTracerInternals.h"

#include "vtkFloatArray.h"
#include "vtkRefractaLightingVolume.h"

using namespace vtkPhotonTracerDetail;

namespace
{
// Fixed-point accumulators per voxel: S_ms (3), and with the split the lattice's source (3) and
// its direction sums (3), in that order (photon_hand_to_lattice).
size_t AccumulatorsPerVoxel(int splitOrders)
{
  return splitOrders > 0 ? 9 : 3;
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
  const size_t bytes = voxels * AccumulatorsPerVoxel(run.SplitOrders) * sizeof(cl_long);
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
  run.Multiple->SetName(vtkRefractaLightingVolume::MultipleScatteringName());
  if (!this->ResolveDeposits(run, run.MultipleFixed.Get(), 0, nullptr, 0, 3, run.Multiple, nullptr))
  {
    return false;
  }
  if (run.SplitOrders == 0)
  {
    return true;
  }
  run.LatticeSource->SetName(vtkRefractaLightingVolume::MultipleScatteringSourceName());
  run.LatticeSourceDirection->SetName(
    vtkRefractaLightingVolume::MultipleScatteringSourceDirectionName());
  return this->ResolveDeposits(run, run.MultipleFixed.Get(), 3 * voxels, run.MultipleFixed.Get(),
    6 * voxels, 3, run.LatticeSource, run.LatticeSourceDirection);
}
