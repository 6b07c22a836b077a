// vtkPhotonTracer's last stages: the deposits resolved into the radiance and direction fields,
// smoothed and normalised on the device (Stage 4), and the output with its counters and energy
// books.
#include "vtkPhotonTracer.h"
#include "vtkPhotonTracerInternals.h"

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkOpenCLContext.h"
#include "vtkOpenCLDeviceArrays.h"
#include "vtkPointData.h"
#include "vtkRefractaLightingVolume.h"
#include "vtkTypeInt64Array.h"

#include "photon_tallies.cl" // the layout of the tallies and counters, shared with the kernels

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

using namespace vtkPhotonTracerDetail;

//------------------------------------------------------------------------------
// With S1 in lobes the photons deposit into their lobe's block only: the first block, all of S1,
// is their sum, made before anything reads it.
bool vtkPhotonTracer::SumLobeDeposits(Internals& run)
{
  if (run.Lobes < 2 || !run.M.Scatters)
  {
    return true;
  }
  vtkOpenCLContext* ctx = run.Context;
  cl_program program = ctx->GetProgram({ "refracta_common.cl", "radiance_smooth.cl" }, "", this);
  vtkOpenCLKernel sum =
    program ? ctx->CreateKernel(program, "radiance_sum_lobes", this) : vtkOpenCLKernel();
  const cl_ulong count = 6 * static_cast<cl_ulong>(run.M.Voxels);
  const cl_int lobes = run.Lobes;
  return sum &&
    ctx->Check(vtkOpenCLSetKernelArgs(sum.Get(), run.Deposits.Get(), count, lobes),
      "clSetKernelArg(radiance_sum_lobes)", this) &&
    Run1D(ctx, sum.Get(), count, "radiance_sum_lobes", this);
}

//------------------------------------------------------------------------------
// Stage 4: resolve, smooth, normalise.
bool vtkPhotonTracer::ResolveRadiance(Internals& run)
{
  const auto start = Clock::now();
  if (!this->SumLobeDeposits(run))
  {
    return false;
  }
  vtkFloatArray* radiance = run.Radiance;
  vtkFloatArray* direction = run.Direction;
  radiance->SetName(vtkRefractaLightingVolume::RadianceName());
  direction->SetName(vtkRefractaLightingVolume::RadianceDirectionName());
  if (!run.M.Scatters)
  {
    for (vtkFloatArray* a : { radiance, direction })
    {
      a->SetNumberOfComponents(3);
      a->SetNumberOfTuples(static_cast<vtkIdType>(run.M.Voxels));
      a->FillValue(0.0f);
    }
  }
  else if (!this->ResolveDeposits(
             run, run.Deposits.Get(), 0, run.Deposits.Get(), 3, 6, radiance, direction))
  {
    return false;
  }
  // S1's lobes: the blocks of six per voxel after the first.
  run.LobeRadiance.clear();
  run.LobeDirection.clear();
  for (int k = 0; run.M.Scatters && k < run.Lobes && run.Lobes > 1; ++k)
  {
    auto values = vtkSmartPointer<vtkFloatArray>::New();
    auto directions = vtkSmartPointer<vtkFloatArray>::New();
    values->SetName(vtkRefractaLightingVolume::RadianceLobeName(k));
    directions->SetName(vtkRefractaLightingVolume::RadianceLobeDirectionName(k));
    // No device copies kept: the view pass interleaves the lobes on the host.
    const size_t block = 6 * run.M.Voxels * (1 + k);
    if (!this->ResolveDeposits(run, run.Deposits.Get(), block, run.Deposits.Get(), block + 3, 6,
          values, directions, true, false))
    {
      return false;
    }
    run.LobeRadiance.push_back(values);
    run.LobeDirection.push_back(directions);
  }
  this->SmoothingSeconds = Seconds(start);
  this->PeakDeviceMemoryBytes = run.Alloc.Bytes;
  return true;
}

