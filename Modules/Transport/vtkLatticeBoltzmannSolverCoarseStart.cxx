// vtkLatticeBoltzmannSolver: the coarse start (a cascadic multigrid start). A Solve() from a zero
// state first solves the problem on a grid of half the resolution, then starts from that grid's
// steady state; a warm Solve() adds the change of the coarse grid's steady state to the last
// one instead. See CoarseStart and CoarseWarmStart in the header and lbl_restrict_source /
// lbl_prolong_state in Kernels/lbl.cl.
#include "vtkLatticeBoltzmannSolver.h"

#include "vtkCommand.h"
#include "vtkLatticeBoltzmannSolverInternals.h"
#include "vtkObjectFactory.h"
#include "vtkOpenCLContext.h"
#include "vtkSMPTools.h"

#include <algorithm>

namespace
{
// Share of a Solve()'s progress given to its coarse start (a coarse step costs 1/8 of a fine one).
constexpr double CoarseProgressShare = 0.15;

// Forwards the coarse solver's progress to the fine one (scaled into its first share) and the
// fine solver's abort request, set by the fine solver's observers, to the coarse one.
class vtkCoarseStartProgress : public vtkCommand
{
public:
  static vtkCoarseStartProgress* New();
  vtkLatticeBoltzmannSolver* Fine = nullptr;
  double* Progress = nullptr;
  void Execute(vtkObject* caller, unsigned long, void* callData) override
  {
    const double coarse = callData ? *static_cast<double*>(callData) : 0.0;
    *this->Progress = std::max(*this->Progress, CoarseProgressShare * coarse);
    this->Fine->InvokeEvent(vtkCommand::ProgressEvent, this->Progress);
    if (this->Fine->GetAbortSolve())
    {
      static_cast<vtkLatticeBoltzmannSolver*>(caller)->SetAbortSolve(true);
    }
  }
};
vtkStandardNewMacro(vtkCoarseStartProgress);
}

//------------------------------------------------------------------------------
void vtkLatticeBoltzmannSolver::RestrictMedium(const int dims[3], const double spacing[3],
  const float* extinction, const float* albedo, const float* anisotropy)
{
  this->CoarseExtinction.clear();
  this->CoarseAlbedo.clear();
  this->CoarseAnisotropy.clear();
  this->CoarseInitialized = false;
  if (!this->CoarseStartApplies(dims))
  {
    return;
  }
  for (int a = 0; a < 3; ++a)
  {
    this->CoarseDims[a] = (dims[a] + 1) / 2;
    this->CoarseSpacing[a] = 2.0 * spacing[a];
  }
  const int cx = this->CoarseDims[0], cy = this->CoarseDims[1], cz = this->CoarseDims[2];
  const size_t nc = size_t(cx) * cy * cz;
  this->CoarseExtinction.assign(3 * nc, 0.0f);
  this->CoarseAlbedo.assign(3 * nc, 0.0f);
  this->CoarseAnisotropy.assign(nc, 0.0f);
  // Per 2x2x2 block (the children that exist): mean extinction, albedo weighted by extinction
  // (the scattering coefficients average), g weighted by scattering; the same clamps as the
  // coefficients of Initialize().
  vtkSMPTools::For(0, cz,
    [&](int first, int last)
    {
      for (int z = first; z < last; ++z)
      {
        for (int y = 0; y < cy; ++y)
        {
          for (int x = 0; x < cx; ++x)
          {
            double st[3] = { 0, 0, 0 }, ss[3] = { 0, 0, 0 }, aSum[3] = { 0, 0, 0 };
            double gSum = 0, gWeighted = 0, gWeight = 0;
            int count = 0;
            for (int fz = 2 * z; fz < std::min(2 * z + 2, dims[2]); ++fz)
            {
              for (int fy = 2 * y; fy < std::min(2 * y + 2, dims[1]); ++fy)
              {
                for (int fx = 2 * x; fx < std::min(2 * x + 2, dims[0]); ++fx)
                {
                  const size_t v = fx + size_t(dims[0]) * (fy + size_t(dims[1]) * fz);
                  const double g =
                    anisotropy ? std::min(0.9999, std::max(-0.9999, double(anisotropy[v]))) : 0.0;
                  double scattering = 0;
                  for (int ch = 0; ch < 3; ++ch)
                  {
                    const double t =
                      extinction ? std::max(0.0, double(extinction[v * 3 + ch])) : 0.0;
                    const double a =
                      albedo ? std::min(1.0, std::max(0.0, double(albedo[v * 3 + ch]))) : 0.0;
                    st[ch] += t;
                    ss[ch] += t * a;
                    aSum[ch] += a;
                    scattering += t * a;
                  }
                  gSum += g;
                  gWeighted += scattering * g;
                  gWeight += scattering;
                  ++count;
                }
              }
            }
            const size_t vc = x + size_t(cx) * (y + size_t(cy) * z);
            for (int ch = 0; ch < 3; ++ch)
            {
              this->CoarseExtinction[3 * vc + ch] = static_cast<float>(st[ch] / count);
              this->CoarseAlbedo[3 * vc + ch] =
                static_cast<float>(st[ch] > 0 ? ss[ch] / st[ch] : aSum[ch] / count);
            }
            this->CoarseAnisotropy[vc] =
              static_cast<float>(gWeight > 0 ? gWeighted / gWeight : gSum / count);
          }
        }
      }
    });
}

