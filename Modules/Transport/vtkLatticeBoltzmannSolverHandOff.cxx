// The lattice's side of the lighting volume's device hand-off (vtkOpenCLDeviceArrays): its
// source from point arrays, taken from their device copies where the context holds them, and its
// S_ms into a point array whose device copy it keeps for the view pass, and S_ms's direction.
#include "vtkLatticeBoltzmannSolver.h"
#include "vtkLatticeBoltzmannSolverInternals.h"

#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkOpenCLContext.h"
#include "vtkOpenCLDeviceArrays.h"
#include "vtkPointData.h"
#include "vtkRefractaLightingVolume.h"
#include "vtkRefractaMedium.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace
{
// Whether `a` is null (when `optional`) or has 3 components and `n` tuples; else says why.
bool HasVoxelTriples(vtkDataArray* a, vtkIdType n, bool optional, vtkObject* reporter)
{
  if ((!a && optional) || (a && a->GetNumberOfComponents() == 3 && a->GetNumberOfTuples() == n))
  {
    return true;
  }
  vtkErrorWithObjectMacro(reporter,
    "The lattice's source and output arrays need 3 components and one tuple per voxel ("
      << n << "); `" << (a && a->GetName() ? a->GetName() : "(missing)") << "` has "
      << (a ? a->GetNumberOfComponents() : 0) << " x " << (a ? a->GetNumberOfTuples() : 0) << ".");
  return false;
}
}

//------------------------------------------------------------------------------
bool vtkLatticeBoltzmannSolver::SetSourceArrays(vtkDataArray* s1, vtkDataArray* direction)
{
  if (!this->Source)
  {
    vtkErrorMacro("Initialize() the solver with a grid before setting a source.");
    return false;
  }
  const vtkIdType n = this->NumberOfVoxels;
  if (!HasVoxelTriples(s1, n, false, this) || !HasVoxelTriples(direction, n, true, this))
  {
    return false;
  }
  vtkOpenCLContext* context = this->GetContext();
  vtkOpenCLDeviceArrays* copies = context->GetDeviceArrays();
  // (Looked up only while both may be there: a hit is an upload saved.)
  const cl_mem deviceDirection = direction ? copies->Find(direction) : nullptr;
  const cl_mem deviceS1 = !direction || deviceDirection ? copies->Find(s1) : nullptr;
  if (!deviceS1 || (direction && !deviceDirection))
  {
    // No device copy: read the arrays and upload them.
    std::vector<float> values, directions;
    vtkRefractaMedium::ReadArray(s1, n, 3, 0.0f, values);
    if (direction)
    {
      vtkRefractaMedium::ReadArray(direction, n, 3, 0.0f, directions);
    }
    return this->SetSource(values.data(), direction ? directions.data() : nullptr);
  }
  if (!this->BuildKernels())
  {
    return false;
  }
  // The planes are arranged on the device; the probes are chosen from the host's values of the
  // same array (no read back).
  const cl_uint count = static_cast<cl_uint>(n);
  const cl_int hasDirection = deviceDirection ? 1 : 0;
  const size_t global = static_cast<size_t>(n);
  const size_t local = 64;
  if (!context->Check(
        vtkOpenCLSetKernelArgs(this->FieldSourceKernel.Get(), deviceS1,
          deviceDirection ? deviceDirection : deviceS1, hasDirection, this->Source.Get(), count),
        "clSetKernelArg(lbl_source_from_fields)", this) ||
    !context->RunKernel(
      this->FieldSourceKernel.Get(), 1, &global, &local, "lbl_source_from_fields", this))
  {
    return false;
  }
  // Only float arrays have device copies (vtkOpenCLDeviceArrays::Remember).
  const float* host = vtkFloatArray::FastDownCast(s1)->GetPointer(0);
  return this->ChooseSourceProbes(host, 1, 3);
}

//------------------------------------------------------------------------------
bool vtkLatticeBoltzmannSolver::SetSourceFromLighting(vtkImageData* lighting)
{
  if (!lighting)
  {
    vtkErrorMacro("SetSourceFromLighting() needs a lighting volume.");
    return false;
  }
  if (vtkRefractaLightingVolume::LatticeSourceHasVolumeCaustic(lighting))
  {
    // The bricks' S1 goes back into its voxels on the host.
    std::vector<float> source, direction;
    vtkRefractaLightingVolume::ReadLatticeSource(lighting, source, direction);
    return this->SetSource(source.data(), direction.data());
  }
  vtkPointData* pd = lighting->GetPointData();
  vtkDataArray* s1 = pd->GetArray(vtkRefractaLightingVolume::LatticeSourceName(lighting));
  if (!s1)
  {
    vtkErrorMacro("The lighting volume has no point array `"
      << vtkRefractaLightingVolume::LatticeSourceName(lighting)
      << "` (the lattice's source, 3 components of power per unit volume).");
    return false;
  }
  return this->SetSourceArrays(
    s1, pd->GetArray(vtkRefractaLightingVolume::LatticeSourceDirectionName(lighting)));
}

