#include "vtkRefractaRenderPipeline.h"

#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkEffectPlan.h"
#include "vtkImageData.h"
#include "vtkLatticeBoltzmannLighting.h"
#include "vtkLatticeBoltzmannSolver.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkLightRaySingleScattering.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkMediumValidator.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpenCLContext.h"
#include "vtkOutputWindow.h"
#include "vtkPhotonDiffusionSchedule.h"
#include "vtkPhotonTracer.h"
#include "vtkPolyData.h"
#include "vtkRefractaSurfaceSet.h"
#include "vtkRefractaViewPass.h"
#include "vtkSceneAnalysis.h"
#include "vtkSmartPointer.h"
#include "vtkTimeStamp.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <string>

vtkStandardNewMacro(vtkRefractaRenderPipeline);

namespace
{
// Surfaces with something to hit (the plan depends on their presence only).
int CountSurfaces(vtkRefractaSurfaceSet* set)
{
  return set ? set->GetNumberOfNonEmptySurfaces() : 0;
}
}

namespace
{
// Share of a full render each stage takes when it has not run yet, from the default scene on the
// 2-core PoCL CPU (plan 0.1 s, light passes 20-30 s, view pass 2-6 s); after a stage has run its
// own last duration is used instead.
constexpr std::array<double, vtkRefractaRenderPipeline::NUMBER_OF_STAGES> DefaultStageSeconds = {
  0.1, 20.0, 4.0
};

// The light-independent decisions: while they stay the same, the pruned medium stays valid.
constexpr int LightIndependentEffects[] = { vtkEffectPlan::REFRACTION, vtkEffectPlan::ABSORPTION,
  vtkEffectPlan::EMISSION };

double SecondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}
}

struct vtkRefractaRenderPipeline::Internals
{
  vtkSmartPointer<vtkImageData> Medium;
  vtkSmartPointer<vtkImageData> LightingData;
  vtkSmartPointer<vtkLightCollection> Lights = vtkSmartPointer<vtkLightCollection>::New();
  vtkSmartPointer<vtkCamera> Camera;
  vtkSmartPointer<vtkMatrix4x4> PropMatrix;
  vtkSmartPointer<vtkOpenCLContext> Context;

  vtkNew<vtkSceneAnalysis> Analysis;
  vtkNew<vtkEffectPlan> Plan;
  vtkNew<vtkPhotonDiffusionSchedule> Schedule;
  vtkNew<vtkLightRaySingleScattering> LightRays;       // straight light (vtkEffectPlan's choice)
  vtkNew<vtkLatticeBoltzmannLighting> LightRayLattice; // multiple scattering from its output
  vtkNew<vtkRefractaViewPass> ViewPass;

  vtkSmartPointer<vtkRefractaSurfaceSet> Surfaces;
  int PlannedSurfaces = 0; // surfaces with triangles when the plan last ran

  // Products of the stages.
  vtkSmartPointer<vtkImageData> Planned;
  vtkSmartPointer<vtkLightCollection> DataLights; // the lights in the medium's data frame
  vtkSmartPointer<vtkImageData> Lighting;
  std::vector<float> Image;
  std::vector<float> Transmittance;

  // What each stage saw when it last completed.
  vtkTimeStamp PlanTime;
  vtkTimeStamp LightTime;
  vtkTimeStamp ViewTime;
  vtkImageData* PlannedFrom = nullptr;
  std::vector<vtkLight*> LightList;
  std::array<bool, vtkEffectPlan::NUMBER_OF_EFFECTS> Decisions{};
  vtkCamera* ViewCamera = nullptr;
  int ViewSize[2] = { 0, 0 };
  std::vector<float> ViewDepth;
  bool PlanDone = false;
  bool LightDone = false;
  bool ViewDone = false;

  // The render in progress.
  bool Ran[NUMBER_OF_STAGES] = { false, false, false };
  double Seconds[NUMBER_OF_STAGES] = { 0, 0, 0 };
  double LastSeconds[NUMBER_OF_STAGES] = { -1, -1, -1 };
  double StageStart[NUMBER_OF_STAGES] = { 0, 0, 0 }; // progress at which each stage starts
  double StageWeight[NUMBER_OF_STAGES] = { 0, 0, 0 };
  double Progress = 0;
  bool Abort = false;
  vtkAlgorithm* Running = nullptr;
  std::string LastError;
  vtkSmartPointer<vtkCallbackCommand> EventForwarder;

  // A light pass's progress as a fraction of the lighting stage: the light rays and the lattice
  // on their output share it half and half when both run; every other pass has it whole.
  double LightingFraction(vtkObject* caller, double fraction) const
  {
    if (this->Running == this->LightRayLattice.GetPointer())
    {
      if (caller == this->LightRays.GetPointer())
      {
        return 0.5 * fraction;
      }
      if (caller == this->LightRayLattice.GetPointer())
      {
        return 0.5 + 0.5 * fraction;
      }
    }
    return fraction;
  }