//------------------------------------------------------------------------------
bool vtkLatticeBoltzmannSolver::PrepareCoarseLevel(bool& keepState)
{
  if (!this->Coarse)
  {
    this->Coarse = vtkSmartPointer<vtkLatticeBoltzmannSolver>::New();
  }
  vtkLatticeBoltzmannSolver* coarse = this->Coarse;
  const int probeSpacing = std::max(1, this->ProbeSpacing / 2); // the same probes' density
  // Settings that Initialize() reads need a new coarse grid; the others apply as they are.
  const bool initialize = !this->CoarseInitialized || coarse->Lattice != this->Lattice ||
    coarse->CollisionModel != this->CollisionModel || coarse->ProbeSpacing != probeSpacing ||
    coarse->CoarseStart != this->CoarseStart ||
    coarse->MinimumCoarseDimension != this->MinimumCoarseDimension ||
    coarse->Context != this->GetContext();
  coarse->SetContext(this->GetContext());
  coarse->SetLattice(this->Lattice);
  coarse->SetCollisionModel(this->CollisionModel);
  coarse->SetProbeSpacing(probeSpacing);
  coarse->SetCoarseStart(this->CoarseStart);
  coarse->SetCoarseWarmStart(this->CoarseWarmStart);
  coarse->SetMinimumCoarseDimension(this->MinimumCoarseDimension);
  coarse->SetBlockSize(this->BlockSize);
  coarse->SetBlockPolicy(this->BlockPolicy);
  coarse->SetStepsPerExchange(this->StepsPerExchange);
  coarse->SetBoundary(this->Boundary);
  coarse->SetSourceDistribution(this->SourceDistribution);
  coarse->SetTolerance(this->Tolerance);
  coarse->SetCheckInterval(this->CheckInterval);
  coarse->SetMaximumIterations(this->MaximumIterations);
  if (initialize)
  {
    keepState = false;
    this->CoarseInitialized = coarse->Initialize(this->CoarseDims, this->CoarseSpacing,
      this->CoarseExtinction.data(), this->CoarseAlbedo.data(), this->CoarseAnisotropy.data());
    if (!this->CoarseInitialized)
    {
      vtkErrorMacro("The coarse start's grid "
        << this->CoarseDims[0] << " x " << this->CoarseDims[1] << " x " << this->CoarseDims[2]
        << " could not be set up (see the previous "
           "message); turn CoarseStart off to go without.");
      return false;
    }
    return true;
  }
  // A warm solve of its own keeps the state (its source is restricted anew either way).
  return keepState ? coarse->ClearSource() : coarse->ResetState();
}

