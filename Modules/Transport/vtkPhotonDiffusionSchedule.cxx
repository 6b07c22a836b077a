#include "vtkPhotonDiffusionSchedule.h"

#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkIntArray.h"
#include "vtkLatticeBoltzmannSolver.h"
#include "vtkMediumValidator.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPhotonTracer.h"
#include "vtkPointData.h"
#include "vtkRefractaGridFrame.h"
#include "vtkRefractaLightingVolume.h"
#include "vtkRefractaMedium.h"

#include <algorithm>
#include <chrono>
#include <vector>

vtkStandardNewMacro(vtkPhotonDiffusionSchedule);

namespace
{

double Seconds(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Forwards a stage's progress to the schedule, scaled into [First, Last], and the schedule's
// AbortExecute to the stage (the tracer's AbortExecute, or the solver's AbortSolve).
class StageProgress : public vtkCommand
{
public:
  static StageProgress* New() { return new StageProgress; }
  void Execute(vtkObject* caller, unsigned long, void* data) override
  {
    const double p = *static_cast<double*>(data);
    this->Schedule->UpdateProgress(
      std::max(this->Schedule->GetProgress(), this->First + (this->Last - this->First) * p));
    if (this->Schedule->GetAbortExecute())
    {
      if (auto* tracer = vtkPhotonTracer::SafeDownCast(caller))
      {
        tracer->SetAbortExecute(1);
      }
      else if (auto* solver = vtkLatticeBoltzmannSolver::SafeDownCast(caller))
      {
        solver->SetAbortSolve(true);
      }
    }
  }
  vtkAlgorithm* Schedule = nullptr;
  double First = 0.0;
  double Last = 1.0;
};

void AddScalar(vtkFieldData* fd, const char* name, double value)
{
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->InsertNextValue(value);
  fd->AddArray(a);
}
}

//------------------------------------------------------------------------------
vtkPhotonDiffusionSchedule::vtkPhotonDiffusionSchedule()
  : Tracer(vtkSmartPointer<vtkPhotonTracer>::New())
  , Solver(vtkSmartPointer<vtkLatticeBoltzmannSolver>::New())
{
}
vtkPhotonDiffusionSchedule::~vtkPhotonDiffusionSchedule() = default;

vtkPhotonTracer* vtkPhotonDiffusionSchedule::GetPhotonTracer()
{
  return this->Tracer;
}
vtkLatticeBoltzmannSolver* vtkPhotonDiffusionSchedule::GetSolver()
{
  return this->Solver;
}

//------------------------------------------------------------------------------
vtkMTimeType vtkPhotonDiffusionSchedule::GetMTime()
{
  return std::max({ this->Superclass::GetMTime(),
    static_cast<vtkObject*>(this->Tracer.GetPointer())->GetMTime(), this->Solver->GetMTime() });
}

//------------------------------------------------------------------------------
int vtkPhotonDiffusionSchedule::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

//------------------------------------------------------------------------------
bool vtkPhotonDiffusionSchedule::PrepareSolver(vtkImageData* medium)
{
  vtkLatticeBoltzmannSolver* solver = this->Solver;
  this->LastRunWarm = false;
  if (medium && medium == this->TracerInputSource && medium->GetMTime() == this->SolverMediumTime &&
    solver->GetMTime() == this->SolverSettingsTime)
  {
    this->LastRunWarm = this->WarmStart && this->HasField;
    return this->LastRunWarm ? solver->ClearSource() : solver->Restart();
  }
  this->HasField = false;
  this->SolverMediumTime = 0;
  vtkNew<vtkMediumValidator> validator;
  if (!validator->Validate(medium))
  {
    vtkErrorMacro("Input 0 is not a valid medium: " << validator->GetErrorMessage());
    return false;
  }
  int dims[3];
  double spacing[3];
  medium->GetDimensions(dims);
  medium->GetSpacing(spacing);
  const std::vector<float> extinction =
    vtkRefractaMedium::ReadArray(medium, vtkRefractaMedium::ExtinctionName(), 3, 0.0f);
  const std::vector<float> albedo =
    vtkRefractaMedium::ReadArray(medium, vtkRefractaMedium::AlbedoName(), 3, 0.0f);
  const std::vector<float> anisotropy =
    vtkRefractaMedium::ReadArray(medium, vtkRefractaMedium::AnisotropyName(), 1, 0.0f);
  if (!solver->Initialize(dims, spacing, extinction.data(), albedo.data(), anisotropy.data()))
  {
    vtkErrorMacro("The Lattice-Boltzmann solver could not be set up (see the previous message).");
    return false;
  }
  ++this->NumberOfSolverInitializations;
  this->SolverMediumTime = medium->GetMTime();
  this->SolverSettingsTime = solver->GetMTime();
  return true;
}

//------------------------------------------------------------------------------
int vtkPhotonDiffusionSchedule::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  const auto start = std::chrono::steady_clock::now();
  vtkImageData* medium = vtkImageData::GetData(inputVector[0]);
  vtkImageData* output = vtkImageData::GetData(outputVector);
  output->Initialize();
  this->LastRunAborted = this->LastRunInterleaved = false;
  if (!this->PrepareSolver(medium))
  {
    return 0;
  }
  vtkLatticeBoltzmannSolver* solver = this->Solver;

