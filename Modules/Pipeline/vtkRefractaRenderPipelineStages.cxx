// What each stage of vtkRefractaRenderPipeline does: the plan (analysis, decisions, pruned
// medium), the light passes, the view pass, and the surface set they all share.
#include "vtkRefractaRenderPipeline.h"
#include "vtkRefractaRenderPipelineInternals.h"

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkLatticeBoltzmannSolver.h"
#include "vtkLightRaySingleScattering.h"
#include "vtkMath.h"
#include "vtkMediumValidator.h"
#include "vtkNew.h"
#include "vtkPhotonTracer.h"
#include "vtkRefractaLightingVolume.h"
#include "vtkRefractaMedium.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace
{
// The light-independent decisions: while they stay the same, the pruned medium stays valid.
constexpr int LightIndependentEffects[] = { vtkEffectPlan::REFRACTION, vtkEffectPlan::ABSORPTION,
  vtkEffectPlan::EMISSION };
}

//------------------------------------------------------------------------------
void vtkRefractaRenderPipeline::ConfigureLightRays(vtkPhotonTracer* tracer)
{
  Internals& in = *this->Internal;
  vtkLightRaySingleScattering* rays = in.LightRays;
  rays->SetContext(in.GetContext());
  rays->SetLights(in.DataLights);
  rays->SetSurfaces(in.SceneSurfaces);
  rays->SetMediumToWorld(in.PropMatrix);
  rays->SetLightRadius(tracer->GetLightRadius());
  rays->SetDirectionalLightAngularRadius(tracer->GetDirectionalLightAngularRadius());
  rays->SetMaximumRadianceLobes(tracer->GetMaximumRadianceLobes());
}

//------------------------------------------------------------------------------
bool vtkRefractaRenderPipeline::AddDirectSurfaceLight(vtkPhotonTracer* tracer)
{
  Internals& in = *this->Internal;
  vtkLightRaySingleScattering* rays = in.LightRays;
  this->ConfigureLightRays(tracer);
  rays->SetAbortExecute(in.Abort ? 1 : 0);
  std::vector<float> direct;
  in.Running = rays; // AbortRender() reaches it
  const bool computed = rays->ComputeSurfaceIrradiance(in.Planned, direct);
  in.Running = nullptr;
  if (!computed)
  {
    this->LastRenderAborted = in.Abort || rays->GetAbortExecute();
    rays->SetAbortExecute(0);
    if (!this->LastRenderAborted)
    {
      vtkErrorMacro("The direct light on the surfaces (vtkLightRaySingleScattering) failed; see "
                    "the error above.");
    }
    return false;
  }
  const char* name = vtkRefractaLightingVolume::SurfaceIrradianceName();
  vtkDataArray* photons = in.Lighting->GetFieldData()->GetArray(name);
  constexpr int components = 3 * vtkRefractaLightingVolume::NUMBER_OF_SURFACE_SIDES;
  const vtkIdType texels = static_cast<vtkIdType>(direct.size() / components);
  if (!photons || photons->GetNumberOfTuples() != texels ||
    photons->GetNumberOfComponents() != components)
  {
    vtkErrorMacro("The photon pass's '" << name << "' does not match the surfaces' " << texels
                                        << " texels; the direct light cannot be added.");
    return false;
  }
  // A new array: the photon pass's own output keeps what it computed.
  vtkNew<vtkFloatArray> sum;
  sum->SetName(name);
  sum->SetNumberOfComponents(components);
  sum->SetNumberOfTuples(texels);
  for (vtkIdType t = 0; t < texels; ++t)
  {
    for (int c = 0; c < components; ++c)
    {
      sum->SetTypedComponent(
        t, c, static_cast<float>(photons->GetComponent(t, c)) + direct[components * t + c]);
    }
  }
  in.Lighting->GetFieldData()->AddArray(sum);
  this->LastDirectSurfaceLightByRays = true;
  return true;
}

