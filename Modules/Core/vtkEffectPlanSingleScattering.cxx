// vtkEffectPlan's choice of the single-scattering method (issue 15): photons, per-voxel light
// rays or the gradient-based interpolation of Ren et al. (2008).
#include "vtkEffectPlan.h"

#include "vtkImageData.h"
#include "vtkSceneAnalysis.h"

#include <algorithm>
#include <cstring>
#include <sstream>

namespace
{
const char* const MethodNames[] = { "auto", "photons", "light_rays", "interpolated" };
}

const char* vtkEffectPlan::GetSingleScatteringMethodName(int method)
{
  return method >= AUTOMATIC_METHOD && method < NUMBER_OF_METHODS ? MethodNames[method] : nullptr;
}

int vtkEffectPlan::GetSingleScatteringMethodFromName(const char* name)
{
  for (int m = AUTOMATIC_METHOD; m < NUMBER_OF_METHODS && name; ++m)
  {
    if (std::strcmp(name, MethodNames[m]) == 0)
    {
      return m;
    }
  }
  return -1;
}

//------------------------------------------------------------------------------
// Photons where only they are right; otherwise whichever of light rays and interpolation meets
// the tolerance faster, by the errors and break-even grid size BenchmarkSingleScattering measured.
void vtkEffectPlan::DecideSingleScatteringMethod(vtkSceneAnalysis* analysis)
{
  std::ostringstream why;
  const char* photonsOnly = nullptr;
  // Surface lighting forced on in a scene without surfaces lights nothing: no reason for photons.
  const bool litSurfaces = this->Enabled[SURFACE_LIGHTING] && analysis->GetNumberOfSurfaces() > 0;
  // Refraction forced on in a medium of uniform n (estimate 0) bends nothing: light rays still fit.
  if (this->Enabled[REFRACTION] && this->Estimates[REFRACTION] > 0.0)
  {
    photonsOnly = analysis->GetNumberOfInterfaceSurfaces() > 0
      ? "refraction is on: light paths bend at dielectric interfaces"
      : "refraction is on: light paths curve";
  }
  else if (litSurfaces)
  {
    photonsOnly = "lit surfaces: their irradiance comes from photons";
  }
  else if (analysis->GetEnvironmentLight())
  {
    photonsOnly = "the sky lights the scene: only photons carry it";
  }
  if (!this->Enabled[SINGLE_SCATTERING])
  {
    this->ChosenMethod = PHOTONS;
    this->MethodReason = "single scattering off (photons run only for lit surfaces)";
    return;
  }
  const bool photonsNeeded = litSurfaces || analysis->GetEnvironmentLight();
  if (this->SingleScatteringMethod != AUTOMATIC_METHOD)
  {
    // A forced straight-ray method is honoured where it is an approximation (refraction on: the
    // light is taken as straight) but not where it cannot deliver (surface irradiance, the sky).
    this->ChosenMethod = photonsNeeded ? PHOTONS : this->SingleScatteringMethod;
    why << GetSingleScatteringMethodName(this->SingleScatteringMethod) << " forced";
    if (photonsOnly && this->SingleScatteringMethod != PHOTONS)
    {
      why << (photonsNeeded ? ", but " : ", although ") << photonsOnly;
      why << (photonsNeeded ? ": photons" : " (taken as straight)");
    }
    this->MethodReason = why.str();
    return;
  }
  if (photonsOnly)
  {
    this->ChosenMethod = PHOTONS;
    this->MethodReason = photonsOnly;
    return;
  }
  vtkImageData* medium = analysis->GetMedium();
  const double voxels = medium ? static_cast<double>(medium->GetNumberOfPoints()) : 0.0;
  const double work = voxels * std::max(1, analysis->GetNumberOfPoweredLights());
  if (InterpolationMeasuredError > this->Tolerance)
  {
    this->ChosenMethod = LIGHT_RAYS;
    why << "straight light; interpolation error " << InterpolationMeasuredError << " > tolerance "
        << this->Tolerance;
  }
  else if (work < InterpolationBreakEvenWork)
  {
    this->ChosenMethod = LIGHT_RAYS;
    why << "straight light; voxels x lights " << work << " < " << InterpolationBreakEvenWork
        << ", below which light rays were measured faster";
  }
  else
  {
    this->ChosenMethod = INTERPOLATED;
    why << "straight light; interpolation error " << InterpolationMeasuredError << " <= tolerance "
        << this->Tolerance << " and voxels x lights " << work
        << " >= " << InterpolationBreakEvenWork << ", where it was measured faster";
  }
  this->MethodReason = why.str();
}
