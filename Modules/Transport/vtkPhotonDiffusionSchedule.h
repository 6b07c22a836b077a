/**
 * @class   vtkPhotonDiffusionSchedule
 * @brief   Photon marching and Lattice-Boltzmann diffusion, sequential or interleaved in chunks
 *          of k steps (Bernabei et al., section III and Fig. 1).
 *
 * Input port 0: a Refracta medium. The photon pass (GetPhotonTracer(): lights, photon count and
 * every marching knob) deposits S1; the Lattice-Boltzmann solver (GetSolver(): lattice, blocks,
 * tolerance, ...) spreads it into the multiple-scattering field.
 * - SEQUENTIAL: march every photon to its end, then diffuse from a zero lattice to convergence.
 * - INTERLEAVED (default): the photons advance StepsPerChunk = k steps at a time (default 16);
 *   after each chunk the deposits so far become the lattice's source and DiffusionStepsPerChunk
 *   lattice steps (default 8, the paper's figure) are enqueued before the next chunk, so the
 *   diffusion of what is already deposited proceeds while the marching goes on. When the last
 *   photon has finished, the final S1 (smoothed as the tracer outputs it) replaces the source and
 *   the lattice iterates on from its current state to convergence.
 * Both modes converge to the same steady state (the lattice's fixed point depends only on the
 * final source); the interleaved one starts the final solve from a warm state.
 *
 * WarmStart (default off) is for relighting: when the medium and the solver's settings are
 * unchanged since the last run (a light moved), the photon pass runs without interleaving and the
 * lattice iterates from the last run's field instead of from zero, to the same tolerance. The
 * result differs from a cold start by what the tolerance allows (measured in
 * PhotonDiffusionSchedule.WarmStartAgreesWithColdInFewerSteps), and now depends on the previous
 * run; the first run, and any run after the medium or the solver changed, is cold. Field data
 * `ScheduleWarmStart` says which it was.
 * On one in-order OpenCL queue the interleaving is of kernels (the paper's GPU ran the two
 * passes on different multiprocessors at once; on a CPU device both share the same cores).
 *
 * Output: as vtkLatticeBoltzmannLighting (`Radiance`, `RadianceDirection`,
 * `MultipleScattering` and its `MultipleScatteringDirection`; the tracer's field data;
 * `LatticeBoltzmannIterations`, `...Residual`,
 * `...Converged`), plus field data `ScheduleMode` (0 sequential, 1 interleaved),
 * `ScheduleChunks`, `ScheduleDiffusionStepsDuringMarching`, `ScheduleMarchingSeconds` (photon
 * pass including the interleaved diffusion), `ScheduleFinalSolveSeconds` and
 * `ScheduleTotalSeconds`.
 *
 * Progress and abort: ProgressEvent rises monotonically to 1: the photon pass's progress scaled
 * into [0, s], the final solve's into [s, 0.99], where s is the photon pass's share of the
 * previous run's time (0.5 on the first run). AbortExecute is handed to the running stage (the
 * tracer between photon batches or chunks, the solver between check intervals): the run stops,
 * the output is empty, no error is reported (RequestData returns 1), GetLastRunAborted() is set,
 * and after AbortExecuteOff() the next Update() runs from the start.
 */
#ifndef vtkPhotonDiffusionSchedule_h
#define vtkPhotonDiffusionSchedule_h

#include "RefractaTransportModule.h" // for export macro
#include "vtkImageAlgorithm.h"
#include "vtkSmartPointer.h" // for members

class vtkImageData;
class vtkLatticeBoltzmannSolver;
class vtkPhotonTracer;

