#include "vtkRefractaRenderPipeline.h"

#include "vtkRefractaHostThreads.h"
#include "vtkRefractaMedium.h"
#include "vtkRefractaRenderPipelineInternals.h"

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
#include <cmath>
#include <string>

vtkStandardNewMacro(vtkRefractaRenderPipeline);

namespace
{
// Share of a full render each stage takes when it has not run yet, from the default scene on the
// 2-core PoCL CPU (plan 0.1 s, light passes 20-30 s, view pass 2-6 s); after a stage has run its
// own last duration is used instead.
constexpr std::array<double, vtkRefractaRenderPipeline::NUMBER_OF_STAGES> DefaultStageSeconds = {
  0.1, 20.0, 4.0
};

double SecondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Whether two ray frames give the same rays to a millionth of the image's half-width: a camera
// copied by vtkWindowToImageFilter's re-render rounds its view angle at 3e-8.
bool SameRays(const vtkRefractaViewPass::RayFrame& a, const vtkRefractaViewPass::RayFrame& b)
{
  const auto near = [](const double* x, const double* y, int n)
  {
    for (int i = 0; i < n; ++i)
    {
      if (!(std::fabs(x[i] - y[i]) <= 1e-6 * (1.0 + std::fabs(x[i]))))
      {
        return false;
      }
    }
    return true;
  };
  return a.Parallel == b.Parallel && near(a.Eye, b.Eye, 3) && near(a.U, b.U, 3) &&
    near(a.V, b.V, 3) && near(a.W, b.W, 3) &&
    near(&a.WorldToLocal[0][0], &b.WorldToLocal[0][0], 16);
}
}

//------------------------------------------------------------------------------
vtkRefractaRenderPipeline::vtkRefractaRenderPipeline()
  : Internal(new Internals)
{
  vtkRefractaHostThreads::UseThreadedBackend();
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
  // Every light move re-runs the tracer with the same sizes: its scratch buffers are kept.
  this->Internal->Schedule->GetPhotonTracer()->ReuseScratchBuffersOn();
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

vtkRefractaSurfaceSet* vtkRefractaRenderPipeline::GetSceneSurfaces()
{
  return this->Internal->SceneSurfaces;
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

void vtkRefractaRenderPipeline::SetMultipleScatteringMethod(int method)
{
  this->Internal->Plan->SetMultipleScatteringMethod(method);
}

int vtkRefractaRenderPipeline::GetMultipleScatteringMethod()
{
  return this->Internal->Plan->GetMultipleScatteringMethod();
}

void vtkRefractaRenderPipeline::SetScatteringOrders(int orders)
{
  this->Internal->Plan->SetScatteringOrders(orders);
}

int vtkRefractaRenderPipeline::GetScatteringOrders()
{
  return this->Internal->Plan->GetScatteringOrders();
}

void vtkRefractaRenderPipeline::SetLattice(int directions)
{
  this->Internal->Plan->SetLatticeDirections(directions);
}

int vtkRefractaRenderPipeline::GetLattice()
{
  return this->Internal->Plan->GetLatticeDirections();
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

const std::vector<float>& vtkRefractaRenderPipeline::GetBackgroundPart() const
{
  return this->Internal->BackgroundPart;
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
  for (vtkRefractaSurfaceSet* set : { in.Surfaces.Get(), in.SceneSurfaces })
  {
    if (set)
    {
      t = std::max(t, set->GetMTime());
    }
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
    in.Analysis->GetSurfaces() != in.SceneSurfaces ||
    in.Analysis->GetBackgroundHasStructure() != (in.ViewPass->GetEnvironmentMap() != nullptr) ||
    Internals::CountSurfaces(in.SceneSurfaces) != in.PlannedSurfaces;
}

bool vtkRefractaRenderPipeline::LightingIsStale()
{
  Internals& in = *this->Internal;
  const vtkMTimeType lightTime = in.LightTime.GetMTime();
  return !in.LightDone || in.PlanTime.GetMTime() > lightTime ||
    in.Schedule->GetMTime() > lightTime ||
    (in.LightingData && in.LightingData->GetMTime() > lightTime) ||
    (in.SceneSurfaces && in.SceneSurfaces->GetMTime() > lightTime) ||
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
  if (this->RunStages(true, width, height, depthLimit))
  {
    return true;
  }
  if (!this->LastRenderAborted)
  {
    // An error leaves no image: the last one belongs to inputs that are no longer there, and a
    // front end that shows it would show a scene the user has changed.
    Internals& in = *this->Internal;
    in.Image.clear();
    in.Transmittance.clear();
    in.BackgroundPart.clear();
    in.ViewDone = false;
  }
  return false;
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
  // Checked before the light passes, which place the medium by the same matrix.
  const std::string why = withView
    ? vtkRefractaViewPass::GetRayFrameProblem(in.Camera, in.PropMatrix)
    : vtkRefractaViewPass::GetPropMatrixProblem(in.PropMatrix);
  if (!why.empty())
  {
    vtkErrorMacro(<< why);
    return false;
  }
  const bool refractionForcedOff =
    in.Plan->GetEffectMode(vtkEffectPlan::REFRACTION) == vtkEffectPlan::FORCE_OFF;
  if (!in.UpdateSceneSurfaces(!refractionForcedOff))
  {
    vtkErrorMacro("The medium's exact interfaces (field data "
      << vtkRefractaMedium::InterfaceTrianglesName()
      << " and its companions, from vtkMeshVoxelizer::EXACT_INTERFACES) are inconsistent; see "
         "the error above.");
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
  vtkRefractaViewPass::RayFrame frame;
  vtkRefractaViewPass::ComputeRayFrame(in.Camera, in.Medium, in.PropMatrix, width, height, frame);
  const bool view = light || !in.ViewDone || !SameRays(frame, in.ViewFrame) ||
    in.ViewPass->GetMTime() > viewTime || (env && env->GetMTime() > viewTime) ||
    width != in.ViewSize[0] || height != in.ViewSize[1] || depthChanged;
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
    in.ViewFrame = frame; // the rays this image was made with
    in.LastSeconds[VIEW] = in.Seconds[VIEW];
    this->ReportProgress(VIEW, 1.0);
  }
  this->InvokeEvent(vtkCommand::EndEvent, const_cast<char*>(GetStageName(VIEW)));
  return ok;
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
  os << indent << "LatticeWarmStart: " << this->LatticeWarmStart << "\n";
  os << indent << "DeviceHandOff: " << this->DeviceHandOff << "\n";
  os << indent << "DirectSurfaceLightByRays: " << this->DirectSurfaceLightByRays << " (last "
     << this->LastDirectSurfaceLightByRays << ")\n";
  os << indent << "BackgroundIlluminates: " << this->BackgroundIlluminates << "\n";
  os << indent << "NumberOfPlanRuns: " << this->NumberOfPlanRuns << "\n";
  os << indent << "NumberOfLightPassRuns: " << this->NumberOfLightPassRuns << "\n";
  os << indent << "NumberOfViewPassRuns: " << this->NumberOfViewPassRuns << "\n";
  os << indent << "EffectPlan: " << in.Plan->GetSummary() << "\n";
}