//------------------------------------------------------------------------------
bool vtkPhotonTracer::ResolveDeposits(Internals& run, cl_mem fixed, size_t offset,
  cl_mem directionFixed, size_t directionOffset, size_t stride, vtkFloatArray* values,
  vtkFloatArray* directions, bool unit, bool keep)
{
  Medium& m = run.M;
  vtkOpenCLContext* ctx = run.Context;
  Allocator& alloc = run.Alloc;
  const size_t voxels = m.Voxels;
  const size_t bytes = voxels * 3 * sizeof(float);
  const cl_uint voxelCount = static_cast<cl_uint>(voxels);
  for (vtkFloatArray* a : { values, directions })
  {
    if (a)
    {
      a->SetNumberOfComponents(3);
      a->SetNumberOfTuples(static_cast<vtkIdType>(voxels));
    }
  }
  cl_program smooth = ctx->GetProgram({ "refracta_common.cl", "radiance_smooth.cl" }, "", this);
  if (!smooth)
  {
    return false;
  }
  vtkOpenCLKernel resolve = ctx->CreateKernel(smooth, "radiance_resolve", this);
  vtkOpenCLKernel filter = ctx->CreateKernel(smooth, "radiance_smooth_axis", this);
  vtkOpenCLKernel normalize = ctx->CreateKernel(smooth, "radiance_normalize", this);
  vtkOpenCLKernel scale = ctx->CreateKernel(smooth, "radiance_scale_voxels", this);
  if (!resolve || !filter || !normalize || !scale)
  {
    return false;
  }
  // Deposits become power per unit volume (Physics.md); direction sums stay unnormalised until
  // after the smoothing, which then averages them weighted by power.
  const cl_float valueFactor =
    static_cast<cl_float>(1.0 / (run.Scale * m.Spacing[0] * m.Spacing[1] * m.Spacing[2]));
  const cl_float directionFactor = static_cast<cl_float>(1.0 / run.Scale);
  // One field: resolve it from `source` at `at`, smooth it, and read it into `out`; the buffer
  // it is read from is kept as `out`'s device copy with KeepDeviceCopies.
  auto field = [&](cl_mem source, size_t at, cl_float factor, vtkFloatArray* out, bool unit)
  {
    auto make = [&](bool result)
    {
      return alloc.Make(CL_MEM_READ_WRITE, bytes, nullptr, out->GetName(),
        result && keep && this->KeepDeviceCopies);
    };
    vtkOpenCLBuffer a = make(!this->Smoothing);
    vtkOpenCLBuffer b;
    if (this->Smoothing)
    {
      b = make(true);
    }
    const cl_ulong first = static_cast<cl_ulong>(at);
    const cl_uint strideLongs = static_cast<cl_uint>(stride);
    if (!a || (this->Smoothing && !b) ||
      !ctx->Check(vtkOpenCLSetKernelArgs(
                    resolve.Get(), source, first, strideLongs, factor, a.Get(), voxelCount),
        "clSetKernelArg(radiance_resolve)", this) ||
      !Run1D(ctx, resolve.Get(), voxels, "radiance_resolve", this))
    {
      return false;
    }
    // Deposits near opaque surfaces per unit of the volume they came from (the owned volumes):
    // every field, as each is a sum over the same pieces (the direction sums' smoothing then
    // weighs them as it weighs the values).
    if (run.NumberOfScaledVoxels > 0 &&
      (!ctx->Check(vtkOpenCLSetKernelArgs(scale.Get(), a.Get(), run.ScaledVoxels.Get(),
                     run.VolumeScales.Get(), run.NumberOfScaledVoxels),
         "clSetKernelArg(radiance_scale_voxels)", this) ||
        !Run1D(ctx, scale.Get(), run.NumberOfScaledVoxels, "radiance_scale_voxels", this)))
    {
      return false;
    }
    if (this->Smoothing && !this->SmoothAxes(run, filter.Get(), a.Get(), b.Get()))
    {
      return false;
    }
    const cl_mem result = this->Smoothing ? b.Get() : a.Get();
    if (unit &&
      (!ctx->Check(vtkOpenCLSetKernelArgs(normalize.Get(), result, voxelCount),
         "clSetKernelArg(radiance_normalize)", this) ||
        !Run1D(ctx, normalize.Get(), voxels, "radiance_normalize", this)))
    {
      return false;
    }
    if (!ctx->ReadBuffer(result, bytes, out->GetPointer(0), this))
    {
      return false;
    }
    out->Modified(); // its values are new: so is any copy of them
    if (keep && this->KeepDeviceCopies)
    {
      ctx->GetDeviceArrays()->Remember(out, result, this);
    }
    return true;
  };
  return field(fixed, offset, valueFactor, values, false) &&
    (!directions || field(directionFixed, directionOffset, directionFactor, directions, unit));
}

