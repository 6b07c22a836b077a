#include "vtkLatticeBoltzmannSolver.h"
#include "vtkLatticeBoltzmannSolverInternals.h"

#include "vtkCommand.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpenCLContext.h"
#include "vtkOpenCLMemoryPlan.h"
#include "vtkRefractaHostThreads.h"
#include "vtkRefractaSettings.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <sstream>

vtkStandardNewMacro(vtkLatticeBoltzmannSolver);
vtkRefractaCxxSetClampMacro(vtkLatticeBoltzmannSolver, Tolerance, 0.0, 1.0);

using refracta_lbm::Cx;
using refracta_lbm::Cy;
using refracta_lbm::Cz;
using refracta_lbm::LocalRow;

namespace
{
// The distinct step lengths |c_i spacing| of the lattice's q directions, and each direction's
// class (index into them): directions of one length share one transmittance.
std::vector<double> StepLengthClasses(int q, const double spacing[3], std::vector<int>& classOf)
{
  std::vector<double> lengths;
  classOf.assign(q, 0);
  for (int i = 0; i < q; ++i)
  {
    const double len = std::sqrt(std::pow(Cx[i] * spacing[0], 2) + std::pow(Cy[i] * spacing[1], 2) +
      std::pow(Cz[i] * spacing[2], 2));
    auto it = std::find(lengths.begin(), lengths.end(), len);
    if (it == lengths.end())
    {
      lengths.push_back(len);
      it = lengths.end() - 1;
    }
    classOf[i] = static_cast<int>(it - lengths.begin());
  }
  return lengths;
}

// Planes of the coefficient buffer: T per length class and channel, albedo per channel, g.
size_t CoefficientPlanes(size_t lengthClasses)
{
  return lengthClasses * 3 + 4;
}
}

//------------------------------------------------------------------------------
vtkLatticeBoltzmannSolver::vtkLatticeBoltzmannSolver()
{
  vtkRefractaHostThreads::UseThreadedBackend();
}
vtkLatticeBoltzmannSolver::~vtkLatticeBoltzmannSolver() = default;

