#include "vtkEffectPlan.h"

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkRefractaMedium.h"
#include "vtkRefractaSettings.h"
#include "vtkSceneAnalysis.h"
#include "vtkStringArray.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

vtkStandardNewMacro(vtkEffectPlan);
vtkRefractaCxxSetClampMacro(vtkEffectPlan, Tolerance, 0.0, 1.0);

namespace
{
// The angle of the finest pixel the refraction estimate assumes (radians): VTK's default view
// angle of 30 degrees over 2048 pixels.
constexpr double FinestPixelAngle = 3.14159265358979323846 / 6.0 / 2048.0;

const char* const EffectNames[vtkEffectPlan::NUMBER_OF_EFFECTS] = { "Refraction", "Absorption",
  "SingleScattering", "MultipleScattering", "Emission", "SurfaceLighting" };

bool IsEffect(int effect)
{
  return effect >= 0 && effect < vtkEffectPlan::NUMBER_OF_EFFECTS;
}

// The pass settings of each quality preset, chosen by BenchmarkAccuracyTime (README, "Accuracy
// and time"): per knob the cheapest value whose own error stays within target / sqrt(7) on all
// four benchmark scenes, for targets 10% (draft), 5% (interactive) and 2% (production).
struct PresetSettings
{
  int Photons;
  double PhotonMinimumStep;
  double OctreeTolerance;
  double LatticeTolerance;
  int LatticeBlockSize;
  double ViewStep;
  int Resolution;
};
// Measured (2-core CPU, PoCL; README table): draft 1.2-1.7 s and at most 2.5% from the finest
// setting on the four scenes, interactive 1.8-5.5 s and 1.0%, production 3.6-20 s and 0.27%.
const PresetSettings Presets[3] = {
  { 1 << 16, 2.0, 0.08, 0.01, 0, 0.5, 64 },
  { 1 << 18, 0.5, 0.02, 0.01, 0, 0.25, 64 },
  { 1 << 20, 0.5, 0.0025, 0.01, 0, 0.25, 64 },
};
}

//------------------------------------------------------------------------------
const char* vtkEffectPlan::GetEffectName(int effect)
{
  return IsEffect(effect) ? EffectNames[effect] : nullptr;
}