//------------------------------------------------------------------------------
// Straight light: the light-ray pass (and the lattice on its output when multiple scattering is
// on), with the photon tracer's light extents so that both methods see the same lights.
vtkAlgorithm* vtkRefractaRenderPipeline::PrepareLightRays(vtkPhotonTracer* tracer, int method)
{
  Internals& in = *this->Internal;
  vtkLightRaySingleScattering* rays = in.LightRays;
  this->ConfigureLightRays(tracer);
  rays->SetMethod(method == vtkEffectPlan::INTERPOLATED ? vtkLightRaySingleScattering::INTERPOLATED
                                                        : vtkLightRaySingleScattering::LIGHT_RAYS);
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
  lattice->SetLattice(in.Plan->GetChosenLatticeDirections());
  lattice->SetTolerance(this->GetLatticeSolver()->GetTolerance());
  lattice->SetBlockSize(this->GetLatticeSolver()->GetBlockSize());
  lattice->SetKeepDeviceCopies(this->DeviceHandOff);
  lattice->SetInputData(in.Planned);
  lattice->SetInputConnection(1, rays->GetOutputPort());
  // The orders the photons carry (the split, or every order) still come from photons; the light
  // rays give single scattering without noise.
  const bool photonOrders = tracer->GetScatteringOrders() != 0;
  if (photonOrders)
  {
    tracer->SetInputData(in.Planned);
  }
  lattice->SetPhotonOrdersConnection(photonOrders ? tracer->GetOutputPort() : nullptr);
  return lattice;
}

//------------------------------------------------------------------------------
bool vtkRefractaRenderPipeline::FailPlanOnce(const std::string& message)
{
  // Said once: a front end re-rendering the same bad input does not repeat it.
  Internals& in = *this->Internal;
  if (message != in.LastError)
  {
    vtkErrorMacro(<< message);
    in.LastError = message;
  }
  in.Planned = nullptr;
  return false;
}