  // Photon pass, with the diffusion interleaved between its chunks.
  if (!this->TracerInput || medium != this->TracerInputSource ||
    medium->GetMTime() != this->TracerInputTime)
  {
    this->TracerInput = vtkSmartPointer<vtkImageData>::New();
    this->TracerInput->ShallowCopy(medium);
    this->TracerInputSource = medium;
    this->TracerInputTime = medium->GetMTime();
  }
  this->Tracer->SetInputData(this->TracerInput);
  // A warm start marches without interleaving: the chunks' partial sources would first pull the
  // kept field down towards their own, smaller, fixed points.
  // The first-collision split hands the lattice its source only at the end of the march: the
  // chunks' deposits are S1, not that source, so it runs sequentially.
  const bool interleaved =
    this->Mode == INTERLEAVED && !this->LastRunWarm && this->Tracer->GetScatteringOrders() == 0;
  this->LastRunInterleaved = interleaved;
  this->Tracer->SetStepsPerChunk(interleaved ? this->StepsPerChunk : 0);
  int diffusionSteps = 0;
  bool callbackFailed = false;
  const int perChunk = this->DiffusionStepsPerChunk;
  this->Tracer->SetChunkCallback(
    [solver, perChunk, &diffusionSteps, &callbackFailed](cl_mem deposits, double rf, double df, int)
    {
      const int before = solver->GetStepsDone();
      if (!solver->SetSourceFromFixedPoint(deposits, rf, df) ||
        (perChunk > 0 && !solver->Iterate(perChunk, false)))
      {
        callbackFailed = true;
        return false;
      }
      diffusionSteps += solver->GetStepsDone() - before;
      return true;
    });
  // Progress: the photon pass up to PhotonShare, the final solve the rest (shares measured on the
  // previous run, half and half on the first).
  vtkNew<StageProgress> tracerProgress;
  tracerProgress->Schedule = this;
  tracerProgress->Last = this->PhotonShare;
  const unsigned long tracerObserver =
    this->Tracer->AddObserver(vtkCommand::ProgressEvent, tracerProgress);
  this->Tracer->SetAbortExecute(0);
  this->Tracer->Update();
  this->Tracer->RemoveObserver(tracerObserver);
  this->Tracer->SetChunkCallback(nullptr);
  if (this->Tracer->GetLastRunAborted() || this->GetAbortExecute())
  {
    // An abort is not an error: empty output, no message.
    this->Tracer->SetAbortExecute(0);
    this->LastRunAborted = true;
    return 1;
  }
  vtkImageData* lighting = this->Tracer->GetOutput();
  if (callbackFailed || !lighting || !vtkRefractaGridFrame::SameGrid(lighting, medium) ||
    !lighting->GetPointData()->GetArray(vtkRefractaLightingVolume::RadianceName()))
  {
    vtkErrorMacro("The photon pass failed (see the previous message).");
    return 0;
  }
  const double marching = Seconds(start);