  vtkOpenCLContext* GetContext()
  {
    return this->Context ? this->Context.Get() : vtkOpenCLContext::GetDefault();
  }

  std::vector<vtkLight*> CurrentLightList()
  {
    std::vector<vtkLight*> list;
    vtkCollectionSimpleIterator it;
    this->Lights->InitTraversal(it);
    while (vtkLight* light = this->Lights->GetNextLight(it))
    {
      list.push_back(light);
    }
    return list;
  }
};

//------------------------------------------------------------------------------
vtkRefractaRenderPipeline::vtkRefractaRenderPipeline()
  : Internal(new Internals)
{
  // Forward the passes' progress into this pipeline's, and pass an abort on to them.
  vtkNew<vtkCallbackCommand> forward;
  forward->SetClientData(this);
  forward->SetCallback(
    [](vtkObject* caller, unsigned long, void* clientData, void* callData)
    {
      auto* self = static_cast<vtkRefractaRenderPipeline*>(clientData);
      Internals& in = *self->Internal;
      if (in.Abort)
      {
        if (auto* algorithm = vtkAlgorithm::SafeDownCast(caller))
        {
          algorithm->SetAbortExecute(1);
        }
        else if (auto* view = vtkRefractaViewPass::SafeDownCast(caller))
        {
          view->SetAbortRender(true);
        }
      }
      if (callData)
      {
        const int stage = vtkRefractaViewPass::SafeDownCast(caller) ? VIEW : LIGHTING;
        self->ReportProgress(stage, in.LightingFraction(caller, *static_cast<double*>(callData)));
      }
    });
  this->Internal->Schedule->AddObserver(vtkCommand::ProgressEvent, forward);
  this->Internal->LightRays->AddObserver(vtkCommand::ProgressEvent, forward);
  this->Internal->LightRayLattice->AddObserver(vtkCommand::ProgressEvent, forward);
  static_cast<vtkObject*>(this->Internal->Schedule->GetPhotonTracer())
    ->AddObserver(vtkCommand::ProgressEvent, forward);
  this->Internal->ViewPass->AddObserver(vtkCommand::ProgressEvent, forward);
}

vtkRefractaRenderPipeline::~vtkRefractaRenderPipeline() = default;

//------------------------------------------------------------------------------
void vtkRefractaRenderPipeline::SetEventOwner(vtkObject* owner)
{
  Internals& in = *this->Internal;
  vtkObject* sources[] = { this, in.Schedule, in.Schedule->GetPhotonTracer(),
    in.Schedule->GetSolver(), in.LightRays, in.LightRayLattice, in.ViewPass };
  for (vtkObject* source : sources)
  {
    source->RemoveObservers(vtkCommand::ErrorEvent, in.EventForwarder);
    source->RemoveObservers(vtkCommand::WarningEvent, in.EventForwarder);
  }
  in.EventForwarder = nullptr;
  if (!owner)
  {
    return;
  }
  in.EventForwarder = vtkSmartPointer<vtkCallbackCommand>::New();
  in.EventForwarder->SetClientData(owner);
  in.EventForwarder->SetCallback(
    [](vtkObject*, unsigned long event, void* clientData, void* callData)
    {
      auto* front = static_cast<vtkObject*>(clientData);
      const char* text = static_cast<const char*>(callData);
      if (front->HasObserver(event))
      {
        front->InvokeEvent(event, callData);
      }
      else if (event == vtkCommand::ErrorEvent)
      {
        vtkOutputWindowDisplayErrorText(text);
      }
      else
      {
        vtkOutputWindowDisplayWarningText(text);
      }
    });
  for (vtkObject* source : sources)
  {
    source->AddObserver(vtkCommand::ErrorEvent, in.EventForwarder);
    source->AddObserver(vtkCommand::WarningEvent, in.EventForwarder);
  }
}

const char* vtkRefractaRenderPipeline::GetStageName(int stage)
{
  static const char* const names[] = { "plan", "lighting", "view" };
  return stage >= 0 && stage < NUMBER_OF_STAGES ? names[stage] : "";
}

//------------------------------------------------------------------------------
void vtkRefractaRenderPipeline::SetMedium(vtkImageData* medium)
{
  if (this->Internal->Medium != medium)
  {
    this->Internal->Medium = medium;
    this->Modified();
  }
}

vtkImageData* vtkRefractaRenderPipeline::GetMedium()
{
  return this->Internal->Medium;
}

void vtkRefractaRenderPipeline::SetLightingData(vtkImageData* lighting)
{
  if (this->Internal->LightingData != lighting)
  {
    this->Internal->LightingData = lighting;
    this->Modified();
  }
}

vtkImageData* vtkRefractaRenderPipeline::GetLightingData()
{
  return this->Internal->LightingData;
}