//------------------------------------------------------------------------------
bool vtkLatticeBoltzmannSolver::RunCoarseStart(double& progress, bool correct)
{
  if (!this->PrepareCoarseLevel(correct))
  {
    return false;
  }
  vtkLatticeBoltzmannSolver* coarse = this->Coarse;
  vtkOpenCLContext* context = this->GetContext();
  // The correction needs the coarse level's last steady state after it has moved on.
  const size_t coarseBytes =
    size_t(coarse->Lattice) * 3 * static_cast<size_t>(coarse->NumberOfVoxels) * sizeof(float);
  if (correct)
  {
    if (vtkOpenCLBufferBytes(this->CoarseBefore.Get()) < coarseBytes)
    {
      this->CoarseBefore = context->CreateBuffer(
        CL_MEM_READ_WRITE, coarseBytes, nullptr, "LBL coarse state before the correction", this);
    }
    if (!this->CoarseBefore ||
      !context->CopyBuffer(coarse->CurrentState(), this->CoarseBefore.Get(), coarseBytes, this))
    {
      return false;
    }
  }
  const cl_int4 fdims = { { this->Dims[0], this->Dims[1], this->Dims[2], 0 } };
  const cl_int4 cdims = { { this->CoarseDims[0], this->CoarseDims[1], this->CoarseDims[2], 0 } };
  const size_t cglobal[3] = { size_t(cdims.s[0]), size_t(cdims.s[1]), size_t(cdims.s[2]) };
  const cl_int planes = 6;
  if (!context->Check(vtkOpenCLSetKernelArgs(this->RestrictKernel.Get(), this->Source.Get(),
                        coarse->Source.Get(), fdims, cdims, planes),
        "clSetKernelArg(lbl_restrict_source)", this) ||
    !context->RunKernel(
      this->RestrictKernel.Get(), 3, cglobal, nullptr, "lbl_restrict_source", this) ||
    !coarse->UpdateSourceProbes())
  {
    return false;
  }

  vtkNew<vtkCoarseStartProgress> forward;
  forward->Fine = this;
  forward->Progress = &progress;
  const unsigned long observer = coarse->AddObserver(vtkCommand::ProgressEvent, forward);
  const bool solved = coarse->Solve();
  coarse->RemoveObserver(observer);
  if (!solved)
  {
    vtkErrorMacro("The coarse start's solve failed (see the previous message); turn CoarseStart "
                  "off to go without.");
    return false;
  }
  this->CoarseStartSteps = coarse->Iterations + coarse->CoarseStartSteps;
  this->CoarseStartCost = (coarse->Iterations + coarse->CoarseStartCost) *
    static_cast<double>(coarse->NumberOfVoxels) / static_cast<double>(this->NumberOfVoxels);
  if (coarse->Aborted)
  {
    this->Aborted = true;
    return true;
  }

  // A coarse step lasts two fine ones: the ratio of the two grids' steady states in vacuum.
  const float maxRatio = 2.0f;
  const size_t global[3] = { size_t(fdims.s[0]), size_t(fdims.s[1]), size_t(fdims.s[2]) };
  const size_t local[3] = { refracta_lbm::LocalRow(this->Dims[0]), 1, 1 };
  const cl_mem before = correct ? this->CoarseBefore.Get() : coarse->CurrentState(); // unread
  const cl_int correction = correct ? 1 : 0;
  if (!context->Check(vtkOpenCLSetKernelArgs(this->ProlongKernel.Get(), coarse->CurrentState(),
                        before, coarse->Coefficients.Get(), this->CurrentState(),
                        this->Coefficients.Get(), fdims, cdims, maxRatio, correction),
        "clSetKernelArg(lbl_prolong_state)", this) ||
    !context->RunKernel(this->ProlongKernel.Get(), 3, global, local, "lbl_prolong_state", this))
  {
    return false;
  }
  this->LastSolveCorrected = correct;
  // lbl_block reads the entries fed by neighbouring blocks from the interface, not the state.
  if ((this->UseBlocks() && !this->ExchangeStateAndInterface(true)) || !context->Finish(this))
  {
    return false;
  }
  this->StateIsZero = false;
  return true;
}
