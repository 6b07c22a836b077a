// vtkLatticeBoltzmannSolver: the energy books (total density, the next step's absorption), the
// multiple-scattering read-out, and the analytic collision probability, decay and diffusion
// lengths of the lattice (split from vtkLatticeBoltzmannSolver.cxx, which sets the lattice up and
// iterates it).
#include "vtkLatticeBoltzmannSolver.h"
#include "vtkLatticeBoltzmannSolverInternals.h"

#include "vtkOpenCLContext.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

using refracta_lbm::Cx;
using refracta_lbm::Cy;
using refracta_lbm::Cz;
using refracta_lbm::LocalRow;

//------------------------------------------------------------------------------
bool vtkLatticeBoltzmannSolver::ReadState(std::vector<float>& state)
{
  if (!this->BuildKernels())
  {
    return false;
  }
  state.resize(size_t(this->Lattice) * 3 * this->NumberOfVoxels);
  return this->GetContext()->ReadBuffer(
    this->CurrentState(), state.size() * sizeof(float), state.data(), this);
}

//------------------------------------------------------------------------------
bool vtkLatticeBoltzmannSolver::ComputeTotalDensity(double total[3])
{
  std::vector<float> state;
  if (!this->ReadState(state))
  {
    return false;
  }
  const size_t n = static_cast<size_t>(this->NumberOfVoxels);
  for (int ch = 0; ch < 3; ++ch)
  {
    total[ch] = 0;
    for (int i = 0; i < this->Lattice; ++i)
    {
      const float* plane = state.data() + (size_t(i) * 3 + ch) * n;
      for (size_t v = 0; v < n; ++v)
      {
        total[ch] += plane[v];
      }
    }
  }
  if (this->UseBlocks() && this->StepsPerExchange > 1)
  {
    // The state holds 1/m of each interface value (the next substep's share); the rest is in
    // transit.
    cl_mem iface = this->Interface[this->InterfaceParity].Get();
    const size_t bytes = vtkOpenCLBufferBytes(iface);
    std::vector<float> values(bytes / sizeof(float));
    if (!this->GetContext()->ReadBuffer(iface, bytes, values.data(), this))
    {
      return false;
    }
    const double rest = 1.0 - 1.0 / this->StepsPerExchange;
    for (size_t k = 0; k < values.size(); ++k)
    {
      total[k % 3] += rest * values[k];
    }
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkLatticeBoltzmannSolver::ComputeAbsorbedNextStep(double absorbed[3])
{
  std::vector<float> state;
  if (!this->ReadState(state))
  {
    return false;
  }
  const size_t n = static_cast<size_t>(this->NumberOfVoxels);
  const size_t nclass = this->ClassLengths.size();
  const float* coef = this->HostCoefficients.data();
  for (int ch = 0; ch < 3; ++ch)
  {
    absorbed[ch] = 0;
    for (size_t v = 0; v < n; ++v)
    {
      const double a = coef[(nclass * 3 + ch) * n + v];
      double collided = 0;
      for (int i = 0; i < this->Lattice; ++i)
      {
        const double t = coef[(this->DirectionClass[i] * 3 + ch) * n + v];
        collided += (1.0 - t) * state[(size_t(i) * 3 + ch) * n + v];
      }
      absorbed[ch] += (1.0 - a) * collided;
    }
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkLatticeBoltzmannSolver::ComputeMultipleScattering(float* out)
{
  vtkOpenCLBuffer result;
  return this->ComputeMultipleScatteringOnDevice(result) &&
    this->GetContext()->ReadBuffer(
      result.Get(), 3 * static_cast<size_t>(this->NumberOfVoxels) * sizeof(float), out, this);
}

//------------------------------------------------------------------------------
bool vtkLatticeBoltzmannSolver::ComputeMultipleScatteringOnDevice(vtkOpenCLBuffer& result)
{
  return this->RunVoxelReadOut(this->ScatteredKernel, "lbl_scattered", "LBL S_ms", result);
}

//------------------------------------------------------------------------------
bool vtkLatticeBoltzmannSolver::RunVoxelReadOut(
  vtkOpenCLKernel& kernel, const char* name, const char* bufferName, vtkOpenCLBuffer& result)
{
  if (!this->BuildKernels())
  {
    return false;
  }
  vtkOpenCLContext* context = this->GetContext();
  const size_t n = static_cast<size_t>(this->NumberOfVoxels);
  result =
    context->CreateBuffer(CL_MEM_READ_WRITE, 3 * n * sizeof(float), nullptr, bufferName, this);
  if (!result)
  {
    return false;
  }
  const cl_int4 dims = { { this->Dims[0], this->Dims[1], this->Dims[2], 0 } };
  const size_t global[3] = { size_t(this->Dims[0]), size_t(this->Dims[1]), size_t(this->Dims[2]) };
  const size_t local[3] = { LocalRow(this->Dims[0]), 1, 1 };
  return context->Check(vtkOpenCLSetKernelArgs(kernel.Get(), this->CurrentState(),
                          this->Coefficients.Get(), result.Get(), dims),
           (std::string("clSetKernelArg(") + name + ")").c_str(), this) &&
    context->RunKernel(kernel.Get(), 3, global, local, name, this);
}

//------------------------------------------------------------------------------
double vtkLatticeBoltzmannSolver::CollisionProbability(
  int lattice, int model, double sigmaT, double albedo, double g, double len, double h)
{
  if (model == EXPONENTIAL_COLLISION)
  {
    return 1.0 - std::exp(-sigmaT * len);
  }
  const double s2 = lattice == D3Q18 ? 5.0 / 9.0 : 1.0 / 3.0;
  const double tau = sigmaT * h;
  const double k = 1.0 - albedo * g;
  const double p = (-3 * s2 * tau * tau * k +
                     std::sqrt(9 * s2 * s2 * std::pow(tau, 4) * k * k + 48 * s2 * tau * tau)) /
    4;
  return std::min(1.0, std::max(0.0, p));
}

//------------------------------------------------------------------------------
double vtkLatticeBoltzmannSolver::LatticeDecayLength(
  int lattice, int model, double sigmaT, double albedo, double g, double h)
{
  if (!(albedo < 1.0) || (lattice != 6 && lattice != 18) || !(h > 0))
  {
    return 0.0;
  }
  if (g < 0)
  {
    return LatticeDiffusionLength(lattice, model, sigmaT, albedo, g, h);
  }
  const int q = lattice;
  double rho[18], s[18];
  for (int j = 0; j < q; ++j)
  {
    const double len = h * std::sqrt(double(Cx[j] * Cx[j] + Cy[j] * Cy[j] + Cz[j] * Cz[j]));
    const double p = CollisionProbability(lattice, model, sigmaT, albedo, g, len, h);
    rho[j] = 1 - p + albedo * p * g;
    s[j] = albedo * p * (1 - g) / q;
  }
  auto f = [&](double kappa)
  {
    double sum = 0;
    for (int j = 0; j < q; ++j)
    {
      sum += s[j] / (std::exp(-kappa * h * Cx[j]) - rho[j]);
    }
    return sum - 1.0;
  };
  // The decaying mode lies below the first pole, exp(-kappa h) = rho for directions along +x.
  double hi = 1e6 / h;
  for (int j = 0; j < q; ++j)
  {
    if (Cx[j] == 1 && rho[j] > 0)
    {
      hi = std::min(hi, -std::log(rho[j]) / h);
    }
  }
  double lo = 0;
  if (f(lo) >= 0)
  {
    return 0.0;
  }
  for (int it = 0; it < 200; ++it)
  {
    const double mid = 0.5 * (lo + hi);
    if (f(mid) < 0)
    {
      lo = mid;
    }
    else
    {
      hi = mid;
    }
  }
  return 1.0 / (0.5 * (lo + hi));
}

//------------------------------------------------------------------------------
double vtkLatticeBoltzmannSolver::LatticeDiffusionLength(
  int lattice, int model, double sigmaT, double albedo, double g, double h)
{
  // Uses the axis step's probability (all directions share it in the diffusion-matched model).
  const double p = CollisionProbability(lattice, model, sigmaT, albedo, g, h, h);
  const double rho = 1 - p * (1 - albedo * g);
  const double loss = (1 - albedo) * p;
  const double s2 = lattice == D3Q18 ? 5.0 / 9.0 : 1.0 / 3.0;
  if (!(loss > 0))
  {
    return 0.0;
  }
  return h * std::sqrt(s2 * (1 + rho) / (2 * (1 - rho) * loss));
}