void vtkRefractaRenderPipeline::SetSurfaces(vtkRefractaSurfaceSet* surfaces)
{
  if (this->Internal->Surfaces != surfaces)
  {
    this->Internal->Surfaces = surfaces;
    this->Modified();
  }
}

vtkRefractaSurfaceSet* vtkRefractaRenderPipeline::GetSurfaces()
{
  return this->Internal->Surfaces;
}

void vtkRefractaRenderPipeline::AddLight(vtkLight* light)
{
  if (light)
  {
    this->Internal->Lights->AddItem(light);
  }
}

void vtkRefractaRenderPipeline::RemoveAllLights()
{
  this->Internal->Lights->RemoveAllItems();
}

void vtkRefractaRenderPipeline::SetLights(vtkLightCollection* lights)
{
  // Front ends hand over their renderer's lights on every frame: keep the collection (and its
  // MTime) when they are the same lights, so that only a real light change re-lights.
  std::vector<vtkLight*> list;
  if (lights)
  {
    vtkCollectionSimpleIterator it;
    lights->InitTraversal(it);
    while (vtkLight* light = lights->GetNextLight(it))
    {
      list.push_back(light);
    }
  }
  if (list == this->Internal->CurrentLightList())
  {
    return;
  }
  this->RemoveAllLights();
  for (vtkLight* light : list)
  {
    this->AddLight(light);
  }
}

vtkLightCollection* vtkRefractaRenderPipeline::GetLights()
{
  return this->Internal->Lights;
}

// The camera drives the view stage through its own MTime; setting it does not touch this
// object's MTime, which would re-plan.
void vtkRefractaRenderPipeline::SetCamera(vtkCamera* camera)
{
  this->Internal->Camera = camera;
}

vtkCamera* vtkRefractaRenderPipeline::GetCamera()
{
  return this->Internal->Camera;
}

void vtkRefractaRenderPipeline::SetPropMatrix(vtkMatrix4x4* matrix)
{
  if (this->Internal->PropMatrix != matrix)
  {
    this->Internal->PropMatrix = matrix;
    this->Modified();
  }
}

vtkMatrix4x4* vtkRefractaRenderPipeline::GetPropMatrix()
{
  return this->Internal->PropMatrix;
}

vtkSceneAnalysis* vtkRefractaRenderPipeline::GetSceneAnalysis()
{
  return this->Internal->Analysis;
}

vtkEffectPlan* vtkRefractaRenderPipeline::GetEffectPlan()
{
  return this->Internal->Plan;
}

vtkPhotonTracer* vtkRefractaRenderPipeline::GetPhotonTracer()
{
  return this->Internal->Schedule->GetPhotonTracer();
}

void vtkRefractaRenderPipeline::SetSingleScatteringMethod(int method)
{
  this->Internal->Plan->SetSingleScatteringMethod(method);
}

int vtkRefractaRenderPipeline::GetSingleScatteringMethod()
{
  return this->Internal->Plan->GetSingleScatteringMethod();
}

vtkLightRaySingleScattering* vtkRefractaRenderPipeline::GetLightRays()
{
  return this->Internal->LightRays;
}

vtkLatticeBoltzmannSolver* vtkRefractaRenderPipeline::GetLatticeSolver()
{
  return this->Internal->Schedule->GetSolver();
}

vtkRefractaViewPass* vtkRefractaRenderPipeline::GetViewPass()
{
  return this->Internal->ViewPass;
}

void vtkRefractaRenderPipeline::SetContext(vtkOpenCLContext* context)
{
  Internals& in = *this->Internal;
  if (in.Context != context)
  {
    in.Context = context;
    in.ViewPass->SetContext(context);
    in.Schedule->GetPhotonTracer()->SetContext(context);
    in.Schedule->GetSolver()->SetContext(context);
    in.PlanDone = false; // device buffers live in the old context
    this->Modified();
  }
}

vtkOpenCLContext* vtkRefractaRenderPipeline::GetContext()
{
  return this->Internal->GetContext();
}