//------------------------------------------------------------------------------
void vtkEffectPlan::SetQuality(int quality)
{
  switch (quality)
  {
    case DRAFT:
      this->SetTolerance(0.05);
      break;
    case INTERACTIVE:
      this->SetTolerance(0.02);
      break;
    case PRODUCTION:
      this->SetTolerance(0.005);
      break;
    default:
      vtkErrorMacro("Unknown quality preset "
        << quality << "; use DRAFT (0), INTERACTIVE (1) or PRODUCTION (2).");
      return;
  }
  if (this->Quality != quality || !this->QualityApplied)
  {
    this->Quality = quality;
    this->QualityApplied = true;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
int vtkEffectPlan::GetRecommendedNumberOfPhotons() const
{
  return Presets[this->Quality].Photons;
}

double vtkEffectPlan::GetRecommendedPhotonMinimumStep() const
{
  return Presets[this->Quality].PhotonMinimumStep;
}

double vtkEffectPlan::GetRecommendedOctreeTolerance() const
{
  return Presets[this->Quality].OctreeTolerance;
}

double vtkEffectPlan::GetRecommendedLatticeTolerance() const
{
  return Presets[this->Quality].LatticeTolerance;
}

int vtkEffectPlan::GetRecommendedLatticeBlockSize() const
{
  return Presets[this->Quality].LatticeBlockSize;
}

double vtkEffectPlan::GetRecommendedViewStep() const
{
  return Presets[this->Quality].ViewStep;
}

int vtkEffectPlan::GetRecommendedResolution() const
{
  return Presets[this->Quality].Resolution;
}

//------------------------------------------------------------------------------
void vtkEffectPlan::SetEffectMode(int effect, int mode)
{
  if (!IsEffect(effect) || mode < AUTOMATIC || mode > FORCE_OFF)
  {
    vtkErrorMacro("SetEffectMode(" << effect << ", " << mode << "): effect must be in [0, "
                                   << NUMBER_OF_EFFECTS - 1
                                   << "] and mode AUTOMATIC (0), FORCE_ON (1) or FORCE_OFF (2).");
    return;
  }
  if (this->Modes[effect] != mode)
  {
    this->Modes[effect] = mode;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
int vtkEffectPlan::GetEffectMode(int effect) const
{
  return IsEffect(effect) ? this->Modes[effect] : AUTOMATIC;
}

//------------------------------------------------------------------------------
bool vtkEffectPlan::IsEnabled(int effect) const
{
  return IsEffect(effect) && this->Enabled[effect];
}

//------------------------------------------------------------------------------
double vtkEffectPlan::GetEstimatedContribution(int effect) const
{
  return IsEffect(effect) ? this->Estimates[effect] : 0.0;
}

//------------------------------------------------------------------------------
const char* vtkEffectPlan::GetReason(int effect) const
{
  return IsEffect(effect) ? this->Reasons[effect].c_str() : "";
}

//------------------------------------------------------------------------------
void vtkEffectPlan::DecideEffect(int effect, double estimate, const char* detail)
{
  this->Estimates[effect] = estimate;
  std::ostringstream reason;
  if (this->Modes[effect] == FORCE_ON || this->Modes[effect] == FORCE_OFF)
  {
    this->Enabled[effect] = this->Modes[effect] == FORCE_ON;
    reason << (this->Enabled[effect] ? "on" : "off") << ": forced (estimated change " << estimate
           << ")";
  }
  else
  {
    this->Enabled[effect] = estimate > this->Tolerance;
    reason << (this->Enabled[effect] ? "on" : "off") << ": estimated change " << estimate
           << (this->Enabled[effect] ? " > " : " <= ") << "tolerance " << this->Tolerance;
  }
  if (detail && *detail)
  {
    reason << " (" << detail << ")";
  }
  this->Reasons[effect] = reason.str();
}

//------------------------------------------------------------------------------
bool vtkEffectPlan::Decide(vtkSceneAnalysis* analysis)
{
  if (!analysis)
  {
    vtkErrorMacro("Decide() needs a vtkSceneAnalysis that has been run (Analyze()).");
    return false;
  }
  std::ostringstream detail;

  // Exact dielectric interfaces bend light where the index jumps, which the index field's
  // gradient leaves out (it is zero across them by construction): they alone make refraction
  // visible, and the index on both sides must be kept.
  const int interfaces = analysis->GetNumberOfInterfaceSurfaces();
  detail << "bending " << analysis->GetMaximumBendingAngle() << " rad, displacement "
         << analysis->GetMaximumDisplacementInVoxels() << " voxels";
  if (interfaces > 0)
  {
    detail << ", " << interfaces << " dielectric interface surface(s)";
  }
  if (analysis->GetNumberOfDepositedParticles() > 0)
  {
    // A particle deposit has no index field: its particles scatter and absorb, they do not bend.
    detail << "; refraction does not apply to particles ("
           << analysis->GetNumberOfDepositedParticles() << " deposited)";
  }
  // Behind the medium, a structured background or a surface shows a deflection theta as a shift
  // of theta / delta pixels, delta the pixel's angle; with one ray per pixel an edge's pixels
  // flip where their centres lie within the shift of it, a fraction 2 s / P of the pixels for
  // features of P >= 1 pixel, so the relative L2 change is up to sqrt(2 s). The plan does not
  // follow the camera: delta is a 2048-pixel image over VTK's default 30 degrees. (A
  // deflection of 3e-4 rad moved a checker by half a pixel and changed the image by 22% while
  // the displacement bound said 0.008.)
  double estimate = std::min(analysis->GetMaximumDisplacementInVoxels(), 1.0);
  if (analysis->GetBackgroundHasStructure() || analysis->GetNumberOfSurfaces() > 0)
  {
    const double shift = analysis->GetMaximumBendingAngle() / FinestPixelAngle;
    detail << ", up to " << shift << " pixel(s) of shift behind the medium";
    estimate = std::max(estimate, std::min(std::sqrt(2.0 * shift), 1.0));
  }
  this->DecideEffect(REFRACTION, interfaces > 0 ? 1.0 : estimate, detail.str().c_str());

  const double tau = analysis->GetMaximumOpticalThickness();
  const bool lit = analysis->GetNumberOfPoweredLights() > 0 || analysis->GetEnvironmentLight();
  const double tauS = analysis->GetMaximumScatteringThickness();
  // Scattered light can be all the camera sees (a lit fog on black): without the camera and the
  // background there is nothing to compare it with, so any scattering of a powered light counts.
  // (Below the smallest normal float the kernels, which flush denormals, scatter nothing.)
  const double single =
    (lit && analysis->GetHasScattering() && tauS > std::numeric_limits<float>::min()) ? 1.0 : 0.0;

  // Absorption off drops the extinction, and with it every scattered photon: its change is the
  // attenuation or, when the medium scatters light that would be simulated, that light (a thin
  // lit haze on black, tau 0.005, vanished whole under tolerance 0.01).
  detail.str("");
  detail << "tau_max " << tau;
  double absorption = -std::expm1(-tau);
  if (single > absorption && this->Modes[SINGLE_SCATTERING] != FORCE_OFF)
  {
    absorption = single;
    detail << "; the scattered light needs the extinction";
  }
  this->DecideEffect(ABSORPTION, absorption, detail.str().c_str());

  detail.str("");
  detail << "tau_s " << tauS << ", " << analysis->GetNumberOfPoweredLights() << " powered light(s)"
         << (analysis->GetEnvironmentLight() ? " and the environment" : "");
  this->DecideEffect(SINGLE_SCATTERING, single, detail.str().c_str());

  // Each further order of scattering carries at most q of the previous one, so light scattered
  // twice or more is at most q / (1 - q) of the singly scattered light and at most q of all the
  // scattered light the camera sees.
  const double q = std::min(analysis->GetAlbedoRange()[1] * -std::expm1(-tau), 1.0);
  const double multiple = single > 0.0 ? q : 0.0;
  detail.str("");
  detail << "q = " << q;
  this->DecideEffect(MULTIPLE_SCATTERING, std::min(multiple, 1.0), detail.str().c_str());

  detail.str("");
  detail << "max emission " << analysis->GetMaximumEmission();
  this->DecideEffect(EMISSION, analysis->GetHasEmission() ? 1.0 : 0.0, detail.str().c_str());

  detail.str("");
  detail << analysis->GetNumberOfSurfaces() << " surface(s), "
         << analysis->GetNumberOfPoweredLights() << " powered light(s)"
         << (analysis->GetEnvironmentLight() ? " and the environment" : "");
  this->DecideEffect(SURFACE_LIGHTING, (lit && analysis->GetNumberOfSurfaces() > 0) ? 1.0 : 0.0,
    detail.str().c_str());

  // Without absorption there is no extinction, hence no scattering to simulate.
  if (!this->Enabled[ABSORPTION] && this->Modes[ABSORPTION] != FORCE_ON)
  {
    for (int effect : { SINGLE_SCATTERING, MULTIPLE_SCATTERING })
    {
      if (this->Enabled[effect] && this->Modes[effect] == AUTOMATIC)
      {
        this->Enabled[effect] = false;
        this->Reasons[effect] = "off: extinction is negligible, so nothing scatters";
      }
    }
  }
  if (!this->Enabled[SINGLE_SCATTERING] && this->Enabled[MULTIPLE_SCATTERING] &&
    this->Modes[MULTIPLE_SCATTERING] == AUTOMATIC)
  {
    this->Enabled[MULTIPLE_SCATTERING] = false;
    this->Reasons[MULTIPLE_SCATTERING] = "off: no single scattering to spread";
  }
  this->DecideSingleScatteringMethod(analysis);
  this->DecideMultipleScatteringMethod(analysis);
  // A decision is a result, not a setting: the MTime keeps tracking the settings (tolerance,
  // modes, quality) so that a pipeline can tell a changed plan from a re-decided one.
  this->Decided = true;
  return true;
}

//------------------------------------------------------------------------------
std::string vtkEffectPlan::GetSummary() const
{
  if (!this->Decided)
  {
    return "plan not decided";
  }
  std::ostringstream s;
  for (int e = 0; e < NUMBER_OF_EFFECTS; ++e)
  {
    s << (e ? ", " : "") << EffectNames[e] << " " << (this->Enabled[e] ? "on" : "off");
    if (this->Modes[e] != AUTOMATIC)
    {
      s << " (forced)";
    }
  }
  s << "; tolerance " << this->Tolerance << "; single scattering by "
    << GetSingleScatteringMethodName(this->ChosenMethod);
  if (this->Enabled[MULTIPLE_SCATTERING])
  {
    s << "; multiple scattering by " << GetMultipleScatteringMethodName(this->ChosenMultipleMethod);
    if (this->ChosenMultipleMethod == FIRST_COLLISION_SPLIT)
    {
      s << " (k = " << this->ChosenOrders << ")";
    }
    if (this->ChosenMultipleMethod != PHOTONS_EVERY_ORDER)
    {
      s << " on D3Q" << this->ChosenLattice;
    }
  }
  return s.str();
}

//------------------------------------------------------------------------------
bool vtkEffectPlan::ApplyToMedium(vtkImageData* medium, vtkImageData* pruned) const
{
  if (!medium || !pruned || !this->Decided)
  {
    return false;
  }
  pruned->ShallowCopy(medium);
  vtkPointData* pd = pruned->GetPointData();
  if (!this->Enabled[REFRACTION])
  {
    // Rays go straight, but the index still weighs every source by 1 / n^2 (the radiance law):
    // a nearly uniform n becomes its mean, exactly uniform, rather than vacuum.
    pd->RemoveArray(vtkRefractaMedium::RefractiveIndexGradientName());
    if (vtkDataArray* index = pd->GetArray(vtkRefractaMedium::RefractiveIndexName()))
    {
      double sum = 0.0;
      for (vtkIdType i = 0; i < index->GetNumberOfTuples(); ++i)
      {
        sum += index->GetComponent(i, 0);
      }
      const double mean = index->GetNumberOfTuples() ? sum / index->GetNumberOfTuples() : 1.0;
      pd->RemoveArray(vtkRefractaMedium::RefractiveIndexName());
      if (std::abs(mean - 1.0) > 1e-7)
      {
        vtkNew<vtkFloatArray> uniform;
        uniform->SetName(vtkRefractaMedium::RefractiveIndexName());
        uniform->SetNumberOfTuples(pruned->GetNumberOfPoints());
        uniform->Fill(mean);
        pd->AddArray(uniform);
      }
    }
  }
  if (!this->Enabled[ABSORPTION])
  {
    pd->RemoveArray(vtkRefractaMedium::ExtinctionName());
  }
  if (!this->Enabled[EMISSION])
  {
    pd->RemoveArray(vtkRefractaMedium::EmissionName());
  }
  bool anyMediumArray = false;
  for (int id = 0; id < vtkRefractaMedium::NUMBER_OF_ARRAYS; ++id)
  {
    anyMediumArray = anyMediumArray || pd->GetArray(vtkRefractaMedium::GetArrayName(id));
  }
  if (!anyMediumArray)
  {
    // Everything was pruned: say "vacuum" explicitly so that the result is still a medium.
    vtkNew<vtkFloatArray> vacuum;
    vacuum->SetName(vtkRefractaMedium::ExtinctionName());
    vacuum->SetNumberOfComponents(3);
    vacuum->SetNumberOfTuples(pruned->GetNumberOfPoints());
    vacuum->Fill(0.0);
    pd->AddArray(vacuum);
  }
  this->RecordInFieldData(pruned->GetFieldData());
  return true;
}

//------------------------------------------------------------------------------
void vtkEffectPlan::RecordInFieldData(vtkFieldData* fieldData) const
{
  if (!fieldData)
  {
    return;
  }
  vtkNew<vtkIntArray> enabled;
  enabled->SetName("PlanEnabled");
  vtkNew<vtkDoubleArray> estimates;
  estimates->SetName("PlanEstimatedContribution");
  for (int e = 0; e < NUMBER_OF_EFFECTS; ++e)
  {
    enabled->InsertNextValue(this->Enabled[e] ? 1 : 0);
    estimates->InsertNextValue(this->Estimates[e]);
  }
  vtkNew<vtkDoubleArray> tolerance;
  tolerance->SetName("PlanTolerance");
  tolerance->InsertNextValue(this->Tolerance);
  vtkNew<vtkStringArray> summary;
  summary->SetName("PlanSummary");
  summary->InsertNextValue(this->GetSummary());
  fieldData->AddArray(enabled);
  fieldData->AddArray(estimates);
  fieldData->AddArray(tolerance);
  fieldData->AddArray(summary);
  vtkNew<vtkStringArray> method;
  method->SetName("PlanSingleScatteringMethod");
  method->InsertNextValue(GetSingleScatteringMethodName(this->ChosenMethod));
  method->InsertNextValue(this->MethodReason);
  fieldData->AddArray(method);
  vtkNew<vtkStringArray> multiple;
  multiple->SetName("PlanMultipleScatteringMethod");
  multiple->InsertNextValue(GetMultipleScatteringMethodName(this->ChosenMultipleMethod));
  multiple->InsertNextValue(this->MultipleReason);
  fieldData->AddArray(multiple);
  vtkNew<vtkIntArray> lattice;
  lattice->SetName("PlanLatticeDirections");
  lattice->InsertNextValue(this->ChosenLattice);
  fieldData->AddArray(lattice);
}

//------------------------------------------------------------------------------
void vtkEffectPlan::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Tolerance: " << this->Tolerance << "\n";
  static const char* const qualities[] = { "draft", "interactive", "production" };
  os << indent << "Quality: " << qualities[this->Quality]
     << (this->QualityApplied ? "" : " (the default, not applied: the tolerance is its own)")
     << " (photons " << this->GetRecommendedNumberOfPhotons() << ", photon min step "
     << this->GetRecommendedPhotonMinimumStep() << ", octree eps "
     << this->GetRecommendedOctreeTolerance() << ", lattice tolerance "
     << this->GetRecommendedLatticeTolerance() << ", lattice block "
     << this->GetRecommendedLatticeBlockSize() << ", view step " << this->GetRecommendedViewStep()
     << ", resolution " << this->GetRecommendedResolution() << ")\n";
  for (int e = 0; e < NUMBER_OF_EFFECTS; ++e)
  {
    static const char* const modes[] = { "automatic", "forced on", "forced off" };
    os << indent << EffectNames[e] << ": " << modes[this->Modes[e]] << "; "
       << (this->Decided ? this->Reasons[e] : std::string("not decided")) << "\n";
  }
  os << indent
     << "SingleScatteringMethod: " << GetSingleScatteringMethodName(this->SingleScatteringMethod)
     << "; chosen " << GetSingleScatteringMethodName(this->ChosenMethod) << " ("
     << this->MethodReason << ")\n";
  os << indent << "MultipleScatteringMethod: "
     << GetMultipleScatteringMethodName(this->MultipleScatteringMethod)
     << ", ScatteringOrders: " << this->ScatteringOrders
     << ", LatticeDirections: " << this->LatticeDirections
     << ", D3Q18FitsInMemory: " << this->D3Q18FitsInMemory << "; chosen "
     << GetMultipleScatteringMethodName(this->ChosenMultipleMethod) << ", k " << this->ChosenOrders
     << ", D3Q" << this->ChosenLattice << " (" << this->MultipleReason << ")\n";
}