//------------------------------------------------------------------------------
bool vtkLatticeBoltzmannSolver::ComputeMultipleScattering(vtkFloatArray* out, vtkDataArray* addend)
{
  const vtkIdType n = this->NumberOfVoxels;
  if (!out)
  {
    vtkErrorMacro("ComputeMultipleScattering() needs an output array.");
    return false;
  }
  if (!HasVoxelTriples(addend, n, true, this))
  {
    return false;
  }
  vtkOpenCLContext* context = this->GetContext();
  vtkOpenCLDeviceArrays* copies = context->GetDeviceArrays();
  copies->ForgetOwner(this); // the last result's copy goes before the next is allocated
  vtkOpenCLBuffer result;
  if (!this->ComputeMultipleScatteringOnDevice(result))
  {
    return false;
  }
  const cl_mem deviceAddend = addend ? copies->Find(addend) : nullptr;
  const cl_ulong values = 3 * static_cast<cl_ulong>(n);
  const size_t global = static_cast<size_t>(values);
  const size_t local = 64;
  if (deviceAddend &&
    (!context->Check(
       vtkOpenCLSetKernelArgs(this->AddKernel.Get(), result.Get(), deviceAddend, values),
       "clSetKernelArg(lbl_add)", this) ||
      !context->RunKernel(this->AddKernel.Get(), 1, &global, &local, "lbl_add", this)))
  {
    return false;
  }
  out->SetNumberOfComponents(3);
  out->SetNumberOfTuples(n);
  if (!context->ReadBuffer(result.Get(), global * sizeof(float), out->GetPointer(0), this))
  {
    return false;
  }
  out->Modified();
  if (addend && !deviceAddend)
  {
    vtkRefractaLightingVolume::AddValues(addend, out);
    return true; // the device holds only the lattice's part: no copy of `out`
  }
  if (this->KeepDeviceCopies)
  {
    copies->Remember(out, result.Get(), this);
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkLatticeBoltzmannSolver::ComputeMultipleScatteringDirection(
  vtkFloatArray* out, vtkDataArray* total, vtkDataSet* photonOrders)
{
  const vtkIdType n = this->NumberOfVoxels;
  if (!out)
  {
    vtkErrorMacro("ComputeMultipleScatteringDirection() needs an output array.");
    return false;
  }
  vtkPointData* pd = photonOrders ? photonOrders->GetPointData() : nullptr;
  vtkDataArray* photons =
    pd ? pd->GetArray(vtkRefractaLightingVolume::MultipleScatteringName()) : nullptr;
  vtkDataArray* photonDirection =
    pd ? pd->GetArray(vtkRefractaLightingVolume::MultipleScatteringDirectionName()) : nullptr;
  if (photonOrders && (!photons || !total))
  {
    vtkErrorMacro("The split's direction needs the photons' `"
      << vtkRefractaLightingVolume::MultipleScatteringName()
      << "` and the total S_ms (ComputeMultipleScattering()'s output).");
    return false;
  }
  if (!HasVoxelTriples(total, n, true, this) || !HasVoxelTriples(photons, n, true, this) ||
    !HasVoxelTriples(photonDirection, n, true, this))
  {
    return false;
  }
  vtkOpenCLBuffer result;
  if (!this->RunVoxelReadOut(
        this->ScatteredFluxKernel, "lbl_scattered_flux", "LBL S_ms direction", result))
  {
    return false;
  }
  out->SetNumberOfComponents(3);
  out->SetNumberOfTuples(n);
  if (!this->GetContext()->ReadBuffer(
        result.Get(), 3 * static_cast<size_t>(n) * sizeof(float), out->GetPointer(0), this))
  {
    return false;
  }
  if (photons)
  {
    MergePhotonDirection(out, total, photons, photonDirection);
  }
  out->Modified();
  if (!photons && this->KeepDeviceCopies)
  {
    this->GetContext()->GetDeviceArrays()->Remember(out, result.Get(), this);
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkLatticeBoltzmannSolver::MergePhotonDirection(
  vtkFloatArray* lattice, vtkDataArray* total, vtkDataArray* photons, vtkDataArray* photonDirection)
{
  float* f = lattice->GetPointer(0);
  vtkSMPTools::For(0, lattice->GetNumberOfTuples(),
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType v = begin; v < end; ++v)
      {
        double all = 0, mine = 0;
        for (int c = 0; c < 3; ++c)
        {
          all += total->GetComponent(v, c);
          mine += photons->GetComponent(v, c);
        }
        // The lattice's part is what the total holds beyond the photons' (>= 0 up to rounding).
        const double theirs = std::max(0.0, all - mine);
        const double sum = theirs + mine;
        for (int c = 0; c < 3; ++c)
        {
          const double p = photonDirection ? photonDirection->GetComponent(v, c) : 0.0;
          const double merged = sum > 0 ? (theirs * f[3 * v + c] + mine * p) / sum : 0.0;
          f[3 * v + c] = std::isfinite(merged) ? static_cast<float>(merged) : 0.0f;
        }
      }
    });
}