//------------------------------------------------------------------------------
// Straight light: the light-ray pass (and the lattice on its output when multiple scattering is
// on), with the photon tracer's light extents so that both methods see the same lights.
vtkAlgorithm* vtkRefractaRenderPipeline::PrepareLightRays(vtkPhotonTracer* tracer, int method)
{
  Internals& in = *this->Internal;
  vtkLightRaySingleScattering* rays = in.LightRays;
  rays->SetContext(in.GetContext());
  rays->SetMethod(method == vtkEffectPlan::INTERPOLATED ? vtkLightRaySingleScattering::INTERPOLATED
                                                        : vtkLightRaySingleScattering::LIGHT_RAYS);
  rays->SetLights(in.DataLights);
  rays->SetSurfaces(in.Surfaces);
  rays->SetMediumToWorld(in.PropMatrix);
  rays->SetLightRadius(tracer->GetLightRadius());
  rays->SetDirectionalLightAngularRadius(tracer->GetDirectionalLightAngularRadius());
  rays->SetInputData(in.Planned);
  // An abort reaches the light rays through their progress observer; a new render clears it
  // (the lattice's, when the lattice runs, is cleared with the pass's after the abort).
  rays->SetAbortExecute(0);
  if (!in.Plan->IsEnabled(vtkEffectPlan::MULTIPLE_SCATTERING))
  {
    return rays;
  }
  vtkLatticeBoltzmannLighting* lattice = in.LightRayLattice;
  lattice->SetContext(in.GetContext());
  lattice->SetTolerance(this->GetLatticeSolver()->GetTolerance());
  lattice->SetBlockSize(this->GetLatticeSolver()->GetBlockSize());
  lattice->SetInputData(in.Planned);
  lattice->SetInputConnection(1, rays->GetOutputPort());
  return lattice;
}

//------------------------------------------------------------------------------
void vtkRefractaRenderPipeline::SetOctreeTolerance(double epsilon)
{
  vtkPhotonTracer* tracer = this->GetPhotonTracer();
  tracer->SetPrimaryTolerance(epsilon);
  tracer->SetSecondaryTolerance(4.0 * epsilon);
}

void vtkRefractaRenderPipeline::SetQuality(int quality)
{
  vtkEffectPlan* plan = this->Internal->Plan;
  plan->SetQuality(quality);
  if (plan->GetQuality() != quality)
  {
    return; // the plan reported the unknown preset
  }
  vtkPhotonTracer* tracer = this->GetPhotonTracer();
  tracer->SetNumberOfPhotons(plan->GetRecommendedNumberOfPhotons());
  tracer->SetMinimumStep(plan->GetRecommendedPhotonMinimumStep());
  this->SetOctreeTolerance(plan->GetRecommendedOctreeTolerance());
  vtkLatticeBoltzmannSolver* solver = this->GetLatticeSolver();
  solver->SetTolerance(plan->GetRecommendedLatticeTolerance());
  solver->SetBlockSize(plan->GetRecommendedLatticeBlockSize());
  this->Internal->ViewPass->SetStepSize(plan->GetRecommendedViewStep());
}

//------------------------------------------------------------------------------
const std::vector<float>& vtkRefractaRenderPipeline::GetImage() const
{
  return this->Internal->Image;
}

const std::vector<float>& vtkRefractaRenderPipeline::GetTransmittance() const
{
  return this->Internal->Transmittance;
}

vtkImageData* vtkRefractaRenderPipeline::GetPlannedMedium()
{
  return this->Internal->Planned;
}

vtkImageData* vtkRefractaRenderPipeline::GetLighting()
{
  return this->Internal->Lighting;
}

void vtkRefractaRenderPipeline::AbortRender()
{
  Internals& in = *this->Internal;
  in.Abort = true;
  if (in.Running)
  {
    in.Running->SetAbortExecute(1);
  }
  in.ViewPass->SetAbortRender(true); // cleared at the start of the next Render()
}

bool vtkRefractaRenderPipeline::GetStageRan(int stage) const
{
  return stage >= 0 && stage < NUMBER_OF_STAGES && this->Internal->Ran[stage];
}

double vtkRefractaRenderPipeline::GetStageSeconds(int stage) const
{
  return stage >= 0 && stage < NUMBER_OF_STAGES ? this->Internal->Seconds[stage] : 0.0;
}

//------------------------------------------------------------------------------
vtkMTimeType vtkRefractaRenderPipeline::GetLightsMTime()
{
  vtkMTimeType t = this->Internal->Lights->GetMTime();
  for (vtkLight* light : this->Internal->CurrentLightList())
  {
    t = std::max(t, light->GetMTime());
    if (vtkMatrix4x4* m = light->GetTransformMatrix())
    {
      t = std::max(t, m->GetMTime()); // camera lights follow the camera through this matrix
    }
  }
  return t;
}

vtkMTimeType vtkRefractaRenderPipeline::GetInputsMTime()
{
  Internals& in = *this->Internal;
  vtkMTimeType t = std::max({ this->GetMTime(), in.Plan->GetMTime(), in.Schedule->GetMTime(),
    in.ViewPass->GetMTime(), this->GetLightsMTime() });
  if (in.Camera)
  {
    t = std::max(t, in.Camera->GetMTime());
  }
  if (in.PropMatrix)
  {
    t = std::max(t, in.PropMatrix->GetMTime());
  }
  if (vtkImageData* env = in.ViewPass->GetEnvironmentMap())
  {
    t = std::max(t, env->GetMTime());
  }
  if (in.Surfaces)
  {
    t = std::max(t, in.Surfaces->GetMTime());
  }
  return t;
}