//------------------------------------------------------------------------------
void vtkLatticeBoltzmannSolver::SetLattice(int lattice)
{
  if (lattice != D3Q6 && lattice != D3Q18)
  {
    vtkErrorMacro("Lattice " << lattice << " is not supported: use 6 (D3Q6) or 18 (D3Q18).");
    return;
  }
  if (this->Lattice != lattice)
  {
    this->Lattice = lattice;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkLatticeBoltzmannSolver::SetStepsPerExchange(int steps)
{
  int p = 1;
  while (p * 2 <= std::min(std::max(steps, 1), 64))
  {
    p *= 2;
  }
  if (this->StepsPerExchange != p)
  {
    this->StepsPerExchange = p;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkLatticeBoltzmannSolver::SetContext(vtkOpenCLContext* context)
{
  if (this->Context != context)
  {
    this->Context = context;
    this->BuiltKey[0] = -1;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
vtkOpenCLContext* vtkLatticeBoltzmannSolver::GetContext()
{
  if (!this->Context)
  {
    this->Context = vtkOpenCLContext::GetDefault();
  }
  return this->Context;
}

//------------------------------------------------------------------------------
bool vtkLatticeBoltzmannSolver::UsesBlocks()
{
  vtkOpenCLContext* context = this->GetContext();
  this->DeviceHasLocalMemory = context->Initialize() && context->HasDedicatedLocalMemory();
  return this->UseBlocks();
}

//------------------------------------------------------------------------------
bool vtkLatticeBoltzmannSolver::Initialize(const int dims[3], const double spacing[3],
  const float* extinction, const float* albedo, const float* anisotropy)
{
  vtkOpenCLContext* context = this->GetContext();
  if (!context->Initialize())
  {
    vtkErrorMacro("No OpenCL device: " << context->GetLastErrorMessage());
    return false;
  }
  this->DeviceHasLocalMemory = context->HasDedicatedLocalMemory();
  for (int a = 0; a < 3; ++a)
  {
    if (dims[a] < 1 || !(spacing[a] > 0) || !std::isfinite(spacing[a]))
    {
      vtkErrorMacro("Grid " << dims[0] << "x" << dims[1] << "x" << dims[2] << " with spacing "
                            << spacing[0] << ", " << spacing[1] << ", " << spacing[2]
                            << " is invalid: dimensions must be >= 1 and spacing finite, > 0.");
      return false;
    }
    this->Dims[a] = dims[a];
    this->Spacing[a] = spacing[a];
  }
  const size_t n = static_cast<size_t>(dims[0]) * dims[1] * dims[2];
  this->NumberOfVoxels = static_cast<vtkIdType>(n);
  const int q = this->Lattice;

  // Step-length classes: directions with the same length share one transmittance.
  this->ClassLengths = StepLengthClasses(q, spacing, this->DirectionClass);
  const int nclass = static_cast<int>(this->ClassLengths.size());

  // Coefficients, planar: T per class and channel, albedo per channel, g.
  const size_t planes = CoefficientPlanes(nclass);
  if (!this->PlanMemory(planes))
  {
    return false;
  }
  this->HostCoefficients.assign(planes * n, 0.0f);
  float* coef = this->HostCoefficients.data();
  const double meanEdge = std::cbrt(spacing[0] * spacing[1] * spacing[2]);
  std::atomic<vtkIdType> thick(0);
  vtkSMPTools::For(0, static_cast<vtkIdType>(n),
    [&](vtkIdType first, vtkIdType last)
    {
      vtkIdType localThick = 0;
      for (size_t v = first; v < static_cast<size_t>(last); ++v)
      {
        for (int ch = 0; ch < 3; ++ch)
        {
          const double st = extinction ? std::max(0.0, double(extinction[v * 3 + ch])) : 0.0;
          const double a = albedo ? std::min(1.0, std::max(0.0, double(albedo[v * 3 + ch]))) : 0.0;
          const double g =
            anisotropy ? std::min(0.9999, std::max(-0.9999, double(anisotropy[v]))) : 0.0;
          for (int c = 0; c < nclass; ++c)
          {
            const double p = CollisionProbability(
              q, this->CollisionModel, st, a, g, this->ClassLengths[c], meanEdge);
            if (this->CollisionModel == DIFFUSION_MATCHED && c == 0 && p >= 1.0 && st > 0)
            {
              ++localThick;
            }
            // The kernels take the transmittance T = 1 - p.
            coef[(c * 3 + ch) * n + v] = static_cast<float>(1.0 - p);
          }
          coef[(nclass * 3 + ch) * n + v] = static_cast<float>(a);
        }
        coef[(nclass * 3 + 3) * n + v] =
          anisotropy ? std::min(0.9999f, std::max(-0.9999f, anisotropy[v])) : 0.0f;
      }
      thick += localThick;
    });
  this->NumberOfThickVoxels = thick;
  // Where a CPU device staggers buffers (vtkOpenCLContext::StaggerBuffers), the step's four
  // streams are placed a quarter page apart: the two states (read one, write the other, roles
  // swapping every step) half a page, the coefficients and source a quarter page from both.
  // 128^3 on PoCL: 31-44 ms per step against 44-50 at one offset (Benchmarks.md).
  constexpr size_t Quarter = 1024;
  this->Coefficients = context->CreateBufferAt(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
    planes * n * sizeof(float), coef, "LBL coefficients", this, Quarter);
  this->Source = context->CreateBufferAt(
    CL_MEM_READ_WRITE, 6 * n * sizeof(float), nullptr, "LBL source", this, 3 * Quarter);
  for (int k = 0; k < 2; ++k)
  {
    // One scratch float past the state: lbl_step's branch-free store target for vacuum.
    this->State[k] = context->CreateBufferAt(CL_MEM_READ_WRITE,
      (size_t(q) * 3 * n + 1) * sizeof(float), nullptr, "LBL state", this, 2 * Quarter * k);
  }
  if (!this->Coefficients || !this->Source || !this->State[0] || !this->State[1] ||
    !context->ZeroBuffer(this->Source.Get(), 6 * n * sizeof(float), this))
  {
    return false;
  }

  // Probes: every ProbeSpacing-th voxel per axis, offset by half a spacing.
  this->SourceIsZero = true;
  this->GridProbes.clear();
  const int p = this->ProbeSpacing;
  auto axis = [p](int d)
  {
    std::vector<int> c;
    for (int i = std::min(p / 2, d - 1); i < d; i += p)
    {
      c.push_back(i);
    }
    return c;
  };
  for (int z : axis(dims[2]))
  {
    for (int y : axis(dims[1]))
    {
      for (int x : axis(dims[0]))
      {
        this->GridProbes.push_back(
          static_cast<cl_uint>(x + size_t(dims[0]) * (y + size_t(dims[1]) * z)));
      }
    }
  }
  this->ProbeValues = context->CreateBuffer(CL_MEM_READ_WRITE,
    (this->GridProbes.size() + MaxSourceProbes) * 3 * sizeof(float), nullptr, "LBL probe values",
    this);
  if (!this->ProbeValues || !this->SetProbes({}))
  {
    return false;
  }
  this->BuiltKey[0] = -1;
  this->RestrictMedium(dims, spacing, extinction, albedo, anisotropy);
  return this->BuildKernels() && this->ResetState();
}

//------------------------------------------------------------------------------
bool vtkLatticeBoltzmannSolver::PlanMemory(size_t planes)
{
  vtkNew<vtkOpenCLMemoryPlan> plan;
  this->FillMemoryPlan(plan, this->Lattice, this->Dims, planes, this->UseBlocks());
  this->PlannedDeviceMemoryBytes = plan->GetDeviceBytes();
  this->PlannedHostMemoryBytes = plan->GetHostBytes();
  if (!plan->Fits(this->GetContext()))
  {
    vtkErrorMacro(<< plan->GetMessage());
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkLatticeBoltzmannSolver::FitsInMemory(
  int lattice, const int dims[3], const double spacing[3])
{
  vtkOpenCLContext* context = this->GetContext();
  if ((lattice != D3Q6 && lattice != D3Q18) || !context->Initialize())
  {
    return false;
  }
  std::vector<int> classOf;
  const size_t planes = CoefficientPlanes(StepLengthClasses(lattice, spacing, classOf).size());
  vtkNew<vtkOpenCLMemoryPlan> plan;
  this->FillMemoryPlan(
    plan, lattice, dims, planes, this->UseBlocksOn(lattice, context->HasDedicatedLocalMemory()));
  return plan->Fits(context);
}

//------------------------------------------------------------------------------
void vtkLatticeBoltzmannSolver::FillMemoryPlan(
  vtkOpenCLMemoryPlan* plan, int lattice, const int dims[3], size_t planes, bool blocked) const
{
  const double v = static_cast<double>(dims[0]) * dims[1] * dims[2];
  std::ostringstream gridText;
  gridText << "grid " << dims[0] << " x " << dims[1] << " x " << dims[2];
  const std::string grid = gridText.str(), gridSetting = "the grid size";
  const std::string stateSetting =
    lattice == D3Q18 ? "the grid size or Lattice (18 -> 6)" : gridSetting;
  plan->Reset("Lattice-Boltzmann solver");
  plan->AddDeviceBuffer(grid, "coefficients", static_cast<double>(planes) * v * 4, gridSetting);
  plan->AddDeviceBuffer(grid, "source", 6 * v * 4, gridSetting);
  for (const char* what : { "lattice state", "lattice state (next)" })
  {
    plan->AddDeviceBuffer(grid, what, (lattice * 3 * v + 1) * 4, stateSetting);
  }
  if (blocked)
  {
    // Interface buffers between blocks: 6 faces of b x b voxels, 3 channels, per block.
    const int b = this->BlockSize;
    double blocks = 1;
    for (int a = 0; a < 3; ++a)
    {
      blocks *= (dims[a] + b - 1) / b;
    }
    for (const char* what : { "block interfaces", "block interfaces (next)" })
    {
      plan->AddDeviceBuffer(grid, what, blocks * 6 * b * b * 3 * 4, "the grid size or BlockSize");
    }
  }
  double probes = MaxSourceProbes;
  for (int a = 0; a < 3; ++a)
  {
    probes *= (dims[a] + this->ProbeSpacing - 1) / this->ProbeSpacing + 1;
  }
  plan->AddDeviceBuffer(grid, "probes", probes * 3 * 4 * 2, "ProbeSpacing");
  plan->AddDeviceBuffer(grid, "multiple-scattering output", 3 * v * 4, gridSetting);
  plan->AddDeviceBuffer(grid, "multiple-scattering direction output", 3 * v * 4, gridSetting);
  // The coarse start's grids hold the same buffers at 1/8, 1/64, ... of the voxels.
  double coarseShare = 0;
  for (int d[3] = { dims[0], dims[1], dims[2] }; this->CoarseStartApplies(d);)
  {
    coarseShare = coarseShare / 8 + 1.0 / 8;
    for (int& e : d)
    {
      e = (e + 1) / 2;
    }
  }
  if (coarseShare > 0)
  {
    plan->AddDeviceBuffer(
      grid, "coarse-start grids", coarseShare * plan->GetDeviceBytes(), "CoarseStart (off)");
  }
  // Host: the coefficients kept for the absorption sums, the state read back for the energy
  // books, the output, and the source's staging (kept between solves).
  plan->AddHostMemory(grid, "coefficient copy", static_cast<double>(planes) * v * 4, gridSetting);
  plan->AddHostMemory(grid, "state read-back", lattice * 3 * v * 4, stateSetting);
  plan->AddHostMemory(grid, "MultipleScattering", 3 * v * 4, gridSetting);
  plan->AddHostMemory(grid, "source staging", 6 * v * 4, gridSetting);
  if (coarseShare > 0)
  {
    // The coarser grids' host copies, and the first one's medium (7 floats a coarse voxel).
    plan->AddHostMemory(grid, "coarse-start grids",
      coarseShare * plan->GetHostBytes() + 7.0 * 4 * v / 8, "CoarseStart (off)");
  }
}

double vtkLatticeBoltzmannSolver::GetAllocatedDeviceMemoryBytes() const
{
  double total = 0;
  for (const vtkOpenCLBuffer* b :
    { &this->State[0], &this->State[1], &this->Interface[0], &this->Interface[1],
      &this->Coefficients, &this->Source, &this->Probes, &this->ProbeValues })
  {
    total += static_cast<double>(vtkOpenCLBufferBytes(b->Get()));
  }
  return total;
}

//------------------------------------------------------------------------------
bool vtkLatticeBoltzmannSolver::BuildKernels()
{
  if (!this->Coefficients)
  {
    vtkErrorMacro("Initialize() the solver with a grid before iterating.");
    return false;
  }
  const int q = static_cast<int>(this->DirectionClass.size());
  if (q != this->Lattice)
  {
    vtkErrorMacro("The lattice changed from D3Q" << q << " to D3Q" << this->Lattice
                                                 << " after Initialize(); initialize again.");
    return false;
  }
  const bool blocked = this->UseBlocks();
  const int key[6] = { q, this->Boundary, this->SourceDistribution, blocked ? this->BlockSize : 0,
    blocked ? this->StepsPerExchange : 0, static_cast<int>(this->ClassLengths.size()) };
  if (std::equal(key, key + 6, this->BuiltKey))
  {
    return true;
  }
  vtkOpenCLContext* context = this->GetContext();
  std::ostringstream options;
  options << "-DREFRACTA_LBL_Q=" << q << " -DREFRACTA_LBL_NCLASS=" << this->ClassLengths.size()
          << " -DREFRACTA_LBL_CLASSES={";
  for (int i = 0; i < q; ++i)
  {
    options << (i ? "," : "") << this->DirectionClass[i];
  }
  options << "} -DREFRACTA_LBL_BOUNDARY=" << this->Boundary
          << " -DREFRACTA_LBL_SOURCE_PHASE=" << this->SourceDistribution;
  // The directions' unit vectors in the grid's frame (the source's phase function, S_ms's
  // direction) take the spacing's shape; Initialize() sets it and always rebuilds.
  const double largest = std::max({ this->Spacing[0], this->Spacing[1], this->Spacing[2] });
  const char* axis[3] = { "X", "Y", "Z" };
  for (int a = 0; a < 3; ++a)
  {
    options << " -DREFRACTA_LBL_S" << axis[a] << "="
            << vtkOpenCLContext::FloatLiteral(this->Spacing[a] / largest);
  }
  if (blocked)
  {
    options << " -DREFRACTA_LBL_B=" << this->BlockSize
            << " -DREFRACTA_LBL_SUBSTEPS=" << this->StepsPerExchange;
  }
  cl_program program = context->GetProgram({ "refracta_common.cl", "lbl.cl" }, options.str(), this);
  if (!program)
  {
    return false;
  }
  this->StepKernel = context->CreateKernel(program, "lbl_step", this);
  this->ProbeKernel = context->CreateKernel(program, "lbl_probes", this);
  this->ScatteredKernel = context->CreateKernel(program, "lbl_scattered", this);
  this->ScatteredFluxKernel = context->CreateKernel(program, "lbl_scattered_flux", this);
  this->SourceKernel = context->CreateKernel(program, "lbl_source_from_fixed", this);
  this->RestrictKernel = context->CreateKernel(program, "lbl_restrict_source", this);
  this->ProlongKernel = context->CreateKernel(program, "lbl_prolong_state", this);
  this->FieldSourceKernel = context->CreateKernel(program, "lbl_source_from_fields", this);
  this->AddKernel = context->CreateKernel(program, "lbl_add", this);
  if (!this->StepKernel || !this->ProbeKernel || !this->ScatteredKernel ||
    !this->ScatteredFluxKernel || !this->SourceKernel || !this->RestrictKernel ||
    !this->ProlongKernel || !this->FieldSourceKernel || !this->AddKernel)
  {
    return false;
  }
  if (blocked)
  {
    this->BlockKernel = context->CreateKernel(program, "lbl_block", this);
    this->StateInterfaceKernel = context->CreateKernel(program, "lbl_block_state_interface", this);
    if (!this->BlockKernel || !this->StateInterfaceKernel)
    {
      return false;
    }
    const int b = this->BlockSize;
    size_t blocks = 1;
    for (int a = 0; a < 3; ++a)
    {
      this->NumberOfBlocks[a] = (this->Dims[a] + b - 1) / b;
      blocks *= this->NumberOfBlocks[a];
    }
    for (int k = 0; k < 2; ++k)
    {
      this->Interface[k] = context->CreateBuffer(
        CL_MEM_READ_WRITE, blocks * 6 * b * b * 3 * sizeof(float), nullptr, "LBL interface", this);
      if (!this->Interface[k])
      {
        return false;
      }
    }
  }
  std::copy(key, key + 6, this->BuiltKey);
  // A different schedule cannot continue another one's state.
  return this->ResetState();
}

//------------------------------------------------------------------------------
bool vtkLatticeBoltzmannSolver::ResetState()
{
  if (!this->State[0])
  {
    vtkErrorMacro("Initialize() the solver with a grid first.");
    return false;
  }
  vtkOpenCLContext* context = this->GetContext();
  const size_t bytes = (size_t(this->Lattice) * 3 * this->NumberOfVoxels + 1) * sizeof(float);
  for (int k = 0; k < 2; ++k)
  {
    if (!context->ZeroBuffer(this->State[k].Get(), bytes, this))
    {
      return false;
    }
    if (this->Interface[k] && this->UseBlocks())
    {
      const size_t ibytes = vtkOpenCLBufferBytes(this->Interface[k].Get());
      if (!context->ZeroBuffer(this->Interface[k].Get(), ibytes, this))
      {
        return false;
      }
    }
  }
  this->Current = 0;
  this->InterfaceParity = 0;
  this->StateIsZero = true;
  this->CoarseMatchesState = false;
  this->Iterations = 0;
  this->Residual = -1.0;
  this->Converged = false;
  this->PreviousProbes.assign(this->NumberOfProbes * 3, 0.0f);
  return true;
}

//------------------------------------------------------------------------------
bool vtkLatticeBoltzmannSolver::Restart()
{
  return this->ClearSource() && this->ResetState();
}

//------------------------------------------------------------------------------
bool vtkLatticeBoltzmannSolver::ClearSource()
{
  if (!this->Source)
  {
    vtkErrorMacro("Initialize() the solver with a grid first.");
    return false;
  }
  this->SourceIsZero = true;
  this->Iterations = 0;
  this->Residual = -1.0;
  this->Converged = false;
  const size_t bytes = 6 * static_cast<size_t>(this->NumberOfVoxels) * sizeof(float);
  return this->GetContext()->ZeroBuffer(this->Source.Get(), bytes, this) && this->SetProbes({});
}

//------------------------------------------------------------------------------
bool vtkLatticeBoltzmannSolver::SetSource(const float* s1, const float* direction)
{
  if (!this->Source)
  {
    vtkErrorMacro("Initialize() the solver with a grid before setting a source.");
    return false;
  }
  const size_t n = static_cast<size_t>(this->NumberOfVoxels);
  std::vector<float>& planar = this->HostSource;
  planar.resize(6 * n); // every value is written below
  vtkSMPTools::For(0, static_cast<vtkIdType>(n),
    [&](vtkIdType first, vtkIdType last)
    {
      for (size_t v = first; v < static_cast<size_t>(last); ++v)
      {
        for (int c = 0; c < 3; ++c)
        {
          planar[c * n + v] = s1 ? s1[v * 3 + c] : 0.0f;
          planar[(3 + c) * n + v] = direction ? direction[v * 3 + c] : 0.0f;
        }
      }
    });
  // The probes come from the values written: no read back.
  return this->GetContext()->WriteBuffer(
           this->Source.Get(), planar.size() * sizeof(float), planar.data(), this) &&
    this->ChooseSourceProbes(s1, 1, 3);
}

//------------------------------------------------------------------------------
bool vtkLatticeBoltzmannSolver::SetSourceFromFixedPoint(
  cl_mem deposits, double radianceFactor, double directionFactor)
{
  if (!this->BuildKernels())
  {
    return false;
  }
  vtkOpenCLContext* context = this->GetContext();
  const cl_uint n = static_cast<cl_uint>(this->NumberOfVoxels);
  const size_t global = n;
  const size_t local = 64;
  this->SourceIsZero = false; // unknown until UpdateSourceProbes() reads it back
  return context->Check(vtkOpenCLSetKernelArgs(this->SourceKernel.Get(), deposits,
                          static_cast<float>(radianceFactor), static_cast<float>(directionFactor),
                          this->Source.Get(), n),
           "clSetKernelArg(lbl_source_from_fixed)", this) &&
    context->RunKernel(this->SourceKernel.Get(), 1, &global, &local, "lbl_source_from_fixed", this);
}

//------------------------------------------------------------------------------
bool vtkLatticeBoltzmannSolver::Iterate(int steps, bool wait)
{
  if (!this->BuildKernels())
  {
    return false;
  }
  vtkOpenCLContext* context = this->GetContext();
  const cl_int4 dims = { { this->Dims[0], this->Dims[1], this->Dims[2], 0 } };
  const size_t global[3] = { size_t(this->Dims[0]), size_t(this->Dims[1]), size_t(this->Dims[2]) };
  const size_t local[3] = { LocalRow(this->Dims[0]), 1, 1 };
  this->StateIsZero = this->StateIsZero && steps <= 0;
  // Steps from outside a Solve() leave a state the coarse level knows nothing of.
  this->CoarseMatchesState = this->CoarseMatchesState && this->InSolve;
  if (this->UseBlocks())
  {
    const int m = this->StepsPerExchange;
    const int b = this->BlockSize;
    const cl_int4 nblocks = { { this->NumberOfBlocks[0], this->NumberOfBlocks[1],
      this->NumberOfBlocks[2], 0 } };
    const size_t bglobal[3] = { size_t(nblocks.s[0]) * b, size_t(nblocks.s[1]) * b,
      size_t(nblocks.s[2]) * b };
    const size_t blocal[3] = { size_t(b), size_t(b), size_t(b) };
    const int launches = (steps + m - 1) / m;
    for (int l = 0; l < launches; ++l)
    {
      // Fig. 5: read the interface written by the previous launch, write the other one.
      cl_mem in = this->Interface[this->InterfaceParity].Get();
      cl_mem out = this->Interface[1 - this->InterfaceParity].Get();
      if (!context->Check(vtkOpenCLSetKernelArgs(this->BlockKernel.Get(), this->State[0].Get(),
                            this->Coefficients.Get(), this->Source.Get(), in, out, dims, nblocks),
            "clSetKernelArg(lbl_block)", this) ||
        !context->RunKernel(this->BlockKernel.Get(), 3, bglobal, blocal, "lbl_block", this))
      {
        return false;
      }
      this->InterfaceParity = 1 - this->InterfaceParity;
      this->Iterations += m;
    }
    if (launches > 0 && !this->ExchangeStateAndInterface(false))
    {
      return false;
    }
  }
  else
  {
    for (int s = 0; s < steps; ++s)
    {
      if (!context->Check(vtkOpenCLSetKernelArgs(this->StepKernel.Get(),
                            this->State[this->Current].Get(), this->State[1 - this->Current].Get(),
                            this->Coefficients.Get(), this->Source.Get(), dims),
            "clSetKernelArg(lbl_step)", this) ||
        !context->RunKernel(this->StepKernel.Get(), 3, global, local, "lbl_step", this))
      {
        return false;
      }
      this->Current = 1 - this->Current;
      ++this->Iterations;
    }
  }
  return wait ? context->Finish(this) : true;
}

//------------------------------------------------------------------------------
bool vtkLatticeBoltzmannSolver::ExchangeStateAndInterface(bool toInterface)
{
  vtkOpenCLContext* context = this->GetContext();
  const cl_int4 dims = { { this->Dims[0], this->Dims[1], this->Dims[2], 0 } };
  const cl_int4 nblocks = { { this->NumberOfBlocks[0], this->NumberOfBlocks[1],
    this->NumberOfBlocks[2], 0 } };
  const size_t global[3] = { size_t(this->Dims[0]), size_t(this->Dims[1]), size_t(this->Dims[2]) };
  const size_t local[3] = { LocalRow(this->Dims[0]), 1, 1 };
  const cl_int direction = toInterface ? 1 : 0;
  return context->Check(
           vtkOpenCLSetKernelArgs(this->StateInterfaceKernel.Get(), this->State[0].Get(),
             this->Interface[this->InterfaceParity].Get(), dims, nblocks, direction),
           "clSetKernelArg(lbl_block_state_interface)", this) &&
    context->RunKernel(
      this->StateInterfaceKernel.Get(), 3, global, local, "lbl_block_state_interface", this);
}

//------------------------------------------------------------------------------
bool vtkLatticeBoltzmannSolver::Solve()
{
  this->Converged = false;
  this->Aborted = false;
  this->AbortSolve = false;
  if (!this->BuildKernels())
  {
    return false;
  }
  double progress = 0.0;
  this->CoarseStartSteps = 0;
  this->CoarseStartCost = 0.0;
  this->LastSolveCorrected = false;
  // From zero: the coarse start. From the last Solve()'s result: its coarse correction.
  const bool correct = !this->StateIsZero && this->CoarseWarmStart && this->CoarseMatchesState;
  const bool coarse = this->CoarseStart && (this->StateIsZero || correct) && !this->SourceIsZero &&
    this->HasCoarseLevel();
  this->CoarseMatchesState = false; // until this Solve() ends with the coarse result beside it
  if (coarse)
  {
    if (!this->RunCoarseStart(progress, correct))
    {
      return false;
    }
    if (this->Aborted)
    {
      return true;
    }
  }
  struct InSolveScope
  {
    bool& Flag;
    explicit InSolveScope(bool& flag)
      : Flag(flag)
    {
      this->Flag = true;
    }
    ~InSolveScope() { this->Flag = false; }
  } inSolve(this->InSolve);
  std::vector<float> values;
  if (!this->ReadProbes(values))
  {
    return false;
  }
  this->PreviousProbes = values;
  int interval = this->CheckInterval;
  if (this->UseBlocks())
  {
    const int m = this->StepsPerExchange;
    interval = (interval + m - 1) / m * m;
  }
  int done = 0;
  double firstResidual = -1.0; // first finite residual, the start of the log-scale estimate
  while (done < this->MaximumIterations)
  {
    if (this->AbortSolve)
    {
      this->Aborted = true;
      return true;
    }
    const int before = this->Iterations;
    // Not waited for: the probes' blocking read right after waits for the same queue, and a
    // clFinish() more per check interval is a host round trip a GPU idles through.
    if (!this->Iterate(std::min(interval, this->MaximumIterations - done), false))
    {
      return false;
    }
    const int ran = this->Iterations - before;
    done += ran;
    double residual = 0;
    if (!this->CheckConvergence(ran, residual))
    {
      return false;
    }
    this->Residual = residual;
    if (residual < this->Tolerance)
    {
      this->Converged = true;
      progress = 1.0;
      this->InvokeEvent(vtkCommand::ProgressEvent, &progress);
      break;
    }
    // Progress: iterations done, or the way from the first residual down to Tolerance on a log
    // scale, whichever is further; never back.
    double estimate = static_cast<double>(done) / this->MaximumIterations;
    if (firstResidual < 0 && std::isfinite(residual) && residual > 0)
    {
      firstResidual = residual;
    }
    if (firstResidual > this->Tolerance && this->Tolerance > 0 && std::isfinite(residual) &&
      residual > 0)
    {
      estimate = std::max(
        estimate, std::log(firstResidual / residual) / std::log(firstResidual / this->Tolerance));
    }
    progress = std::max(progress, std::min(estimate, 1.0));
    this->InvokeEvent(vtkCommand::ProgressEvent, &progress);
  }
  if (this->AbortSolve)
  {
    this->Aborted = true;
  }
  this->CoarseMatchesState = coarse && !this->Aborted;
  return true;
}

//------------------------------------------------------------------------------
void vtkLatticeBoltzmannSolver::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Lattice: D3Q" << this->Lattice << "\n";
  os << indent << "BlockSize: " << this->BlockSize << "\n";
  os << indent << "BlockPolicy: "
     << (this->BlockPolicy == ALWAYS_BLOCKS ? "always blocks" : "dedicated local memory") << "\n";
  os << indent << "StepsPerExchange: " << this->StepsPerExchange << "\n";
  os << indent << "Boundary: " << (this->Boundary == VACUUM ? "vacuum" : "reflective") << "\n";
  os << indent << "SourceDistribution: "
     << (this->SourceDistribution == ISOTROPIC_SOURCE ? "isotropic" : "phase function") << "\n";
  os << indent << "CollisionModel: "
     << (this->CollisionModel == DIFFUSION_MATCHED ? "diffusion matched" : "exponential") << "\n";
  os << indent << "CoarseWarmStart: " << this->CoarseWarmStart << "\n";
  os << indent << "LastSolveCorrected: " << this->LastSolveCorrected << "\n";
  os << indent << "NumberOfThickVoxels: " << this->NumberOfThickVoxels << "\n";
  os << indent << "PlannedDeviceMemoryBytes: " << this->PlannedDeviceMemoryBytes << "\n";
  os << indent << "PlannedHostMemoryBytes: " << this->PlannedHostMemoryBytes << "\n";
  os << indent << "Tolerance: " << this->Tolerance << "\n";
  os << indent << "CheckInterval: " << this->CheckInterval << "\n";
  os << indent << "ProbeSpacing: " << this->ProbeSpacing << "\n";
  os << indent << "MaximumIterations: " << this->MaximumIterations << "\n";
  os << indent << "CoarseStart: " << (this->CoarseStart ? "on" : "off") << "\n";
  os << indent << "KeepDeviceCopies: " << (this->KeepDeviceCopies ? "on" : "off") << "\n";
  os << indent << "MinimumCoarseDimension: " << this->MinimumCoarseDimension << "\n";
  os << indent << "CoarseStartSteps: " << this->CoarseStartSteps << "\n";
  os << indent << "CoarseStartCost: " << this->CoarseStartCost << "\n";
  os << indent << "Iterations: " << this->Iterations << "\n";
  os << indent << "Residual: " << this->Residual << "\n";
  os << indent << "Converged: " << this->Converged << "\n";
}