//------------------------------------------------------------------------------
bool vtkRefractaRenderPipeline::RunPlan()
{
  Internals& in = *this->Internal;
  in.PlanDone = in.LightDone = in.ViewDone = false;
  vtkNew<vtkMediumValidator> validator;
  if (!validator->Validate(in.Medium))
  {
    return this->FailPlanOnce(
      std::string("The medium is not a valid Refracta medium: ") + validator->GetErrorMessage());
  }

  // The lights in the medium's data frame (the inverse of the placement).
  vtkNew<vtkMatrix4x4> toData;
  if (in.PropMatrix)
  {
    vtkMatrix4x4::Invert(in.PropMatrix, toData);
  }
  in.DataLights = vtkSmartPointer<vtkLightCollection>::New();
  in.Analysis->SetMedium(in.Medium);
  in.Analysis->SetSurfaces(in.SceneSurfaces);
  in.Analysis->SetEnvironmentLight(this->BackgroundIlluminates);
  in.Analysis->SetBackgroundHasStructure(in.ViewPass->GetEnvironmentMap() != nullptr);
  in.Analysis->RemoveAllLights();
  int index = 0;
  for (vtkLight* light : in.CurrentLightList())
  {
    if (!light->GetSwitch())
    {
      ++index;
      continue;
    }
    // The passes refuse such a light; checked here too, because the plan would otherwise count a
    // negative intensity as no light and skip the passes without a word.
    std::string lightError;
    if (!vtkMediumValidator::CheckLight(light, index++, lightError))
    {
      return this->FailPlanOnce(lightError);
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
        // Matched at the medium's centre; a light nearer the centre than the box's nearest face
        // (only a light inside can be) is matched at that face's distance instead, so that a
        // lamp at the centre of a cloud does not go dark as d -> 0.
        double bounds[6], centre[3], position[3];
        double nearestFace = std::numeric_limits<double>::infinity();
        in.Medium->GetBounds(bounds);
        copy->GetPosition(position);
        for (int a = 0; a < 3; ++a)
        {
          centre[a] = 0.5 * (bounds[2 * a] + bounds[2 * a + 1]);
          const double half = 0.5 * (bounds[2 * a + 1] - bounds[2 * a]);
          nearestFace = half > 0.0 ? std::min(nearestFace, half) : nearestFace;
        }
        nearestFace = std::isfinite(nearestFace) ? nearestFace : 0.0;
        scale *= std::max(
          std::max(vtkMath::Distance2BetweenPoints(position, centre), nearestFace * nearestFace),
          1e-300);
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
  const bool analysed = in.Analysis->Analyze();
  // The automatic lattice's D3Q18 only where the device holds it (3x D3Q6's state); asked only
  // where the plan would choose it.
  const bool askMemory = analysed && in.Plan->CallsForD3Q18(in.Analysis);
  in.Plan->SetD3Q18FitsInMemory(!askMemory ||
    this->GetLatticeSolver()->FitsInMemory(
      vtkLatticeBoltzmannSolver::D3Q18, in.Medium->GetDimensions(), in.Medium->GetSpacing()));
  const bool decided = analysed && in.Plan->Decide(in.Analysis);
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
    // Clear voxels next to scattering ones take their albedo, so that interpolation does not
    // absorb at the rim of a white fog (vtkRefractaMedium::FillAlbedoWithoutExtinction).
    vtkRefractaMedium::FillAlbedoWithoutExtinction(planned);
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
  in.PlannedSurfaces = Internals::CountSurfaces(in.SceneSurfaces);
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
  this->LastDirectSurfaceLightByRays = false;
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
    tracer->SetKeepDeviceCopies(this->DeviceHandOff);
    // The lattice the plan chose, whatever was set on the solver itself.
    in.Schedule->GetSolver()->SetLattice(in.Plan->GetChosenLatticeDirections());
    in.Schedule->GetSolver()->SetKeepDeviceCopies(this->DeviceHandOff);
    tracer->SetLights(in.DataLights);
    tracer->SetSurfaces(surfaces ? in.SceneSurfaces : nullptr);
    // The split's halves share their units only under a rigid placement, the passes' documented
    // frame (a volume scaled by s put them s^2 apart).
    tracer->SetSkipDirectSurfaceLight(
      this->DirectSurfaceLightByRays && Internals::IsRigid(in.PropMatrix));
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
    // scattering, so light rays and analog scattering never run together. Otherwise the photons
    // carry the orders the plan chose (the first-collision split, or every order) and the
    // lattice the rest.
    const bool multiple = in.Plan->IsEnabled(vtkEffectPlan::MULTIPLE_SCATTERING);
    const bool analog = multiple && surfaces && Internals::CountSurfaces(in.SceneSurfaces) > 0;
    tracer->SetAnalogScattering(analog);
    tracer->SetScatteringOrders(multiple ? in.Plan->GetChosenScatteringOrders() : 0);
    const bool everyOrder = analog || tracer->GetScatteringOrders() == vtkPhotonTracer::EVERY_ORDER;
    const int method = in.Plan->GetChosenSingleScatteringMethod();
    if (!analog && (method == vtkEffectPlan::LIGHT_RAYS || method == vtkEffectPlan::INTERPOLATED))
    {
      pass = this->PrepareLightRays(tracer, method);
    }
    else if (multiple && !everyOrder)
    {
      // Interleaving the lattice with the marching (Bernabei et al.) helps where the two
      // share a device with spare parallelism: measured up to 4% on an H200; on a CPU device
      // both compete for the same cores, so sequential there. The lattice's coarse start runs
      // in the sequential schedule only (the interleaved one has advanced the state before the
      // final solve) and saves 35-45% of the lattice's steps, device-independent counts
      // (BenchmarkLatticeBoltzmann --table1): sequential wherever it applies.
      const bool interleaved = this->MultipleScatteringSchedule == INTERLEAVED_SCHEDULE ||
        (this->MultipleScatteringSchedule == AUTOMATIC_SCHEDULE && in.GetContext()->GetIsGPU() &&
          !in.Schedule->GetSolver()->CoarseStartApplies(in.Planned->GetDimensions()));
      in.Schedule->SetMode(interleaved ? vtkPhotonDiffusionSchedule::INTERLEAVED
                                       : vtkPhotonDiffusionSchedule::SEQUENTIAL);
      in.Schedule->SetWarmStart(this->LatticeWarmStart);
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
    if (pass == in.Schedule)
    {
      this->LastScheduleInterleaved = in.Schedule->GetLastRunInterleaved();
    }
    output = vtkImageData::SafeDownCast(pass->GetOutputDataObject(0));
    if (in.Abort || pass->GetAbortExecute())
    {
      pass->SetAbortExecute(0);
      this->LastRenderAborted = true;
      return false;
    }
    if (!output || output->GetNumberOfPoints() == 0)
    {
      // The lattice on the light rays' output: name the pass that runs first as well.
      const std::string passes = pass == in.LightRayLattice.GetPointer()
        ? std::string(in.LightRays->GetClassName()) + " and " + pass->GetClassName()
        : pass->GetClassName();
      vtkErrorMacro("The light passes (" << passes << ") failed; see the error above.");
      return false;
    }
    in.Lighting = vtkSmartPointer<vtkImageData>::New();
    in.Lighting->ShallowCopy(output);
    // Only when the photons lit surfaces in this stage: the flag is the tracer's last run's, and
    // the light rays' stage (no lit surfaces) does not run the tracer.
    if (surfaces && tracer->GetLastSkippedDirectSurfaceLight() &&
      !this->AddDirectSurfaceLight(tracer))
    {
      in.Lighting = nullptr;
      return false;
    }
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
  in.ViewPass->SetSurfaces(in.SceneSurfaces);
  if (!in.ViewPass->Render(in.Camera, width, height, in.PropMatrix, depthLimit, in.Image,
        &in.Transmittance, nullptr, &in.BackgroundPart))
  {
    this->LastRenderAborted = in.ViewPass->GetLastRenderAborted();
    return false;
  }
  const size_t pixels = static_cast<size_t>(width) * height;
  in.ViewDepth.assign(
    depthLimit ? depthLimit : nullptr, depthLimit ? depthLimit + pixels : nullptr);
  in.ViewSize[0] = width;
  in.ViewSize[1] = height;
  in.ViewDone = true;
  in.ViewTime.Modified();
  ++this->NumberOfViewPassRuns;
  return true;
}

//------------------------------------------------------------------------------
bool vtkRefractaRenderPipeline::Internals::UpdateSceneSurfaces(bool withInterfaces)
{
  vtkFieldData* fd = this->Medium ? this->Medium->GetFieldData() : nullptr;
  const bool interfaces =
    withInterfaces && fd && fd->GetArray(vtkRefractaMedium::InterfaceTrianglesName());
  if (!interfaces)
  {
    this->SceneSurfaces = this->Surfaces;
    return true;
  }
  // The composed set holds the caller's meshes, materials and matrices and the placement by
  // reference, so their later changes reach it through its MTime; recompose only when the
  // medium or the caller's set itself changed.
  const vtkMTimeType t = this->ComposeTime.GetMTime();
  if (this->ComposedMedium != this->Medium || this->Medium->GetMTime() > t ||
    this->ComposedFrom != this->Surfaces || (this->Surfaces && this->Surfaces->GetMTime() > t) ||
    this->ComposedMatrix != this->PropMatrix || this->SceneSurfaces != this->ComposedSurfaces)
  {
    this->ComposedSurfaces->CopySurfaces(this->Surfaces);
    const int added = this->ComposedSurfaces->AddMediumInterfaces(this->Medium, this->PropMatrix);
    this->ComposedMedium = this->Medium;
    this->ComposedFrom = this->Surfaces;
    this->ComposedMatrix = this->PropMatrix;
    this->ComposeTime.Modified();
    if (added < 0)
    {
      this->ComposedMedium = nullptr; // try again (and say it again) on the next render
      this->SceneSurfaces = nullptr;
      return false;
    }
  }
  this->SceneSurfaces = this->ComposedSurfaces;
  return true;
}