bool vtkRefractaRenderPipeline::PlanIsStale()
{
  Internals& in = *this->Internal;
  const vtkMTimeType planTime = in.PlanTime.GetMTime();
  return !in.PlanDone || in.Medium != in.PlannedFrom || in.Medium->GetMTime() > planTime ||
    this->GetMTime() > planTime || in.Plan->GetMTime() > planTime ||
    in.CurrentLightList() != in.LightList || this->GetLightsMTime() > planTime ||
    (in.PropMatrix && in.PropMatrix->GetMTime() > planTime) ||
    in.Analysis->GetSurfaces() != in.Surfaces || CountSurfaces(in.Surfaces) != in.PlannedSurfaces;
}

bool vtkRefractaRenderPipeline::LightingIsStale()
{
  Internals& in = *this->Internal;
  const vtkMTimeType lightTime = in.LightTime.GetMTime();
  return !in.LightDone || in.PlanTime.GetMTime() > lightTime ||
    in.Schedule->GetMTime() > lightTime ||
    (in.LightingData && in.LightingData->GetMTime() > lightTime) ||
    (in.Surfaces && in.Surfaces->GetMTime() > lightTime) ||
    (this->BackgroundIlluminates && this->BackgroundIsNewerThan(lightTime));
}

// Whether the view pass's background (colour, map, orientation) changed after `time`: with
// BackgroundIlluminates it is a light.
bool vtkRefractaRenderPipeline::BackgroundIsNewerThan(vtkMTimeType time)
{
  Internals& in = *this->Internal;
  vtkImageData* env = in.ViewPass->GetEnvironmentMap();
  return in.ViewPass->GetMTime() > time || (env && env->GetMTime() > time);
}

//------------------------------------------------------------------------------
void vtkRefractaRenderPipeline::ReportProgress(int stage, double fraction)
{
  Internals& in = *this->Internal;
  fraction = std::min(std::max(fraction, 0.0), 1.0);
  double progress = in.StageStart[stage] + in.StageWeight[stage] * fraction;
  if (progress > in.Progress)
  {
    in.Progress = progress;
    this->InvokeEvent(vtkCommand::ProgressEvent, &progress);
  }
}

//------------------------------------------------------------------------------
bool vtkRefractaRenderPipeline::Render(int width, int height, const float* depthLimit)
{
  return this->RunStages(true, width, height, depthLimit);
}

//------------------------------------------------------------------------------
bool vtkRefractaRenderPipeline::UpdateLighting()
{
  return this->RunStages(false, 0, 0, nullptr);
}

