// vtkLatticeBoltzmannSolver's convergence test: the probes (a sparse grid, and the voxels where
// the source is strongest) read on the device, and the largest relative change between two
// reads (split from vtkLatticeBoltzmannSolver.cxx, which sets the lattice up and iterates it).
#include "vtkLatticeBoltzmannSolver.h"
#include "vtkLatticeBoltzmannSolverInternals.h"

#include "vtkOpenCLContext.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

//------------------------------------------------------------------------------
bool vtkLatticeBoltzmannSolver::SetProbes(const std::vector<cl_uint>& extra)
{
  std::vector<cl_uint> probes = this->GridProbes;
  probes.insert(probes.end(), extra.begin(), extra.end());
  this->NumberOfProbes = probes.size();
  this->Probes = this->GetContext()->CreateBuffer(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
    probes.size() * sizeof(cl_uint), probes.data(), "LBL probes", this);
  this->PreviousProbes.assign(this->NumberOfProbes * 3, 0.0f);
  return static_cast<bool>(this->Probes);
}

//------------------------------------------------------------------------------
bool vtkLatticeBoltzmannSolver::UpdateSourceProbes()
{
  const size_t n = static_cast<size_t>(this->NumberOfVoxels);
  std::vector<float>& planes = this->HostSource; // its first 3 n floats: S1 per channel
  planes.resize(std::max(planes.size(), 3 * n));
  return this->GetContext()->ReadBuffer(
           this->Source.Get(), 3 * n * sizeof(float), planes.data(), this) &&
    this->ChooseSourceProbes(planes.data(), n, 1);
}

//------------------------------------------------------------------------------
bool vtkLatticeBoltzmannSolver::ChooseSourceProbes(
  const float* s1, size_t channelStride, size_t voxelStride)
{
  // The sparse grid of probes can miss a small source entirely (light from a point source needs
  // as many steps as its Manhattan distance to reach a probe), which would read as "converged"
  // at once. The voxels with the strongest source are probes too; a source that is zero
  // everywhere is known to give a zero field.
  const size_t n = static_cast<size_t>(this->NumberOfVoxels);
  std::vector<std::pair<float, cl_uint>> strongest;
  for (size_t v = 0; s1 && v < n; ++v)
  {
    const float* at = s1 + v * voxelStride;
    const float total = at[0] + at[channelStride] + at[2 * channelStride];
    if (total > 0 && (strongest.size() < MaxSourceProbes || total > strongest.back().first))
    {
      if (strongest.size() == MaxSourceProbes)
      {
        strongest.pop_back();
      }
      strongest.emplace_back(total, static_cast<cl_uint>(v));
      std::sort(strongest.begin(), strongest.end(),
        [](const std::pair<float, cl_uint>& a, const std::pair<float, cl_uint>& b)
        { return a.first > b.first; });
    }
  }
  this->SourceIsZero = strongest.empty();
  std::vector<cl_uint> extra;
  for (const auto& e : strongest)
  {
    extra.push_back(e.second);
  }
  if (!this->SetProbes(extra))
  {
    return false;
  }
  // Keep the comparison baseline of the grid probes; the new ones start from the state now.
  std::vector<float> now;
  if (this->StepKernel && this->ReadProbes(now))
  {
    this->PreviousProbes = now;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkLatticeBoltzmannSolver::ReadProbes(std::vector<float>& values)
{
  vtkOpenCLContext* context = this->GetContext();
  const cl_int4 dims = { { this->Dims[0], this->Dims[1], this->Dims[2], 0 } };
  const cl_uint count = static_cast<cl_uint>(this->NumberOfProbes);
  const size_t global = count;
  values.resize(this->NumberOfProbes * 3);
  cl_mem state = this->UseBlocks() ? this->State[0].Get() : this->State[this->Current].Get();
  return context->Check(vtkOpenCLSetKernelArgs(this->ProbeKernel.Get(), state, this->Probes.Get(),
                          this->ProbeValues.Get(), count, dims),
           "clSetKernelArg(lbl_probes)", this) &&
    context->RunKernel(this->ProbeKernel.Get(), 1, &global, nullptr, "lbl_probes", this) &&
    context->ReadBuffer(
      this->ProbeValues.Get(), values.size() * sizeof(float), values.data(), this);
}

//------------------------------------------------------------------------------
bool vtkLatticeBoltzmannSolver::CheckConvergence(int stepsSinceLast, double& residual)
{
  if (!this->BuildKernels())
  {
    return false;
  }
  std::vector<float> values;
  if (!this->ReadProbes(values))
  {
    return false;
  }
  double peak = 0;
  for (size_t k = 0; k < values.size(); ++k)
  {
    if (!std::isfinite(values[k]))
    {
      vtkErrorMacro("The lattice density became non-finite ("
        << values[k] << ") at probe " << k / 3 << " after " << this->Iterations << " steps.");
      return false;
    }
    peak = std::max(peak, std::abs(double(values[k])));
  }
  // Largest relative change of any probe and channel; probes darker than ProbeFloor times the
  // brightest are measured relative to that floor (they hardly matter, and deep in an absorbing
  // medium they may never stop changing in relative terms at float precision). A sum over the
  // probes instead would be dominated by the bright source voxels, which settle long before the
  // far field does.
  double change = 0;
  const double floor = ProbeFloor * peak;
  for (size_t k = 0; k < values.size(); ++k)
  {
    const double now = values[k];
    const double delta = std::abs(now - double(this->PreviousProbes[k]));
    if (delta > 0)
    {
      change = std::max(change, delta / std::max(std::abs(now), floor));
    }
  }
  this->PreviousProbes = values;
  // All probes dark: converged only when there is no source at all (light still on its way to
  // the probes otherwise).
  residual = peak > 0 ? change / std::max(1, stepsSinceLast)
                      : (this->SourceIsZero ? 0.0 : std::numeric_limits<double>::infinity());
  return true;
}