  // Final source: the tracer's S1 (smoothed as it outputs it), or with the first-collision split
  // the light it handed on; the lattice continues from its state (interleaved), from the last
  // run's field (warm start) or from zero (sequential).
  const auto solveStart = std::chrono::steady_clock::now();
  if (!interleaved && !this->LastRunWarm && !solver->ResetState())
  {
    return 0;
  }
  vtkNew<StageProgress> solverProgress;
  solverProgress->Schedule = this;
  solverProgress->First = this->PhotonShare;
  solverProgress->Last = 0.99;
  const unsigned long solverObserver =
    solver->AddObserver(vtkCommand::ProgressEvent, solverProgress);
  // The source from the tracer's arrays: from their device copies when the tracer kept them
  // (vtkPhotonTracer::KeepDeviceCopies), the volume caustic's bricks folded back in on the host.
  const bool solved = solver->SetSourceFromLighting(lighting) && solver->Solve();
  solver->RemoveObserver(solverObserver);
  if (!solved)
  {
    vtkErrorMacro("The Lattice-Boltzmann solver failed (see the previous message).");
    output->Initialize();
    return 0;
  }
  this->HasField = true; // converged or stopped part way: either is a valid start
  if (solver->GetAborted() || this->GetAbortExecute())
  {
    output->Initialize();
    this->LastRunAborted = true;
    return 1;
  }
  vtkNew<vtkFloatArray> ms;
  ms->SetName(vtkRefractaLightingVolume::MultipleScatteringName());
  // The lattice's S_ms plus, with the first-collision split, the photons' own (orders up to k).
  if (!solver->ComputeMultipleScattering(ms,
        lighting->GetPointData()->GetArray(vtkRefractaLightingVolume::MultipleScatteringName())))
  {
    output->Initialize();
    return 0;
  }
  const double finalSolve = Seconds(solveStart);
  if (marching + finalSolve > 0)
  {
    this->PhotonShare = std::min(0.95, std::max(0.05, marching / (marching + finalSolve)));
  }

  // S_ms's direction: the lattice's flux, with the split merged with the photons' orders'.
  vtkNew<vtkFloatArray> msDirection;
  msDirection->SetName(vtkRefractaLightingVolume::MultipleScatteringDirectionName());
  const bool split = vtkRefractaLightingVolume::HasPhotonMultipleScattering(lighting);
  if (!solver->ComputeMultipleScatteringDirection(
        msDirection, split ? ms.GetPointer() : nullptr, split ? lighting : nullptr))
  {
    output->Initialize();
    return 0;
  }

  output->CopyStructure(medium);
  vtkRefractaLightingVolume::PassSingleScattering(lighting, output);
  output->GetPointData()->AddArray(ms);
  output->GetPointData()->AddArray(msDirection);
  vtkFieldData* fd = output->GetFieldData();
  fd->PassData(lighting->GetFieldData());
  vtkNew<vtkIntArray> iterations;
  iterations->SetName("LatticeBoltzmannIterations");
  iterations->InsertNextValue(solver->GetIterations());
  vtkNew<vtkIntArray> converged;
  converged->SetName("LatticeBoltzmannConverged");
  converged->InsertNextValue(solver->GetConverged() ? 1 : 0);
  fd->AddArray(iterations);
  fd->AddArray(converged);
  AddScalar(fd, "LatticeBoltzmannResidual", solver->GetResidual());
  AddScalar(fd, "ScheduleMode", interleaved ? INTERLEAVED : SEQUENTIAL);
  AddScalar(fd, "ScheduleWarmStart", this->LastRunWarm ? 1 : 0);
  AddScalar(fd, "ScheduleChunks", this->Tracer->GetNumberOfChunks());
  AddScalar(fd, "ScheduleDiffusionStepsDuringMarching", diffusionSteps);
  AddScalar(fd, "ScheduleMarchingSeconds", marching);
  AddScalar(fd, "ScheduleFinalSolveSeconds", finalSolve);
  AddScalar(fd, "ScheduleTotalSeconds", Seconds(start));
  return 1;
}

//------------------------------------------------------------------------------
void vtkPhotonDiffusionSchedule::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Mode: " << (this->Mode == INTERLEAVED ? "interleaved" : "sequential") << "\n";
  os << indent << "StepsPerChunk: " << this->StepsPerChunk << "\n";
  os << indent << "DiffusionStepsPerChunk: " << this->DiffusionStepsPerChunk << "\n";
  os << indent << "WarmStart: " << this->WarmStart << "\n";
  os << indent << "LastRunWarm: " << this->LastRunWarm << "\n";
  os << indent << "LastRunInterleaved: " << this->LastRunInterleaved << "\n";
  os << indent << "LastRunAborted: " << this->LastRunAborted << "\n";
}
