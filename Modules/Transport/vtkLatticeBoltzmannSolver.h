/**
 * @class   vtkLatticeBoltzmannSolver
 * @brief   OpenCL Lattice-Boltzmann lighting solver (Geist et al. 2004, Bernabei et al. III-C).
 *
 * The solver behind vtkLatticeBoltzmannLighting, usable on its own (tests, benchmarks, the
 * concurrent photon/diffusion schedule). It owns the device buffers of one grid:
 * - the lattice state f_i (power per unit volume travelling along lattice direction i, RGB),
 *   for the 6 principal directions (D3Q6, the paper's choice) or the 18 directions of the original
 *   LBL (D3Q18: 6 axes and 12 face diagonals, no rest direction);
 * - per-voxel coefficients derived from the medium: the probability T = exp(-sigma_t len) of
 *   crossing the voxel uncollided along each direction (len = the step length along it), the
 *   albedo and the Henyey-Greenstein g;
 * - the source S1 (power per unit volume scattered out of the direct beam, the photon pass's
 *   `Radiance`) and, for SourceDistribution = PHASE_FUNCTION, its mean direction.
 *
 * One lattice step: collide (uncollided part keeps its direction; of the scattered part the
 * fraction |g| goes forward (g > 0) or backward (g < 0) and the rest is spread evenly over the Q
 * directions; the absorbed part leaves the lattice) and stream to the neighbour; the source is
 * injected each step like scattered light. Iterating converges to the steady state
 * f = sum_k M^k s, the diffuse field of light scattered at least once. See Kernels/lbl.cl for the
 * update and the correction of the paper's Theta matrix.
 *
 * Units. With f in power per unit volume, the multiple-scattering output is
 * S_ms(r) = a sum_i (1 - T_i) f_i(r) = sigma_s phi_ms, where the fluence of the diffuse field is
 * phi_ms = sum_i f_i (1 - T_i) / sigma_t (the expected path length of a packet in the voxel,
 * exactly len_i where sigma_t = 0).
 *
 * Blocks (D3Q6 only; D3Q18 always runs unblocked): BlockSize b > 0 partitions the grid into b^3
 * blocks that iterate StepsPerExchange steps locally and exchange density through alternating
 * interface buffers (Fig. 5). StepsPerExchange = 1 is step for step the global update; larger
 * values reach the same steady state. The blocks stage the lattice in local memory, which pays
 * where it is on-chip (GPUs); on a device whose local memory is ordinary memory (CPU devices)
 * the global update runs instead unless BlockPolicy is ALWAYS_BLOCKS (UsesBlocks() says which).
 *
 * Termination (Solve()): every CheckInterval steps the summed density at sparse probe voxels
 * (every ProbeSpacing-th voxel per axis, plus the 8 voxels with the strongest source) is read
 * back; the residual is max over probes and channels of |p_new - p_old| / max(p_new, 1e-4 *
 * brightest probe) / (steps between the checks), the largest relative change per step.
 * Solve() stops when it falls below Tolerance (Converged), at MaximumIterations, or when a probe
 * stops being finite (an error).
 */
#ifndef vtkLatticeBoltzmannSolver_h
#define vtkLatticeBoltzmannSolver_h

#include "RefractaTransportModule.h" // for export macro
#include "vtkObject.h"
#include "vtkSmartPointer.h" // for the context

#include <algorithm> // for std::min_element
#include <vector>    // for std::vector

#ifndef __VTK_WRAP__
#include "vtkOpenCLHandle.h" // for buffers and kernels
#endif

class vtkDataArray;
class vtkDataSet;
class vtkFloatArray;
class vtkImageData;
class vtkOpenCLContext;
class vtkOpenCLMemoryPlan;