//------------------------------------------------------------------------------
bool vtkRefractaRenderPipeline::RunStages(
  bool withView, int width, int height, const float* depthLimit)
{
  Internals& in = *this->Internal;
  in.Abort = false;
  in.ViewPass->SetAbortRender(false);
  this->LastRenderAborted = false;
  std::fill(std::begin(in.Ran), std::end(in.Ran), false);
  std::fill(std::begin(in.Seconds), std::end(in.Seconds), 0.0);
  if (!in.Medium)
  {
    vtkErrorMacro("No medium: call SetMedium() with a Refracta medium (vtkImageData) first.");
    return false;
  }
  if (withView && !in.Camera)
  {
    vtkErrorMacro("No camera: call SetCamera() with a vtkCamera first.");
    return false;
  }
  if (withView && (width < 1 || height < 1))
  {
    vtkErrorMacro("The image size " << width << " x " << height << " has no pixels.");
    return false;
  }

  // Which stages will run decides how the progress range is shared among them; without a light
  // that is on, the light stage only hands over the lighting data (or nothing).
  const bool plan = this->PlanIsStale();
  const bool light = plan || this->LightingIsStale();
  bool anyLightOn = false;
  for (vtkLight* l : in.CurrentLightList())
  {
    anyLightOn = anyLightOn || l->GetSwitch();
  }
  const bool stages[NUMBER_OF_STAGES] = { plan, light, withView };
  double total = 0;
  for (int s = 0; s < NUMBER_OF_STAGES; ++s)
  {
    double seconds = in.LastSeconds[s] >= 0 ? in.LastSeconds[s] + 1e-3 : DefaultStageSeconds[s];
    if (s == LIGHTING && (!anyLightOn || in.LightingData))
    {
      seconds = 1e-3;
    }
    in.StageWeight[s] = stages[s] ? seconds : 0.0;
    total += in.StageWeight[s];
  }
  double start = 0;
  for (int s = 0; s < NUMBER_OF_STAGES; ++s)
  {
    in.StageWeight[s] = total > 0 ? in.StageWeight[s] / total : 0.0; // 0: lighting up to date
    in.StageStart[s] = start;
    start += in.StageWeight[s];
  }
  in.Progress = 0;
  double zero = 0;
  this->InvokeEvent(vtkCommand::ProgressEvent, &zero);

  // An abort between stages stops before the next one starts.
  auto aborted = [&]()
  {
    this->LastRenderAborted = this->LastRenderAborted || in.Abort;
    return this->LastRenderAborted;
  };
  auto run = [&](int stage, bool (vtkRefractaRenderPipeline::*body)()) -> bool
  {
    if (aborted())
    {
      return false;
    }
    const char* name = GetStageName(stage);
    this->InvokeEvent(vtkCommand::StartEvent, const_cast<char*>(name));
    const auto t0 = std::chrono::steady_clock::now();
    const bool ok = (this->*body)();
    in.Seconds[stage] = SecondsSince(t0);
    in.Ran[stage] = true;
    if (ok)
    {
      in.LastSeconds[stage] = in.Seconds[stage];
      this->ReportProgress(stage, 1.0);
    }
    this->InvokeEvent(vtkCommand::EndEvent, const_cast<char*>(name));
    return ok;
  };
  if (plan && !run(PLAN, &vtkRefractaRenderPipeline::RunPlan))
  {
    return false;
  }
  if (light && !run(LIGHTING, &vtkRefractaRenderPipeline::RunLighting))
  {
    return false;
  }
  if (!withView)
  {
    return true;
  }

  // The view stage.
  const vtkMTimeType viewTime = in.ViewTime.GetMTime();
  vtkImageData* env = in.ViewPass->GetEnvironmentMap();
  const size_t pixels = static_cast<size_t>(width) * height;
  const bool depthChanged = depthLimit ? in.ViewDepth.size() != pixels ||
      !std::equal(in.ViewDepth.begin(), in.ViewDepth.end(), depthLimit)
                                       : !in.ViewDepth.empty();
  const bool view = light || !in.ViewDone || in.Camera != in.ViewCamera ||
    in.Camera->GetMTime() > viewTime || in.ViewPass->GetMTime() > viewTime ||
    (env && env->GetMTime() > viewTime) ||
    (in.PropMatrix && in.PropMatrix->GetMTime() > viewTime) || width != in.ViewSize[0] ||
    height != in.ViewSize[1] || depthChanged;
  if (!view)
  {
    this->ReportProgress(VIEW, 1.0);
    return true;
  }
  if (aborted())
  {
    return false;
  }
  this->InvokeEvent(vtkCommand::StartEvent, const_cast<char*>(GetStageName(VIEW)));
  const auto t0 = std::chrono::steady_clock::now();
  const bool ok = this->RunView(width, height, depthLimit);
  in.Seconds[VIEW] = SecondsSince(t0);
  in.Ran[VIEW] = true;
  if (ok)
  {
    in.LastSeconds[VIEW] = in.Seconds[VIEW];
    this->ReportProgress(VIEW, 1.0);
  }
  this->InvokeEvent(vtkCommand::EndEvent, const_cast<char*>(GetStageName(VIEW)));
  return ok;
}