class REFRACTATRANSPORT_EXPORT vtkPhotonDiffusionSchedule : public vtkImageAlgorithm
{
public:
  static vtkPhotonDiffusionSchedule* New();
  vtkTypeMacro(vtkPhotonDiffusionSchedule, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum ModeType
  {
    SEQUENTIAL = 0,
    INTERLEAVED = 1
  };

  ///@{
  /**
   * Schedule (default INTERLEAVED).
   */
  vtkSetClampMacro(Mode, int, SEQUENTIAL, INTERLEAVED);
  vtkGetMacro(Mode, int);
  ///@}

  ///@{
  /**
   * Photon steps per chunk k (default 16) and lattice steps enqueued after each chunk (default
   * 8), interleaved mode only.
   */
  vtkSetClampMacro(StepsPerChunk, int, 1, 1 << 20);
  vtkGetMacro(StepsPerChunk, int);
  vtkSetClampMacro(DiffusionStepsPerChunk, int, 0, 1 << 20);
  vtkGetMacro(DiffusionStepsPerChunk, int);
  ///@}

  /**
   * The photon pass (configure lights and photon knobs on it; its input is set by this filter).
   */
  vtkPhotonTracer* GetPhotonTracer();

  /**
   * The lattice solver (configure its knobs; Initialize() is called by this filter).
   */
  vtkLatticeBoltzmannSolver* GetSolver();

  vtkMTimeType GetMTime() override;

  ///@{
  /**
   * Start the lattice of a relight from the last run's field (see the class description).
   * Default off: every run starts from zero and is bit-identical to a fresh schedule's.
   */
  vtkSetMacro(WarmStart, bool);
  vtkGetMacro(WarmStart, bool);
  vtkBooleanMacro(WarmStart, bool);
  ///@}

  /**
   * Whether the last run started the lattice from the previous run's field.
   */
  vtkGetMacro(LastRunWarm, bool);

  /**
   * Whether the last run interleaved the lattice with the marching: Mode INTERLEAVED, not a warm
   * start, and no first-collision split (vtkPhotonTracer::ScatteringOrders 0).
   */
  vtkGetMacro(LastRunInterleaved, bool);

  /**
   * Whether the last RequestData stopped because AbortExecute was set (its output is empty).
   */
  vtkGetMacro(LastRunAborted, bool);

  /**
   * How many runs validated the medium and initialised the solver with it (uploading its
   * coefficients); the others (the medium and the solver's settings unchanged, e.g. a light
   * move) only restarted the solver (vtkLatticeBoltzmannSolver::Restart()).
   */
  vtkGetMacro(NumberOfSolverInitializations, int);

protected:
  vtkPhotonDiffusionSchedule();
  ~vtkPhotonDiffusionSchedule() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int Mode = INTERLEAVED;
  int StepsPerChunk = 16;
  int DiffusionStepsPerChunk = 8;
  bool LastRunAborted = false;
  bool WarmStart = false;
  bool LastRunWarm = false;
  bool LastRunInterleaved = false;
  bool HasField = false;    // the solver holds a field of the current medium to start from
  double PhotonShare = 0.5; // the photon pass's share of the progress
  vtkSmartPointer<vtkPhotonTracer> Tracer;
  vtkSmartPointer<vtkLatticeBoltzmannSolver> Solver;
  // The tracer's input: a shallow copy of the medium, made again only when the medium changed,
  // so that the tracer keeps its uploaded medium and octree across light changes.
  vtkSmartPointer<vtkImageData> TracerInput;
  vtkImageData* TracerInputSource = nullptr;
  vtkMTimeType TracerInputTime = 0;
  // The medium the solver was last initialised with (validated, coefficients uploaded), and the
  // solver's MTime then: while both are unchanged a run only restarts the solver.
  vtkMTimeType SolverMediumTime = 0;
  vtkMTimeType SolverSettingsTime = 0;
  int NumberOfSolverInitializations = 0;

  bool PrepareSolver(vtkImageData* medium);

private:
  vtkPhotonDiffusionSchedule(const vtkPhotonDiffusionSchedule&) = delete;
  void operator=(const vtkPhotonDiffusionSchedule&) = delete;
};

#endif