//------------------------------------------------------------------------------
bool vtkPhotonTracer::SmoothAxes(Internals& run, cl_kernel filter, cl_mem a, cl_mem b)
{
  // One launch per axis, a -> b -> a -> b: the separable 3x3x3 filter, its result in b.
  const Medium& m = run.M;
  const cl_int4 dims = Int4(m.Dims);
  const cl_int extinctionChannels = m.Attenuates ? m.ExtinctionChannels : 0;
  const double bias = std::min(this->SmoothingBias, 1e30);
  const cl_float biasLimit = static_cast<cl_float>(bias);
  // The optical depth up to which the plain filter's bias stays within biasLimit: cosh(tau) - 1
  // <= 2 biasLimit (the kernel evaluates cosh only beyond it).
  const cl_float tauLimit = static_cast<cl_float>(std::acosh(1.0 + 2.0 * bias));
  const cl_uint voxelCount = static_cast<cl_uint>(m.Voxels);
  // The links opaque surfaces cut (uploaded with the surfaces, UploadGridCuts).
  const cl_int cutLinks = run.Cuts ? 1 : 0;
  cl_mem from = a, to = b;
  for (cl_int axis = 0; axis < 3; ++axis)
  {
    const cl_float spacing = static_cast<cl_float>(m.Spacing[axis]);
    if (!run.Context->Check(
          vtkOpenCLSetKernelArgs(filter, from, run.ExtBuffer.Get(), extinctionChannels, dims, axis,
            spacing, biasLimit, tauLimit, run.CutLinksBuffer.Get(), cutLinks, to, voxelCount),
          "clSetKernelArg(radiance_smooth_axis)", this) ||
      !Run1D(run.Context, filter, m.Voxels, "radiance_smooth_axis", this))
    {
      return false;
    }
    std::swap(from, to);
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkPhotonTracer::WriteOutput(Internals& run, vtkImageData* output)
{
  const double scale = run.Scale;
  const std::vector<cl_long>& tally = run.Tally;
  const std::vector<cl_long>& count = run.Count;
  output->CopyStructure(run.Input);
  output->GetPointData()->AddArray(run.Radiance);
  output->GetPointData()->SetScalars(run.Radiance);
  output->GetPointData()->AddArray(run.Direction);
  for (size_t k = 0; k < run.LobeRadiance.size(); ++k)
  {
    output->GetPointData()->AddArray(run.LobeRadiance[k]);
    output->GetPointData()->AddArray(run.LobeDirection[k]);
  }
  vtkFieldData* fd = output->GetFieldData();
  auto addCount = [&](const char* name, long long value)
  {
    vtkNew<vtkTypeInt64Array> a;
    a->SetName(name);
    a->InsertNextValue(value);
    fd->AddArray(a);
  };
  addCount("NumberOfPhotons", static_cast<long long>(run.Photons));
  addCount("PhotonsMarched", count[PHOTON_COUNTER_MARCHED]);
  addCount("PhotonsMissed", count[PHOTON_COUNTER_MISSED]);
  addCount("TerminatedEscaped", count[PHOTON_COUNTER_ESCAPED]);
  addCount("TerminatedRoulette", count[PHOTON_COUNTER_ROULETTE]);
  addCount("TerminatedStepCap", count[PHOTON_COUNTER_STEP_CAP]);
  addCount("TerminatedInvalid", count[PHOTON_COUNTER_INVALID]);
  addCount("TotalSteps", count[PHOTON_COUNTER_STEPS]);
  addCount("TotalVoxelPieces", count[PHOTON_COUNTER_PIECES]);
  addCount("TerminatedSurface", count[PHOTON_COUNTER_SURFACE]);
  addCount("SurfaceHits", count[PHOTON_COUNTER_SURFACE_HITS]);
  addCount("InterfaceReflections", count[PHOTON_COUNTER_INTERFACE_REFLECTIONS]);
  addCount("InterfaceTransmissions", count[PHOTON_COUNTER_INTERFACE_TRANSMISSIONS]);
  addCount("RadianceLobes", static_cast<long long>(std::max<size_t>(1, run.LobeRadiance.size())));
  auto energy = [&](int t, int c) { return static_cast<double>(tally[3 * t + c]) / scale; };
  auto addEnergy = [&](const char* name, const std::array<double, 3>& v)
  {
    vtkNew<vtkDoubleArray> a;
    a->SetName(name);
    a->SetNumberOfComponents(3);
    a->InsertNextTuple(v.data());
    fd->AddArray(a);
  };
  std::array<double, 3> e[PHOTON_TALLY_ALL_BOOKS], remaining;
  for (int t = 0; t < PHOTON_TALLY_ALL_BOOKS; ++t)
  {
    for (int c = 0; c < 3; ++c)
    {
      e[t][c] = energy(t, c);
    }
  }
  for (int c = 0; c < 3; ++c)
  {
    remaining[c] =
      e[PHOTON_TALLY_REMAINING][c] + e[PHOTON_TALLY_KILLED][c] - e[PHOTON_TALLY_GAINED][c];
  }
  addEnergy("EnergyEmitted", e[PHOTON_TALLY_EMITTED]);
  addEnergy("EnergyAbsorbed", e[PHOTON_TALLY_ABSORBED]);
  addEnergy("EnergyEscaped", e[PHOTON_TALLY_ESCAPED]);
  addEnergy("EnergyScattered", e[PHOTON_TALLY_SCATTERED]);
  addEnergy("EnergyRemaining", remaining);
  addEnergy("EnergyRouletteKilled", e[PHOTON_TALLY_KILLED]);
  addEnergy("EnergyRouletteGained", e[PHOTON_TALLY_GAINED]);
  addEnergy("EnergySurface", e[PHOTON_TALLY_SURFACE]);
  addEnergy("EnergyInterfaceReflected", e[PHOTON_TALLY_INTERFACE_REFLECTED]);
  addEnergy("EnergyInterfaceTransmitted", e[PHOTON_TALLY_INTERFACE_TRANSMITTED]);
  this->WriteSurfaceOutput(run, output);
}