//------------------------------------------------------------------------------
bool vtkRefractaRenderPipeline::RunPlan()
{
  Internals& in = *this->Internal;
  in.PlanDone = in.LightDone = in.ViewDone = false;
  vtkNew<vtkMediumValidator> validator;
  if (!validator->Validate(in.Medium))
  {
    // Said once: a front end re-rendering the same bad medium does not repeat it.
    const std::string message =
      std::string("The medium is not a valid Refracta medium: ") + validator->GetErrorMessage();
    if (message != in.LastError)
    {
      vtkErrorMacro(<< message);
      in.LastError = message;
    }
    in.Planned = nullptr;
    return false;
  }

  // The lights in the medium's data frame (the inverse of the placement).
  vtkNew<vtkMatrix4x4> toData;
  if (in.PropMatrix)
  {
    vtkMatrix4x4::Invert(in.PropMatrix, toData);
  }
  in.DataLights = vtkSmartPointer<vtkLightCollection>::New();
  in.Analysis->SetMedium(in.Medium);
  in.Analysis->SetSurfaces(in.Surfaces);
  in.Analysis->SetEnvironmentLight(this->BackgroundIlluminates);
  in.Analysis->RemoveAllLights();
  for (vtkLight* light : in.CurrentLightList())
  {
    if (!light->GetSwitch())
    {
      continue;
    }
    vtkNew<vtkLight> copy;
    copy->DeepCopy(light);
    copy->SetLightTypeToSceneLight();
    copy->SetTransformMatrix(nullptr);
    double p[4] = { 0, 0, 0, 1 }, f[4] = { 0, 0, 0, 1 };
    light->GetTransformedPosition(p);
    light->GetTransformedFocalPoint(f);
    toData->MultiplyPoint(p, p);
    toData->MultiplyPoint(f, f);
    copy->SetPosition(p[0] / p[3], p[1] / p[3], p[2] / p[3]);
    copy->SetFocalPoint(f[0] / f[3], f[1] / f[3], f[2] / f[3]);
    if (this->LightUnits == VTK_LIGHT_UNITS)
    {
      double scale = vtkMath::Pi();
      if (light->GetPositional())
      {
        double bounds[6], centre[3], position[3];
        in.Medium->GetBounds(bounds);
        copy->GetPosition(position);
        for (int a = 0; a < 3; ++a)
        {
          centre[a] = 0.5 * (bounds[2 * a] + bounds[2 * a + 1]);
        }
        scale *= std::max(vtkMath::Distance2BetweenPoints(position, centre), 1e-300);
      }
      copy->SetIntensity(light->GetIntensity() * scale);
    }
    in.DataLights->AddItem(copy);
    in.Analysis->AddLight(copy);
  }

  // MultipleScattering off overrides the plan's decision without changing its mode.
  const int userMode = in.Plan->GetEffectMode(vtkEffectPlan::MULTIPLE_SCATTERING);
  if (!this->MultipleScattering)
  {
    in.Plan->SetEffectMode(vtkEffectPlan::MULTIPLE_SCATTERING, vtkEffectPlan::FORCE_OFF);
  }
  const bool decided = in.Analysis->Analyze() && in.Plan->Decide(in.Analysis);
  in.Plan->SetEffectMode(vtkEffectPlan::MULTIPLE_SCATTERING, userMode);
  if (!decided)
  {
    vtkErrorMacro("The scene analysis failed (see the error above).");
    return false;
  }

  // Prune the medium only when it or a light-independent decision changed, so that a light
  // move keeps the medium the view pass and the photon pass already hold.
  bool prune = !in.Planned || in.Medium != in.PlannedFrom ||
    in.Medium->GetMTime() > in.PlanTime.GetMTime() || in.Plan->GetMTime() > in.PlanTime.GetMTime();
  for (int effect : LightIndependentEffects)
  {
    prune = prune || in.Plan->IsEnabled(effect) != in.Decisions[effect];
  }
  if (prune)
  {
    auto planned = vtkSmartPointer<vtkImageData>::New();
    in.Plan->ApplyToMedium(in.Medium, planned);
    in.Planned = planned;
    if (!in.ViewPass->SetMedium(in.Planned))
    {
      in.Planned = nullptr;
      return false;
    }
    ++this->NumberOfMediumUpdates;
  }
  for (int e = 0; e < vtkEffectPlan::NUMBER_OF_EFFECTS; ++e)
  {
    in.Decisions[e] = in.Plan->IsEnabled(e);
  }
  in.PlannedFrom = in.Medium;
  in.PlannedSurfaces = CountSurfaces(in.Surfaces);
  in.LightList = in.CurrentLightList();
  in.LastError.clear();
  in.PlanDone = true;
  in.PlanTime.Modified();
  ++this->NumberOfPlanRuns;
  return true;
}