class REFRACTATRANSPORT_EXPORT vtkLatticeBoltzmannSolver : public vtkObject
{
public:
  static vtkLatticeBoltzmannSolver* New();
  vtkTypeMacro(vtkLatticeBoltzmannSolver, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum LatticeType
  {
    D3Q6 = 6,
    D3Q18 = 18
  };
  enum BoundaryType
  {
    VACUUM = 0,     ///< density leaving the grid is lost (no light reflected by the faces)
    REFLECTIVE = 1, ///< density leaving the grid comes back in the opposite direction
  };
  enum SourceDistributionType
  {
    ISOTROPIC_SOURCE = 0,      ///< S1 is spread evenly over the lattice directions
    PHASE_FUNCTION_SOURCE = 1, ///< S1 is spread by the HG phase around its mean direction
  };

  ///@{
  /**
   * Lattice: 6 (D3Q6, default) or 18 (D3Q18). Other values are refused with an error. Inside
   * vtkRefractaRenderPipeline each light pass sets it to the effect plan's choice (set the
   * pipeline's Lattice there).
   */
  void SetLattice(int lattice);
  vtkGetMacro(Lattice, int);
  ///@}

  ///@{
  /**
   * Block edge b in voxels (D3Q6 only); 0 runs the unblocked (global) update. Default 4.
   */
  vtkSetClampMacro(BlockSize, int, 0, 8);
  vtkGetMacro(BlockSize, int);
  ///@}

  ///@{
  /**
   * Where BlockSize > 0 takes effect. DEDICATED_LOCAL_MEMORY (default): on devices whose local
   * memory is on-chip (vtkOpenCLContext::HasDedicatedLocalMemory(); GPUs); elsewhere the global
   * update runs, which is faster there (64^3 on PoCL's 2-core CPU device: 3.7 ms per step
   * against 21-23 ms for b = 4, and fewer steps to converge; Documentation/Reference.md).
   * ALWAYS_BLOCKS: on every device (tests of the blocked kernels, benchmarks).
   */
  enum BlockPolicyType
  {
    DEDICATED_LOCAL_MEMORY = 0,
    ALWAYS_BLOCKS = 1
  };
  vtkSetClampMacro(BlockPolicy, int, DEDICATED_LOCAL_MEMORY, ALWAYS_BLOCKS);
  vtkGetMacro(BlockPolicy, int);
  ///@}

  /**
   * Whether the blocked update runs: BlockSize > 0, D3Q6, and the BlockPolicy allows it on the
   * context's device.
   */
  bool UsesBlocks();

  ///@{
  /**
   * Lattice steps a block iterates between interface exchanges: a power of two in [1, 64]
   * (others are rounded down to one). Default 4.
   */
  void SetStepsPerExchange(int steps);
  vtkGetMacro(StepsPerExchange, int);
  ///@}

  ///@{
  /**
   * Boundary of the grid's faces. Default VACUUM.
   */
  vtkSetClampMacro(Boundary, int, VACUUM, REFLECTIVE);
  vtkGetMacro(Boundary, int);
  ///@}

  ///@{
  /**
   * How the source S1 enters the lattice. Default PHASE_FUNCTION_SOURCE (falls back to isotropic
   * in voxels without a source direction).
   */
  vtkSetClampMacro(SourceDistribution, int, ISOTROPIC_SOURCE, PHASE_FUNCTION_SOURCE);
  vtkGetMacro(SourceDistribution, int);
  ///@}

  ///@{
  /**
   * Convergence: relative change of the probe density per step below Tolerance (default 1e-4),
   * checked every CheckInterval steps (default 8, rounded up to StepsPerExchange in blocked
   * mode), probes every ProbeSpacing voxels per axis (default 8), at most MaximumIterations
   * steps (default 5000).
   */
  void SetTolerance(double value);
  vtkGetMacro(Tolerance, double);
  vtkSetClampMacro(CheckInterval, int, 1, 4096);
  vtkGetMacro(CheckInterval, int);
  vtkSetClampMacro(ProbeSpacing, int, 1, 4096);
  vtkGetMacro(ProbeSpacing, int);
  vtkSetClampMacro(MaximumIterations, int, 0, 1 << 30);
  vtkGetMacro(MaximumIterations, int);
  ///@}

  ///@{
  /**
   * Coarse start (default on): a Solve() that begins from a zero lattice state (after
   * Initialize(), ResetState() or Restart(); not a warm start after ClearSource(), not a state
   * that Iterate() has advanced) first solves the same problem on a grid of half the resolution
   * and starts from that solution instead of from zero: a cascadic multigrid start. The coarse
   * grid averages each 2x2x2 block of voxels (extinction; albedo weighted by extinction; g
   * weighted by scattering; the source), has twice the spacing, and is itself started from a
   * coarser grid while its every axis keeps at least MinimumCoarseDimension voxels (default 16).
   * Its steady state is prolonged to the fine grid (each voxel takes its parent's densities,
   * scaled by the ratio of the two grids' collision probabilities: the exact ratio of the two
   * steady states in a homogeneous medium; Kernels/lbl.cl, lbl_prolong_state). A coarse step
   * costs an eighth of a fine one and carries light twice as far, so the slow, smooth part of
   * the solution, which takes the fine lattice most of its steps, is paid for at the coarse
   * level. The fixed point does not depend on the start: the fine grid still iterates until its
   * own residual is below Tolerance. No coarse grid is built when an axis has fewer than
   * 2 * MinimumCoarseDimension voxels. Initialize() reads both settings (it builds the coarse
   * grid's medium); switching CoarseStart off later skips the coarse start.
   */
  vtkSetMacro(CoarseStart, bool);
  vtkGetMacro(CoarseStart, bool);
  vtkBooleanMacro(CoarseStart, bool);
  vtkSetClampMacro(MinimumCoarseDimension, int, 4, 1 << 20);
  vtkGetMacro(MinimumCoarseDimension, int);
  ///@}

  ///@{
  /**
   * Coarse correction of a warm start (default on; needs CoarseStart): a Solve() that continues
   * from the steady state of the last Solve() (a warm start after ClearSource() and a new
   * source, e.g. vtkPhotonDiffusionSchedule's WarmStart for a light move) first solves the coarse
   * grid again, starting from its own last steady state, and adds the change of the coarse
   * solution, prolonged as in the coarse start, to the fine state (clamped at zero;
   * Kernels/lbl.cl, lbl_prolong_state). The smooth part of the change is paid for at the coarse
   * level and the fine detail of the last solution is kept, where a plain warm start carries the
   * whole change on the fine grid and a coarse start from zero rebuilds the detail. Applies only
   * when the state is the last Solve()'s result with the coarse grid's result beside it (not
   * after Iterate() from outside a Solve(), ResetState() or Initialize()); the levels below
   * correct their own warm starts the same way. The fixed point does not depend on the start.
   * GetLastSolveCorrected() says whether the last Solve() applied it.
   */
  vtkSetMacro(CoarseWarmStart, bool);
  vtkGetMacro(CoarseWarmStart, bool);
  vtkBooleanMacro(CoarseWarmStart, bool);
  vtkGetMacro(LastSolveCorrected, bool);
  ///@}

  ///@{
  /**
   * Keep the buffer ComputeMultipleScattering(vtkFloatArray*, ...) reads its result from as the
   * output array's device copy in the context's vtkOpenCLDeviceArrays (default off), so that the
   * view pass takes `MultipleScattering` from the device instead of uploading it again. The copy
   * holds 12 bytes per voxel of device memory while the array lives. vtkRefractaRenderPipeline
   * turns it on (its DeviceHandOff).
   */
  vtkSetMacro(KeepDeviceCopies, bool);
  vtkGetMacro(KeepDeviceCopies, bool);
  vtkBooleanMacro(KeepDeviceCopies, bool);
  ///@}

  /**
   * Whether a Solve() from a zero state on a grid of these dimensions would start from a coarse
   * grid with the present settings (CoarseStart on, every axis >= 2 * MinimumCoarseDimension).
   */
  bool CoarseStartApplies(const int dims[3]) const
  {
    return this->CoarseStart && *std::min_element(dims, dims + 3) >= 2 * this->MinimumCoarseDimension;
  }

  ///@{
  /**
   * The last Solve()'s coarse start: lattice steps run on the coarser grids (all levels summed;
   * 0 when none ran) and their cost in steps of this grid (a level's steps count 8^-level, as
   * its voxels do).
   */
  vtkGetMacro(CoarseStartSteps, int);
  vtkGetMacro(CoarseStartCost, double);
  ///@}

  /**
   * The OpenCL context (default: vtkOpenCLContext::GetDefault()).
   */
  void SetContext(vtkOpenCLContext* context);
  vtkOpenCLContext* GetContext();

  ///@{
  /**
   * Results of the last Solve(): lattice steps done (since the last ResetState()), the last
   * residual (-1 before any check), whether it converged.
   */
  vtkGetMacro(Iterations, int);
  vtkGetMacro(Residual, double);
  vtkGetMacro(Converged, bool);
  ///@}

  /**
   * Number of lattice steps run by Iterate() and Solve() since ResetState().
   */
  int GetStepsDone() const { return this->Iterations; }

  enum CollisionModelType
  {
    EXPONENTIAL_COLLISION = 0, ///< p = 1 - exp(-sigma_t len): the voxel's exact transmittance
    DIFFUSION_MATCHED = 1,     ///< p chosen so that the lattice diffuses like the continuum
  };

  ///@{
  /**
   * How the per-step collision probability p of a voxel is derived from sigma_t.
   * EXPONENTIAL_COLLISION: p = 1 - exp(-sigma_t len) along each direction (len its step length):
   * a packet crossing the voxel is attenuated exactly, but the lattice can collide at most once
   * per step, so its diffusion length exceeds the continuum's by a factor ~1 + sigma_t h / 4.
   * DIFFUSION_MATCHED (default): p (the same for every direction) solves
   * L_lattice(p) = 1 / sqrt(3 sigma_a sigma_t') with the lattice's diffusion limit
   * L^2 = h^2 s2 (1 + rho) / (2 (1 - rho) (1 - a) p), rho = 1 - p (1 - a g), s2 = 1/3 (D3Q6) or
   * 5/9 (D3Q18), h the cube root of the voxel volume:
   * p = (-3 s2 tau^2 k + sqrt(9 s2^2 tau^4 k^2 + 48 s2 tau^2)) / 4, tau = sigma_t h, k = 1 - a g.
   * p tends to tau (D3Q6) for thin voxels and is clamped to 1 for optically thick ones
   * (tau > sqrt(2 / (2 - k)) for D3Q6), where no lattice of this resolution can diffuse as little
   * as the medium does; GetNumberOfThickVoxels() counts them.
   */
  vtkSetClampMacro(CollisionModel, int, EXPONENTIAL_COLLISION, DIFFUSION_MATCHED);
  vtkGetMacro(CollisionModel, int);
  ///@}

  /**
   * Voxel channels whose DIFFUSION_MATCHED p was clamped to 1 in the last Initialize().
   */
  vtkGetMacro(NumberOfThickVoxels, vtkIdType);

  /**
   * Per-step collision probability of a direction of step length `len` in a voxel of mean edge
   * h (see CollisionModel).
   */
  static double CollisionProbability(
    int lattice, int model, double sigmaT, double albedo, double g, double len, double h);

  /**
   * Exact asymptotic decay length, along a lattice axis, of the lattice's steady state in a
   * homogeneous medium (sigma_t, albedo a < 1, g, cubic voxels of edge h): the 1/kappa of the
   * decaying mode f_i ~ exp(-kappa x), from the dispersion relation
   * 1 = sum_j (1/Q) (1 - |g|) a p_j / (exp(-kappa h c_jx) - rho_j), rho_j = 1 - p_j + a p_j g+,
   * (g >= 0; for g < 0 it uses the diffusion limit). Returns 0 when there is no decaying mode.
   */
  static double LatticeDecayLength(
    int lattice, int model, double sigmaT, double albedo, double g, double h);

  /**
   * Diffusion limit of the lattice: L^2 = h^2 s2 (1 + rho) / (2 (1 - rho) (1 - q)), with
   * rho = 1 - p (1 - a g) the direction persistence, q = 1 - (1 - a) p the survival per step and
   * s2 the mean square step per axis (1/3 for D3Q6, 5/9 for D3Q18): the lattice's diffusion
   * coefficient is D = h^2 s2 (1 + rho) / (2 (1 - rho)) per step.
   */
  static double LatticeDiffusionLength(
    int lattice, int model, double sigmaT, double albedo, double g, double h);

#ifndef __VTK_WRAP__
  /**
   * Allocate the buffers for a grid of dims voxels with the given spacing and upload the medium
   * (interleaved RGB arrays of dims[0]*dims[1]*dims[2] tuples; nullptr means 0; anisotropy one
   * value per voxel or nullptr for 0). Resets the state and the source. Returns false after
   * reporting an error.
   */
  bool Initialize(const int dims[3], const double spacing[3], const float* extinction,
    const float* albedo, const float* anisotropy);

  /**
   * Upload the source S1 (interleaved RGB, power per unit volume) and optionally its mean
   * direction (interleaved xyz, any length; zero means no direction). nullptr clears it.
   */
  bool SetSource(const float* s1, const float* direction);

  /**
   * SetSource() from point arrays of 3 components and one tuple per voxel (`direction` may be
   * null): where the context holds device copies of both (vtkOpenCLDeviceArrays, e.g. the photon
   * pass's output with vtkPhotonTracer::KeepDeviceCopies), the source is arranged from them on
   * the device and nothing is uploaded; otherwise the arrays are read and uploaded.
   */
  bool SetSourceArrays(vtkDataArray* s1, vtkDataArray* direction);

  /**
   * SetSource() from a lighting volume's lattice source: S1 (`Radiance` and
   * `RadianceDirection`), or with the first-collision split the light the photons handed on
   * (`MultipleScatteringSource` and its direction; vtkRefractaLightingVolume::LatticeSourceName()),
   * with a volume caustic's bricks folded back into their voxels.
   */
  bool SetSourceFromLighting(vtkImageData* lighting);

  /**
   * The planar source buffer (3 planes of S1, then 3 of direction when PHASE_FUNCTION_SOURCE),
   * for producers that write the source on the device (the concurrent photon schedule).
   */
  cl_mem GetSourceBuffer() const
  {
    return this->Source.Get();
  }

  /**
   * Enqueue (without waiting) the conversion of a photon pass's fixed-point accumulators
   * (six cl_long per voxel: RGB power, then the direction sums; see
   * vtkPhotonTracer::SetChunkCallback) into the source buffer: S1 = power * radianceFactor.
   */
  bool SetSourceFromFixedPoint(cl_mem deposits, double radianceFactor, double directionFactor);

  /**
   * Re-read the source buffer and add its strongest voxels to the convergence probes; call it
   * after writing the source on the device (SetSource() and SetSourceArrays() choose them from
   * their host values instead).
   */
  bool UpdateSourceProbes();

  /**
   * Zero the lattice state (and interfaces) and the step count.
   */
  bool ResetState();

  /**
   * Back to the state Initialize() leaves (zero lattice state, zero source, the grid probes only)
   * on the same grid and medium, without recomputing or uploading the medium's coefficients: what
   * a new light needs when the medium has not changed. Bit-identical to Initialize() with the
   * same medium from then on.
   */
  bool Restart();

  /**
   * Zero the source and drop the source probes, keep the lattice state: a new source then
   * iterates on from the last field instead of from zero (a warm start; the fixed point does not
   * depend on the start, only the number of steps to reach it does). The step count, residual
   * and convergence flag start again. Restart() is ClearSource() followed by ResetState().
   */
  bool ClearSource();

  /**
   * Run n lattice steps (rounded up to StepsPerExchange in blocked mode); enqueues and, when
   * `wait` is true, waits. Returns false after reporting an error.
   */
  bool Iterate(int n, bool wait = true);

  /**
   * Iterate from the current state until converged, MaximumIterations, an abort or an error.
   * After every check interval it invokes vtkCommand::ProgressEvent (call data: a double in
   * [0, 1], never decreasing within a Solve()): the larger of the fraction of MaximumIterations
   * done and the fraction of the way, on a log scale, from the first residual to Tolerance,
   * log(r0 / r) / log(r0 / Tolerance). Progress 1 is reported when it converges.
   * Abort: SetAbortSolve(true) (e.g. from a ProgressEvent observer) stops it at the next check
   * interval (every CheckInterval steps); it then returns true with GetAborted() set and the
   * state as it was at that check. Solve() clears AbortSolve when it starts.
   */
  bool Solve();

  ///@{
  /**
   * Abort request for Solve() (see there), and whether the last Solve() was aborted.
   */
  vtkSetMacro(AbortSolve, bool);
  vtkGetMacro(AbortSolve, bool);
  vtkGetMacro(Aborted, bool);
  ///@}

  /**
   * The residual now (probes compared with the previous call); use between Iterate() calls.
   * Returns false on a non-finite probe. `stepsSinceLast` normalises it per step.
   */
  bool CheckConvergence(int stepsSinceLast, double& residual);

  /**
   * The state in planar layout (Q * 3 planes of N floats), global-equivalent in blocked mode.
   */
  bool ReadState(std::vector<float>& state);

  /**
   * Total density per channel, summed in double: the state plus the density in transit in the
   * interface buffers (blocked mode). With sigma_a = 0 and reflective faces it is conserved.
   */
  bool ComputeTotalDensity(double total[3]);

  /**
   * Power absorbed per channel by the next step from the current state (host, double), the
   * quantity the total density loses per step when the faces reflect and there is no source.
   */
  bool ComputeAbsorbedNextStep(double absorbed[3]);

  /**
   * S_ms = sigma_s phi_ms per voxel (interleaved RGB, N tuples).
   */
  bool ComputeMultipleScattering(float* out);

  /**
   * ComputeMultipleScattering() into `out` (3 components, resized to one tuple per voxel), plus
   * `addend` when given (3 components, one tuple per voxel: the photons' own S_ms of the
   * first-collision split), added on the device when the context holds its device copy. With
   * KeepDeviceCopies the result's buffer becomes `out`'s device copy (vtkOpenCLDeviceArrays).
   */
  bool ComputeMultipleScattering(vtkFloatArray* out, vtkDataArray* addend);

  /**
   * The direction of the light S_ms scatters (MultipleScatteringDirection of
   * vtkRefractaLightingVolume): per voxel the net flux of the light the lattice scatters there
   * over its scattered power, F / S = sum_i w_i c_i / |c_i| / sum_i w_i with w_i = a (1 - T_i)
   * f_i over the directions i and the channels, into `out` (3 components in the grid's frame,
   * resized to one tuple per voxel). Its length is that light's mean cosine about F: 0 where it
   * is isotropic, 1 where it is collimated along a lattice direction, zero where nothing
   * scatters. The view pass shades S_ms about it (Physics.md, "The direction of multiple
   * scattering"). With the first-collision split give `total` (S_ms of the lattice and the
   * photons, ComputeMultipleScattering()'s result with its addend) and `photons` (the photon
   * pass's output: its `MultipleScattering` is the photons' part, its
   * `MultipleScatteringDirection` their flux over their fluence, isotropic where missing): each
   * voxel's direction is then the two parts' directions weighted by their scattered power
   * (channel sums). A `total` or photon array of the wrong shape is an error.
   */
  bool ComputeMultipleScatteringDirection(
    vtkFloatArray* out, vtkDataArray* total = nullptr, vtkDataSet* photons = nullptr);

  /**
   * Step-length class of each direction and the lengths (filled by Initialize()).
   */
  const std::vector<double>& GetClassLengths() const
  {
    return this->ClassLengths;
  }
#endif

  ///@{
  /**
   * Memory planning: Initialize() estimates the solver's device buffers (coefficients, source,
   * two lattice states of Lattice x 3 floats per voxel, block interfaces, probes, the output)
   * and host copies from the grid size, Lattice and BlockSize, and checks them against the
   * context's limits (vtkOpenCLMemoryPlan) before it allocates anything. What does not fit fails
   * Initialize() with a message naming the buffer, the limit and the setting to lower.
   * GetPlannedDeviceMemoryBytes() / GetPlannedHostMemoryBytes() are the last plan's totals
   * (bytes); GetAllocatedDeviceMemoryBytes() sums the solver's device buffers as allocated now
   * (the output buffer of ComputeMultipleScattering() is temporary and not included).
   */
  vtkGetMacro(PlannedDeviceMemoryBytes, double);
  vtkGetMacro(PlannedHostMemoryBytes, double);
  double GetAllocatedDeviceMemoryBytes() const;
  ///@}

  /**
   * Whether a grid of `dims` voxels of `spacing` on `lattice` (6 or 18) would fit the context's
   * limits, by the plan Initialize() makes, nothing allocated and nothing reported (false also for
   * another lattice or without a device). The lattice alone is counted, not the other passes'
   * buffers beside it. vtkRefractaRenderPipeline asks it before its effect plan's automatic D3Q18
   * runs.
   */
  bool FitsInMemory(int lattice, const int dims[3], const double spacing[3]);

  /**
   * Number of voxels of the initialized grid.
   */
  vtkIdType GetNumberOfVoxels() const
  {
    return this->NumberOfVoxels;
  }

protected:
  vtkLatticeBoltzmannSolver();
  ~vtkLatticeBoltzmannSolver() override;

  bool UseBlocks() const
  {
    return this->UseBlocksOn(this->Lattice, this->DeviceHasLocalMemory);
  }
  bool UseBlocksOn(int lattice, bool deviceHasLocalMemory) const
  {
    return this->BlockSize > 0 && lattice == D3Q6 &&
      (this->BlockPolicy == ALWAYS_BLOCKS || deviceHasLocalMemory);
  }
  bool PlanMemory(size_t coefficientPlanes);
  // The buffers of a grid of `dims` voxels on `lattice` with `coefficientPlanes` planes, in
  // blocks or not.
  void FillMemoryPlan(vtkOpenCLMemoryPlan* plan, int lattice, const int dims[3],
    size_t coefficientPlanes, bool blocked) const;
  bool BuildKernels();
  bool ReadProbes(std::vector<float>& values);
  bool SetProbes(const std::vector<cl_uint>& extra);
  // Adds the voxels with the strongest source to the probes, from host values: voxel v's RGB at
  // s1[v * voxelStride + c * channelStride] (null: a zero source).
  bool ChooseSourceProbes(const float* s1, size_t channelStride, size_t voxelStride);
#ifndef __VTK_WRAP__
  // S_ms into a new device buffer (lbl_scattered), not read back.
  bool ComputeMultipleScatteringOnDevice(vtkOpenCLBuffer& result);
  // The split's direction: the lattice's (in `lattice`) and the photons' weighted by their parts
  // of `total` (ComputeMultipleScatteringDirection()).
  static void MergePhotonDirection(vtkFloatArray* lattice, vtkDataArray* total,
    vtkDataArray* photons, vtkDataArray* photonDirection);
  // Runs a read-out kernel (state, coefficients -> 3 floats per voxel) into a new buffer.
  bool RunVoxelReadOut(
    vtkOpenCLKernel& kernel, const char* name, const char* bufferName, vtkOpenCLBuffer& result);
#endif
  // Coarse start (vtkLatticeBoltzmannSolverCoarseStart.cxx).
  void RestrictMedium(const int dims[3], const double spacing[3], const float* extinction,
    const float* albedo, const float* anisotropy);
  bool HasCoarseLevel() const
  {
    return !this->CoarseExtinction.empty();
  }
  // Sets the coarse level up; `keepState` (a warm start's correction) keeps its last steady
  // state when the level needs no new Initialize(), and is cleared otherwise.
  bool PrepareCoarseLevel(bool& keepState);
  // The coarse start (`correct` false: the fine state becomes the prolonged coarse solution) or
  // the coarse correction of a warm start (`correct` true, and kept by PrepareCoarseLevel()).
  bool RunCoarseStart(double& progress, bool correct);
  // Blocked mode: the state's interface-fed entries from the interface the next launch reads
  // (after a launch), or that interface from the state (toInterface: the coarse start's seed).
  bool ExchangeStateAndInterface(bool toInterface);
  static constexpr size_t MaxSourceProbes = 8;
  static constexpr double ProbeFloor = 1e-4;

  int Lattice = D3Q6;
  int BlockSize = 4;
  int BlockPolicy = DEDICATED_LOCAL_MEMORY;
  bool DeviceHasLocalMemory = false; // the context's, read when the lattice is initialised
  int StepsPerExchange = 4;
  int Boundary = VACUUM;
  int SourceDistribution = PHASE_FUNCTION_SOURCE;
  double Tolerance = 1e-4;
  int CheckInterval = 8;
  int ProbeSpacing = 8;
  int MaximumIterations = 5000;
  int CollisionModel = DIFFUSION_MATCHED;
  vtkIdType NumberOfThickVoxels = 0;
  double PlannedDeviceMemoryBytes = 0;
  double PlannedHostMemoryBytes = 0;

  bool CoarseStart = true;
  bool CoarseWarmStart = true;
  bool LastSolveCorrected = false;
  // The state is the last Solve()'s result and the coarse level holds its counterpart: what a
  // coarse correction needs (cleared by ResetState(), Initialize() and Iterate() from outside).
  bool CoarseMatchesState = false;
  bool InSolve = false;
  bool KeepDeviceCopies = false;
  int MinimumCoarseDimension = 16;
  int CoarseStartSteps = 0;
  double CoarseStartCost = 0.0;
  bool StateIsZero = true;
  // The coarse grid's medium (restricted by Initialize()) and its solver, set up on first use.
  vtkSmartPointer<vtkLatticeBoltzmannSolver> Coarse;
  int CoarseDims[3] = { 0, 0, 0 };
  double CoarseSpacing[3] = { 0, 0, 0 };
  std::vector<float> CoarseExtinction, CoarseAlbedo, CoarseAnisotropy;
  bool CoarseInitialized = false;

  int Iterations = 0;
  double Residual = -1.0;
  bool Converged = false;
  bool AbortSolve = false;
  bool Aborted = false;

  vtkSmartPointer<vtkOpenCLContext> Context;
  int Dims[4] = { 0, 0, 0, 0 };
  double Spacing[3] = { 1, 1, 1 }; // of the grid Initialize() was given
  int NumberOfBlocks[4] = { 0, 0, 0, 0 };
  vtkIdType NumberOfVoxels = 0;
  std::vector<int> DirectionClass;
  std::vector<double> ClassLengths;
  std::vector<float> HostCoefficients; // planar, kept for the host-side absorption sum
  // Host staging of the source (planar, 6 floats a voxel) and of its read-back for the probes,
  // kept between solves: fresh vectors of this size cost more in page faults than their copy.
  std::vector<float> HostSource;
  std::vector<float> PreviousProbes;
  size_t NumberOfProbes = 0;
  bool SourceIsZero = true;
#ifndef __VTK_WRAP__
  std::vector<cl_uint> GridProbes;
#endif
  int BuiltKey[6] = { -1, -1, -1, -1, -1, -1 };
  int InterfaceParity = 0;

#ifndef __VTK_WRAP__
  vtkOpenCLBuffer State[2];
  vtkOpenCLBuffer Interface[2];
  vtkOpenCLBuffer Coefficients;
  vtkOpenCLBuffer Source;
  vtkOpenCLBuffer Probes;
  vtkOpenCLBuffer ProbeValues;
  vtkOpenCLKernel StepKernel;
  vtkOpenCLKernel BlockKernel;
  vtkOpenCLKernel StateInterfaceKernel; // lbl_block_state_interface
  vtkOpenCLKernel ProbeKernel;
  vtkOpenCLKernel ScatteredKernel;
  vtkOpenCLKernel ScatteredFluxKernel; // lbl_scattered_flux
  vtkOpenCLKernel SourceKernel;
  vtkOpenCLKernel FieldSourceKernel; // lbl_source_from_fields
  vtkOpenCLKernel AddKernel;         // lbl_add
  vtkOpenCLKernel RestrictKernel;
  vtkOpenCLKernel ProlongKernel;
  vtkOpenCLBuffer CoarseBefore;  // the coarse level's last steady state, during a correction
  int Current = 0;
  cl_mem CurrentState() const
  {
    return this->UseBlocks() ? this->State[0].Get() : this->State[this->Current].Get();
  }
#endif

private:
  vtkLatticeBoltzmannSolver(const vtkLatticeBoltzmannSolver&) = delete;
  void operator=(const vtkLatticeBoltzmannSolver&) = delete;
};

#endif