//------------------------------------------------------------------------------
bool vtkRefractaRenderPipeline::RunLighting()
{
  Internals& in = *this->Internal;
  in.LightDone = in.ViewDone = false;
  in.Lighting = nullptr;
  // Surfaces need the photon pass even where nothing in the medium scatters (a caustic of a
  // clear glass ball on a floor).
  const bool surfaces = in.Plan->IsEnabled(vtkEffectPlan::SURFACE_LIGHTING);
  const bool lit = (in.Plan->IsEnabled(vtkEffectPlan::SINGLE_SCATTERING) || surfaces) &&
    (in.Analysis->GetNumberOfPoweredLights() > 0 || this->BackgroundIlluminates);
  if (in.LightingData)
  {
    in.Lighting = in.LightingData;
  }
  else if (lit)
  {
    vtkPhotonTracer* tracer = in.Schedule->GetPhotonTracer();
    tracer->SetLights(in.DataLights);
    tracer->SetSurfaces(surfaces ? in.Surfaces.Get() : nullptr);
    tracer->SetMediumToWorld(in.PropMatrix);
    // The background the view pass shows is the one that lights the scene.
    tracer->SetBackgroundIlluminates(this->BackgroundIlluminates);
    tracer->SetBackgroundColor(in.ViewPass->GetBackgroundColor());
    tracer->SetEnvironmentMap(in.ViewPass->GetEnvironmentMap());
    tracer->SetEnvironmentUp(in.ViewPass->GetEnvironmentUp());
    tracer->SetEnvironmentRight(in.ViewPass->GetEnvironmentRight());
    vtkAlgorithm* pass = tracer;
    vtkImageData* output = nullptr;
    // With surfaces, multiple scattering is the photons' own (analog scattering): the lattice
    // knows no surfaces, so the light it carries would never light them (Physics.md, "Surfaces
    // and multiple scattering"). Surfaces also make the plan choose photons for single
    // scattering, so light rays and analog scattering never run together.
    const bool multiple = in.Plan->IsEnabled(vtkEffectPlan::MULTIPLE_SCATTERING);
    const bool analog = multiple && surfaces && CountSurfaces(in.Surfaces) > 0;
    tracer->SetAnalogScattering(analog);
    const int method = in.Plan->GetChosenSingleScatteringMethod();
    if (!analog && (method == vtkEffectPlan::LIGHT_RAYS || method == vtkEffectPlan::INTERPOLATED))
    {
      pass = this->PrepareLightRays(tracer, method);
    }
    else if (multiple && !analog)
    {
      // Interleaving the lattice with the marching (Bernabei et al.) helps where the two
      // share a device with spare parallelism: measured up to 4% on an H200; on a CPU device
      // both compete for the same cores, so sequential there.
      const bool interleaved = this->MultipleScatteringSchedule == INTERLEAVED_SCHEDULE ||
        (this->MultipleScatteringSchedule == AUTOMATIC_SCHEDULE && in.GetContext()->GetIsGPU());
      in.Schedule->SetMode(interleaved ? vtkPhotonDiffusionSchedule::INTERLEAVED
                                       : vtkPhotonDiffusionSchedule::SEQUENTIAL);
      this->LastScheduleInterleaved = interleaved;
      in.Schedule->SetInputData(in.Planned);
      pass = in.Schedule;
    }
    else
    {
      tracer->SetInputData(in.Planned);
    }
    in.Running = pass;
    if (in.Abort)
    {
      pass->SetAbortExecute(1);
    }
    pass->Update();
    in.Running = nullptr;
    output = vtkImageData::SafeDownCast(pass->GetOutputDataObject(0));
    if (in.Abort || pass->GetAbortExecute())
    {
      pass->SetAbortExecute(0);
      this->LastRenderAborted = true;
      return false;
    }
    if (!output || output->GetNumberOfPoints() == 0)
    {
      vtkErrorMacro(
        "The light passes (" << pass->GetClassName() << ") failed; see the error above.");
      return false;
    }
    in.Lighting = vtkSmartPointer<vtkImageData>::New();
    in.Lighting->ShallowCopy(output);
    ++this->NumberOfLightPassRuns;
  }
  if (!in.ViewPass->SetLighting(in.Lighting))
  {
    in.Lighting = nullptr;
    return false;
  }
  in.LightDone = true;
  in.LightTime.Modified();
  return true;
}

//------------------------------------------------------------------------------
bool vtkRefractaRenderPipeline::RunView(int width, int height, const float* depthLimit)
{
  Internals& in = *this->Internal;
  in.ViewDone = false;
  in.ViewPass->SetSurfaces(in.Surfaces);
  if (!in.ViewPass->Render(
        in.Camera, width, height, in.PropMatrix, depthLimit, in.Image, &in.Transmittance))
  {
    this->LastRenderAborted = in.ViewPass->GetLastRenderAborted();
    return false;
  }
  const size_t pixels = static_cast<size_t>(width) * height;
  in.ViewDepth.assign(
    depthLimit ? depthLimit : nullptr, depthLimit ? depthLimit + pixels : nullptr);
  in.ViewCamera = in.Camera;
  in.ViewSize[0] = width;
  in.ViewSize[1] = height;
  in.ViewDone = true;
  in.ViewTime.Modified();
  ++this->NumberOfViewPassRuns;
  return true;
}

//------------------------------------------------------------------------------
void vtkRefractaRenderPipeline::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  Internals& in = *this->Internal;
  os << indent << "Medium: " << in.Medium.Get() << "\n";
  os << indent << "LightingData: " << in.LightingData.Get() << "\n";
  os << indent << "Lights: " << in.Lights->GetNumberOfItems() << "\n";
  os << indent << "Camera: " << in.Camera.Get() << "\n";
  os << indent << "PropMatrix: " << in.PropMatrix.Get() << "\n";
  os << indent << "MultipleScattering: " << this->MultipleScattering << "\n";
  os << indent << "LightUnits: "
     << (this->LightUnits == VTK_LIGHT_UNITS ? "VTK_LIGHT_UNITS" : "RADIOMETRIC_LIGHT_UNITS")
     << "\n";
  os << indent << "MultipleScatteringSchedule: " << this->MultipleScatteringSchedule << "\n";
  os << indent << "BackgroundIlluminates: " << this->BackgroundIlluminates << "\n";
  os << indent << "NumberOfPlanRuns: " << this->NumberOfPlanRuns << "\n";
  os << indent << "NumberOfLightPassRuns: " << this->NumberOfLightPassRuns << "\n";
  os << indent << "NumberOfViewPassRuns: " << this->NumberOfViewPassRuns << "\n";
  os << indent << "EffectPlan: " << in.Plan->GetSummary() << "\n";
}
