// Tests of vtkSceneAnalysis (facts with analytic values) and vtkEffectPlan (decisions, the
// threshold switch, overrides, records).
#include "EffectPlanTestMedium.h"

#include "vtkCommand.h"
#include "vtkEffectPlan.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkRefractaSurfaceSet.h"
#include "vtkSceneAnalysis.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"
#include "vtkTestErrorObserver.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>

namespace
{
using refracta_test::MakeMedium;
using refracta_test::Voxel;

// A uniform fog of n^3 voxels.
vtkSmartPointer<vtkImageData> UniformFog(int n, double spacing, double sigmaT, double albedo)
{
  return MakeMedium(n, n, n, spacing,
    [=](int, int, int)
    {
      Voxel v;
      v.SigmaT = sigmaT;
      v.Albedo = albedo;
      return v;
    });
}

vtkSmartPointer<vtkLight> MakeDirectionalLight(double intensity)
{
  auto light = vtkSmartPointer<vtkLight>::New();
  light->SetPositional(false);
  light->SetPosition(-10, 0.5, 0.5);
  light->SetFocalPoint(0, 0.5, 0.5); // travels along +x
  light->SetIntensity(intensity);
  return light;
}

void Plan(vtkImageData* medium, vtkLight* light, vtkEffectPlan* plan, vtkSceneAnalysis* analysis)
{
  analysis->SetMedium(medium);
  analysis->RemoveAllLights();
  if (light)
  {
    analysis->AddLight(light);
  }
  ASSERT_TRUE(analysis->Analyze());
  ASSERT_TRUE(plan->Decide(analysis));
}
}

TEST(SceneAnalysis, PureAbsorption)
{
  // 20 voxels of 0.1 with sigma_t = 0.5: tau = 1 along every axis.
  auto medium = MakeMedium(20, 20, 20, 0.1,
    [](int, int, int)
    {
      Voxel v;
      v.SigmaT = 0.5;
      return v;
    });
  vtkNew<vtkSceneAnalysis> analysis;
  vtkNew<vtkEffectPlan> plan;
  auto light = MakeDirectionalLight(1.0);
  Plan(medium, light, plan, analysis);
  for (int axis = 0; axis < 3; ++axis)
  {
    EXPECT_NEAR(analysis->GetMaximumOpticalThickness(axis), 1.0, 1e-6);
  }
  EXPECT_EQ(analysis->GetMaximumBendingAngle(), 0.0);
  EXPECT_FALSE(analysis->GetHasScattering());
  EXPECT_DOUBLE_EQ(analysis->GetOccupiedFraction(), 1.0);
  // Toward a light along +x: the deepest probe sits 15/16 of the way across the box [-0.05,
  // 1.95], marched in half-voxel steps (so within one step).
  EXPECT_NEAR(analysis->GetOpticalThicknessTowardLight(0), 0.5 * (15.0 / 16.0) * 2.0, 0.5 * 0.05);

  EXPECT_FALSE(plan->IsEnabled(vtkEffectPlan::REFRACTION));
  EXPECT_TRUE(plan->IsEnabled(vtkEffectPlan::ABSORPTION));
  EXPECT_NEAR(
    plan->GetEstimatedContribution(vtkEffectPlan::ABSORPTION), 1.0 - std::exp(-1.0), 1e-6);
  EXPECT_FALSE(plan->IsEnabled(vtkEffectPlan::SINGLE_SCATTERING));
  EXPECT_FALSE(plan->IsEnabled(vtkEffectPlan::MULTIPLE_SCATTERING));
  EXPECT_FALSE(plan->IsEnabled(vtkEffectPlan::EMISSION));
}

// A voxel's optical depth: the largest sigma_t times the largest spacing. A scattering medium
// denser than 4 per voxel is under-resolved (its surface glow is lost in the voxel samples; an
// outside review's sigma 1000 on 32^3 rendered black); absorption alone is not.
TEST(SceneAnalysis, VoxelOpticalDepthFlagsUnderResolvedScattering)
{
  vtkNew<vtkSceneAnalysis> analysis;
  vtkNew<vtkEffectPlan> plan;
  auto light = MakeDirectionalLight(1.0);
  Plan(UniformFog(8, 0.1, 30.0, 0.9), light, plan, analysis);
  EXPECT_NEAR(analysis->GetMaximumVoxelOpticalDepth(), 3.0, 1e-5);
  EXPECT_FALSE(analysis->IsUnderResolved());
  Plan(UniformFog(8, 0.1, 100.0, 0.9), light, plan, analysis);
  EXPECT_NEAR(analysis->GetMaximumVoxelOpticalDepth(), 10.0, 1e-4);
  EXPECT_TRUE(analysis->IsUnderResolved());
  EXPECT_NE(analysis->GetSummary().find("voxel tau <= 10"), std::string::npos)
    << analysis->GetSummary();
  Plan(UniformFog(8, 0.1, 100.0, 0.0), light, plan, analysis);
  EXPECT_FALSE(analysis->IsUnderResolved());
  // Dense tinted glass (no albedo) beside a thin scattering haze: nothing dense scatters.
  auto mixed = MakeMedium(8, 8, 8, 0.1,
    [](int i, int, int)
    {
      Voxel v;
      v.SigmaT = i < 4 ? 50.0 : 0.2;
      v.Albedo = i < 4 ? 0.0 : 0.9;
      return v;
    });
  Plan(mixed, light, plan, analysis);
  EXPECT_TRUE(analysis->GetHasScattering());
  EXPECT_NEAR(analysis->GetMaximumVoxelOpticalDepth(), 0.02, 1e-6);
  EXPECT_FALSE(analysis->IsUnderResolved());
}

TEST(SceneAnalysis, LinearIndexGradientBendsRays)
{
  // n = 1 + a y with a = 0.2 per unit, on 11^3 voxels of spacing 0.1 (y in [0, 1]).
  const double a = 0.2, s = 0.1;
  auto medium = MakeMedium(11, 11, 11, s,
    [&](int, int j, int)
    {
      Voxel v;
      v.N = 1.0 + a * j * s;
      return v;
    });
  vtkNew<vtkSceneAnalysis> analysis;
  vtkNew<vtkEffectPlan> plan;
  Plan(medium, nullptr, plan, analysis);
  // Central differences of a linear field are exact: abs(grad n) = a everywhere. The largest
  // line integral of a / n runs along x at y = 0 (n = 1): 11 voxels * 0.1 * 0.2 = 0.22.
  EXPECT_NEAR(analysis->GetMaximumBendingAngle(), 11 * s * a, 1e-6);
  EXPECT_NEAR(analysis->GetRefractiveIndexRange()[1], 1.2, 1e-6);
  const double diagonal = std::sqrt(3.0) * 11 * s;
  EXPECT_NEAR(analysis->GetMaximumDisplacementInVoxels(), 11 * s * a * diagonal / s, 1e-5);
  EXPECT_TRUE(plan->IsEnabled(vtkEffectPlan::REFRACTION));
  EXPECT_FALSE(plan->IsEnabled(vtkEffectPlan::ABSORPTION));
  EXPECT_DOUBLE_EQ(analysis->GetOccupiedFraction(), 10.0 / 11.0); // the y = 0 layer is vacuum
}

// A weak index gradient (schlieren): n = 1 + 3e-4 x per unit on 16^3 voxels of 1/16. Rays move
// under a hundredth of a voxel inside the box, so over a uniform background refraction is
// skipped; behind the medium a structured background (an environment map, the checker) or a
// surface shows the 3e-4 rad deflection as a shift of more than a pixel of the finest image the
// plan assumes (2048 pixels over 30 degrees), so it is simulated: skipping it changed a checker
// seen through such a medium by 9% to 22% (relative L2, 30 and 2 degree views) under tolerance
// 0.01.
TEST(EffectPlan, RefractionCountsTheShiftOfAStructuredBackground)
{
  const double s = 1.0 / 16;
  auto medium = MakeMedium(16, 16, 16, s,
    [&](int i, int, int)
    {
      Voxel v;
      v.N = 1.0 + 3e-4 * (i * s + 0.5);
      return v;
    });
  vtkNew<vtkSceneAnalysis> analysis;
  vtkNew<vtkEffectPlan> plan;
  Plan(medium, nullptr, plan, analysis);
  ASSERT_LT(analysis->GetMaximumDisplacementInVoxels(), plan->GetTolerance());
  EXPECT_FALSE(plan->IsEnabled(vtkEffectPlan::REFRACTION))
    << plan->GetReason(vtkEffectPlan::REFRACTION);
  analysis->SetBackgroundHasStructure(true);
  Plan(medium, nullptr, plan, analysis);
  EXPECT_TRUE(plan->IsEnabled(vtkEffectPlan::REFRACTION))
    << plan->GetReason(vtkEffectPlan::REFRACTION);
  EXPECT_NE(std::string(plan->GetReason(vtkEffectPlan::REFRACTION)).find("pixel(s) of shift"),
    std::string::npos);
  // An index that is uniform in float (1 + 1e-9 i rounds to 1) bends nothing: still skipped.
  auto faint = MakeMedium(16, 16, 16, s,
    [&](int i, int, int)
    {
      Voxel v;
      v.N = 1.0 + 1e-9 * i;
      return v;
    });
  Plan(faint, nullptr, plan, analysis);
  EXPECT_FALSE(plan->IsEnabled(vtkEffectPlan::REFRACTION))
    << plan->GetReason(vtkEffectPlan::REFRACTION);
}

TEST(EffectPlan, MultipleScatteringSwitchesAtItsThreshold)
{
  // Fog: sigma_t = 0.1, albedo 0.9 over 2 units: tau = 0.2, tau_s = 0.18.
  auto fog = UniformFog(20, 0.1, 0.1, 0.9);
  const double q = 0.9 * (1.0 - std::exp(-0.2));
  const double multiple = q; // about 0.163
  vtkNew<vtkSceneAnalysis> analysis;
  vtkNew<vtkEffectPlan> plan;
  auto light = MakeDirectionalLight(2.0);
  plan->SetTolerance(multiple * 0.99); // just below the estimate: on
  Plan(fog, light, plan, analysis);
  EXPECT_NEAR(plan->GetEstimatedContribution(vtkEffectPlan::MULTIPLE_SCATTERING), multiple, 1e-5);
  EXPECT_TRUE(plan->IsEnabled(vtkEffectPlan::SINGLE_SCATTERING));
  EXPECT_TRUE(plan->IsEnabled(vtkEffectPlan::MULTIPLE_SCATTERING));
  // Just above it: multiple scattering off, single scattering (estimate 1 when lit) stays.
  EXPECT_EQ(plan->GetEstimatedContribution(vtkEffectPlan::SINGLE_SCATTERING), 1.0);
  plan->SetTolerance(multiple * 1.01);
  ASSERT_TRUE(plan->Decide(analysis));
  EXPECT_FALSE(plan->IsEnabled(vtkEffectPlan::MULTIPLE_SCATTERING));
  EXPECT_TRUE(plan->IsEnabled(vtkEffectPlan::SINGLE_SCATTERING));
  EXPECT_NE(std::string(plan->GetReason(vtkEffectPlan::MULTIPLE_SCATTERING)).find("off"),
    std::string::npos);

  // Quality presets set the tolerance (draft 0.05, production 0.005): both keep q = 0.16.
  plan->SetQuality(vtkEffectPlan::DRAFT);
  ASSERT_TRUE(plan->Decide(analysis));
  EXPECT_EQ(plan->GetTolerance(), 0.05);
  EXPECT_TRUE(plan->IsEnabled(vtkEffectPlan::MULTIPLE_SCATTERING));
  plan->SetQuality(vtkEffectPlan::PRODUCTION);
  ASSERT_TRUE(plan->Decide(analysis));
  EXPECT_TRUE(plan->IsEnabled(vtkEffectPlan::MULTIPLE_SCATTERING));
}

// Each preset selects its measured pass settings (README, "Accuracy and time"): costlier and more
// accurate from draft to production, never less accurate on any knob; an unknown preset is an
// error that leaves the plan as it was.
TEST(EffectPlan, QualityPresetsSelectTheirPassSettings)
{
  vtkNew<vtkEffectPlan> plan;
  EXPECT_EQ(plan->GetQuality(), vtkEffectPlan::INTERACTIVE);
  int photons = 0;
  double minStep = 1e30, octree = 1e30, lattice = 1e30, view = 1e30;
  int resolution = 0;
  for (int q : { vtkEffectPlan::DRAFT, vtkEffectPlan::INTERACTIVE, vtkEffectPlan::PRODUCTION })
  {
    plan->SetQuality(q);
    EXPECT_EQ(plan->GetQuality(), q);
    EXPECT_GE(plan->GetRecommendedNumberOfPhotons(), photons);
    EXPECT_LE(plan->GetRecommendedPhotonMinimumStep(), minStep);
    EXPECT_LE(plan->GetRecommendedOctreeTolerance(), octree);
    EXPECT_LE(plan->GetRecommendedLatticeTolerance(), lattice);
    EXPECT_LE(plan->GetRecommendedViewStep(), view);
    EXPECT_GE(plan->GetRecommendedResolution(), resolution);
    EXPECT_GE(plan->GetRecommendedLatticeBlockSize(), 0);
    photons = plan->GetRecommendedNumberOfPhotons();
    minStep = plan->GetRecommendedPhotonMinimumStep();
    octree = plan->GetRecommendedOctreeTolerance();
    lattice = plan->GetRecommendedLatticeTolerance();
    view = plan->GetRecommendedViewStep();
    resolution = plan->GetRecommendedResolution();
  }
  EXPECT_GT(photons, 65536); // production traces more photons than draft
  vtkNew<vtkTest::ErrorObserver> errors;
  plan->AddObserver(vtkCommand::ErrorEvent, errors);
  plan->SetQuality(7);
  EXPECT_TRUE(errors->GetError());
  EXPECT_EQ(plan->GetQuality(), vtkEffectPlan::PRODUCTION);
  EXPECT_EQ(plan->GetTolerance(), 0.005);
}

TEST(EffectPlan, ScatteringNeedsAPoweredLight)
{
  auto fog = UniformFog(8, 0.25, 1.0, 0.8);
  vtkNew<vtkSceneAnalysis> analysis;
  vtkNew<vtkEffectPlan> plan;
  Plan(fog, nullptr, plan, analysis);
  EXPECT_FALSE(plan->IsEnabled(vtkEffectPlan::SINGLE_SCATTERING));
  auto dark = MakeDirectionalLight(0.0);
  Plan(fog, dark, plan, analysis);
  EXPECT_EQ(analysis->GetNumberOfPoweredLights(), 0);
  EXPECT_FALSE(plan->IsEnabled(vtkEffectPlan::SINGLE_SCATTERING));
  auto off = MakeDirectionalLight(1.0);
  off->SwitchOff();
  Plan(fog, off, plan, analysis);
  EXPECT_FALSE(plan->IsEnabled(vtkEffectPlan::SINGLE_SCATTERING));
  auto on = MakeDirectionalLight(1.0);
  Plan(fog, on, plan, analysis);
  EXPECT_TRUE(plan->IsEnabled(vtkEffectPlan::SINGLE_SCATTERING));
  EXPECT_TRUE(plan->IsEnabled(vtkEffectPlan::MULTIPLE_SCATTERING)); // tau = 2, albedo 0.8
}

// Absorption off drops the extinction, so the scattered light goes with it: a thin lit haze
// (tau 0.0075, under the tolerance) keeps absorption on while it scatters light that is
// simulated. Before, the plan turned absorption off by tau alone and the haze vanished from the
// image (relative change 1.0 under tolerance 0.01). Unlit, or with single scattering forced
// off, tau alone decides again.
TEST(EffectPlan, AbsorptionStaysOnWhileAThinHazeScatters)
{
  auto haze = UniformFog(8, 0.25, 0.004, 1.0);
  vtkNew<vtkSceneAnalysis> analysis;
  vtkNew<vtkEffectPlan> plan;
  Plan(haze, MakeDirectionalLight(1.0), plan, analysis);
  ASSERT_LT(analysis->GetMaximumOpticalThickness(), plan->GetTolerance());
  EXPECT_TRUE(plan->IsEnabled(vtkEffectPlan::ABSORPTION))
    << plan->GetReason(vtkEffectPlan::ABSORPTION);
  EXPECT_TRUE(plan->IsEnabled(vtkEffectPlan::SINGLE_SCATTERING));
  EXPECT_NE(std::string(plan->GetReason(vtkEffectPlan::ABSORPTION)).find("scattered light"),
    std::string::npos);
  Plan(haze, nullptr, plan, analysis);
  EXPECT_FALSE(plan->IsEnabled(vtkEffectPlan::ABSORPTION));
  plan->SetEffectMode(vtkEffectPlan::SINGLE_SCATTERING, vtkEffectPlan::FORCE_OFF);
  Plan(haze, MakeDirectionalLight(1.0), plan, analysis);
  EXPECT_FALSE(plan->IsEnabled(vtkEffectPlan::ABSORPTION));
}

TEST(EffectPlan, EmissionOnlyAndOverrides)
{
  auto glow = MakeMedium(6, 6, 6, 1.0,
    [](int i, int, int)
    {
      Voxel v;
      v.Emission = i == 3 ? 2.0 : 0.0;
      return v;
    });
  vtkNew<vtkSceneAnalysis> analysis;
  vtkNew<vtkEffectPlan> plan;
  Plan(glow, nullptr, plan, analysis);
  EXPECT_TRUE(plan->IsEnabled(vtkEffectPlan::EMISSION));
  EXPECT_FALSE(plan->IsEnabled(vtkEffectPlan::ABSORPTION));
  EXPECT_FALSE(plan->IsEnabled(vtkEffectPlan::REFRACTION));
  EXPECT_NEAR(analysis->GetOccupiedFraction(), 1.0 / 6.0, 1e-12); // one slab of six

  plan->SetEffectMode(vtkEffectPlan::REFRACTION, vtkEffectPlan::FORCE_ON);
  plan->SetEffectMode(vtkEffectPlan::EMISSION, vtkEffectPlan::FORCE_OFF);
  ASSERT_TRUE(plan->Decide(analysis));
  EXPECT_TRUE(plan->IsEnabled(vtkEffectPlan::REFRACTION));
  EXPECT_FALSE(plan->IsEnabled(vtkEffectPlan::EMISSION));
  EXPECT_NE(
    std::string(plan->GetReason(vtkEffectPlan::REFRACTION)).find("forced"), std::string::npos);
  EXPECT_NE(plan->GetSummary().find("Refraction on (forced)"), std::string::npos)
    << plan->GetSummary();

  vtkNew<vtkFieldData> fd;
  plan->RecordInFieldData(fd);
  analysis->RecordInFieldData(fd);
  ASSERT_NE(fd->GetArray("PlanEnabled"), nullptr);
  EXPECT_EQ(fd->GetArray("PlanEnabled")->GetComponent(vtkEffectPlan::REFRACTION, 0), 1);
  EXPECT_EQ(fd->GetArray("PlanEnabled")->GetComponent(vtkEffectPlan::EMISSION, 0), 0);
  ASSERT_NE(fd->GetAbstractArray("PlanSummary"), nullptr);
  EXPECT_NE(fd->GetArray("AnalysisMaximumEmission"), nullptr);
  EXPECT_EQ(fd->GetArray("AnalysisMaximumEmission")->GetComponent(0, 0), 2.0);
}

TEST(EffectPlan, BadInputsAreReported)
{
  vtkNew<vtkSceneAnalysis> analysis;
  vtkNew<vtkTest::ErrorObserver> observer;
  analysis->AddObserver(vtkCommand::ErrorEvent, observer);
  EXPECT_FALSE(analysis->Analyze()); // no medium
  EXPECT_NE(observer->GetErrorMessage().find("null"), std::string::npos);
  observer->Clear();
  auto bad = MakeMedium(2, 2, 2, 1.0,
    [](int, int, int)
    {
      Voxel v;
      v.Albedo = 1.5;
      return v;
    });
  analysis->SetMedium(bad);
  EXPECT_FALSE(analysis->Analyze());
  EXPECT_NE(observer->GetErrorMessage().find("'Albedo'"), std::string::npos);

  vtkNew<vtkEffectPlan> plan;
  vtkNew<vtkTest::ErrorObserver> planObserver;
  plan->AddObserver(vtkCommand::ErrorEvent, planObserver);
  EXPECT_FALSE(plan->Decide(nullptr));
  plan->SetEffectMode(17, vtkEffectPlan::FORCE_ON);
  EXPECT_NE(planObserver->GetErrorMessage().find("SetEffectMode(17"), std::string::npos);
  EXPECT_FALSE(plan->IsEnabled(17));
}

TEST(SceneAnalysis, TinyAndThinGrids)
{
  auto one = MakeMedium(1, 1, 1, 0.5,
    [](int, int, int)
    {
      Voxel v;
      v.SigmaT = 4.0;
      v.N = 1.5;
      return v;
    });
  vtkNew<vtkSceneAnalysis> analysis;
  vtkNew<vtkEffectPlan> plan;
  Plan(one, nullptr, plan, analysis);
  EXPECT_NEAR(analysis->GetMaximumOpticalThickness(), 2.0, 1e-6);
  EXPECT_EQ(analysis->GetMaximumBendingAngle(), 0.0); // one voxel has no gradient
  auto line = MakeMedium(1, 1, 512, 0.01,
    [](int, int, int k)
    {
      Voxel v;
      v.SigmaT = k < 256 ? 1.0 : 0.0;
      return v;
    });
  Plan(line, nullptr, plan, analysis);
  EXPECT_NEAR(analysis->GetMaximumOpticalThickness(2), 2.56, 1e-5);
  EXPECT_NEAR(analysis->GetMaximumOpticalThickness(0), 0.01, 1e-6);
  EXPECT_DOUBLE_EQ(analysis->GetOccupiedFraction(), 0.5);
}

TEST(EffectPlan, SurfacesNeedThePhotonPassInAClearMedium)
{
  // Clear glass (n = 1.5 in the middle, nothing absorbs): alone it needs no light pass; with a
  // floor and a powered light, SurfaceLighting is on (the caustic on the floor) and the plan says
  // why; an empty surface, no light or a forced-off mode turn it off.
  auto glass = MakeMedium(8, 8, 8, 0.25,
    [](int i, int j, int k)
    {
      Voxel v;
      v.N = (i > 2 && i < 5 && j > 2 && j < 5 && k > 2 && k < 5) ? 1.5 : 1.0;
      return v;
    });
  vtkNew<vtkSceneAnalysis> analysis;
  vtkNew<vtkEffectPlan> plan;
  auto sun = MakeDirectionalLight(1.0);
  Plan(glass, sun, plan, analysis);
  EXPECT_FALSE(plan->IsEnabled(vtkEffectPlan::SINGLE_SCATTERING));
  EXPECT_FALSE(plan->IsEnabled(vtkEffectPlan::SURFACE_LIGHTING));
  EXPECT_STREQ(vtkEffectPlan::GetEffectName(vtkEffectPlan::SURFACE_LIGHTING), "SurfaceLighting");

  vtkNew<vtkRefractaSurfaceSet> surfaces;
  vtkNew<vtkPolyData> empty;
  surfaces->AddSurface(empty);
  analysis->SetSurfaces(surfaces);
  Plan(glass, sun, plan, analysis);
  EXPECT_EQ(analysis->GetNumberOfSurfaces(), 0);
  EXPECT_FALSE(plan->IsEnabled(vtkEffectPlan::SURFACE_LIGHTING));

  vtkNew<vtkPlaneSource> floor;
  floor->Update();
  surfaces->AddSurface(floor->GetOutput());
  Plan(glass, sun, plan, analysis);
  EXPECT_EQ(analysis->GetNumberOfSurfaces(), 1);
  EXPECT_TRUE(plan->IsEnabled(vtkEffectPlan::SURFACE_LIGHTING));
  EXPECT_FALSE(plan->IsEnabled(vtkEffectPlan::SINGLE_SCATTERING));
  EXPECT_NE(std::string(plan->GetReason(vtkEffectPlan::SURFACE_LIGHTING)).find("1 surface(s)"),
    std::string::npos);
  EXPECT_NE(analysis->GetSummary().find("1 surface(s)"), std::string::npos);

  Plan(glass, nullptr, plan, analysis);
  EXPECT_FALSE(plan->IsEnabled(vtkEffectPlan::SURFACE_LIGHTING)) << "no light, nothing to light";
  plan->SetEffectMode(vtkEffectPlan::SURFACE_LIGHTING, vtkEffectPlan::FORCE_OFF);
  Plan(glass, sun, plan, analysis);
  EXPECT_FALSE(plan->IsEnabled(vtkEffectPlan::SURFACE_LIGHTING));
}

// Voxels a million times longer on x than on y and z (a grid 16e6 long and 0.8 wide): the probes
// toward the light march half a voxel per step along the axis they cross fastest, so the
// analysis ends at once (half the smallest spacing per step took ~3e7 steps a probe) with the
// same optical depth: sigma_t 1e-6 over 15/16 of the 16e6 length, within one step (tau 0.5).
TEST(SceneAnalysis, ElongatedVoxelsProbeInVoxelSteps)
{
  auto medium = MakeMedium(16, 8, 8, 0.1,
    [](int, int, int)
    {
      Voxel v;
      v.SigmaT = 1e-6;
      return v;
    });
  medium->SetSpacing(1e6, 0.1, 0.1);
  vtkNew<vtkSceneAnalysis> analysis;
  vtkNew<vtkEffectPlan> plan;
  auto light = MakeDirectionalLight(1.0);
  light->SetPosition(-1e8, 0.35, 0.35);
  light->SetFocalPoint(0, 0.35, 0.35);
  Plan(medium, light, plan, analysis);
  EXPECT_NEAR(analysis->GetOpticalThicknessTowardLight(0), 1e-6 * (15.0 / 16.0) * 16e6, 0.5);
}

// A light move re-runs only the light probes: the medium's facts are reused while the medium is
// unmodified (one scan), are identical to a fresh analysis's, and are recomputed after the medium
// changes (Modified()) or another medium is given.
TEST(SceneAnalysis, MediumFactsAreReusedUntilTheMediumChanges)
{
  auto medium = MakeMedium(12, 10, 8, 0.1,
    [](int i, int, int)
    {
      Voxel v;
      v.SigmaT = 0.2 * i;
      v.Albedo = 0.6;
      v.N = 1.0 + 0.01 * i;
      return v;
    });
  auto light = MakeDirectionalLight(1.0);
  vtkNew<vtkSceneAnalysis> analysis;
  analysis->SetMedium(medium);
  analysis->AddLight(light);
  ASSERT_TRUE(analysis->Analyze());
  const double fromMinusX = analysis->GetOpticalThicknessTowardLight(0);
  light->SetPosition(10, 0.5, 0.5); // now travels along -x
  ASSERT_TRUE(analysis->Analyze());
  EXPECT_EQ(analysis->GetNumberOfMediumScans(), 1);
  EXPECT_NE(analysis->GetOpticalThicknessTowardLight(0), fromMinusX);

  vtkNew<vtkSceneAnalysis> fresh;
  fresh->SetMedium(medium);
  fresh->AddLight(light);
  ASSERT_TRUE(fresh->Analyze());
  EXPECT_EQ(analysis->GetSummary(), fresh->GetSummary());
  EXPECT_EQ(analysis->GetOpticalThicknessTowardLight(0), fresh->GetOpticalThicknessTowardLight(0));

  // Change the medium in place: the next analysis scans it again and sees the change.
  vtkDataArray* extinction = medium->GetPointData()->GetArray("Extinction");
  for (vtkIdType p = 0; p < extinction->GetNumberOfTuples(); ++p)
  {
    for (int c = 0; c < 3; ++c)
    {
      extinction->SetComponent(p, c, 2 * extinction->GetComponent(p, c));
    }
  }
  const double before = analysis->GetMaximumOpticalThickness();
  extinction->Modified();
  medium->Modified();
  ASSERT_TRUE(analysis->Analyze());
  EXPECT_EQ(analysis->GetNumberOfMediumScans(), 2);
  EXPECT_NEAR(analysis->GetMaximumOpticalThickness(), 2 * before, 1e-9 * before);

  // An invalid medium is never served from the cache of a valid one.
  vtkNew<vtkImageData> empty;
  analysis->SetMedium(empty);
  vtkNew<vtkTest::ErrorObserver> errors;
  analysis->AddObserver(vtkCommand::ErrorEvent, errors);
  EXPECT_FALSE(analysis->Analyze());
  EXPECT_TRUE(errors->GetError());
}

// The multiple-scattering method (issue 14): automatically the lattice alone where every light is
// outside a medium that does not focus light, and the first-collision split where one is inside
// or where refraction displaces light by a voxel or more (issue 19: the GRIN lens's truth), with
// the smallest k whose measured ray-effect anisotropy is within the tolerance for the lattice in
// use; forced methods and orders are honoured; lit surfaces always get photons carrying every
// order; the choice is recorded with its reason.
TEST(EffectPlan, MultipleScatteringMethodFollowsTheToleranceAndTheLattice)
{
  auto fog = UniformFog(10, 0.1, 2.0, 0.95);
  vtkNew<vtkSceneAnalysis> analysis;
  vtkNew<vtkEffectPlan> plan;
  auto outside = MakeDirectionalLight(1.0);
  Plan(fog, outside, plan, analysis);
  ASSERT_TRUE(plan->IsEnabled(vtkEffectPlan::MULTIPLE_SCATTERING));
  EXPECT_EQ(analysis->GetNumberOfLightsInsideMedium(), 0);
  EXPECT_EQ(plan->GetChosenMultipleScatteringMethod(), vtkEffectPlan::LATTICE_ONLY)
    << plan->GetMultipleScatteringMethodReason();
  // The same fog with n = 1 + 0.3 y bends the light by several voxels: refraction can focus it
  // into a concentrated source inside the medium (a GRIN lens), so the split, with the light
  // outside. A tiny gradient (less than a voxel of displacement, refraction still on) does not.
  for (const double a : { 0.3, 0.002 })
  {
    auto grin = MakeMedium(10, 10, 10, 0.1,
      [a](int, int j, int)
      {
        Voxel v;
        v.N = 1.0 + a * 0.1 * j;
        v.SigmaT = 2.0;
        v.Albedo = 0.95;
        return v;
      });
    Plan(grin, outside, plan, analysis); // tolerance 0.01 (default): k = 7 with D3Q6
    const bool focusing = analysis->GetMaximumDisplacementInVoxels() >= 1.0;
    EXPECT_EQ(focusing, a > 0.1) << analysis->GetMaximumDisplacementInVoxels();
    EXPECT_EQ(plan->GetChosenMultipleScatteringMethod(),
      focusing ? vtkEffectPlan::FIRST_COLLISION_SPLIT : vtkEffectPlan::LATTICE_ONLY)
      << plan->GetMultipleScatteringMethodReason();
    if (focusing)
    {
      EXPECT_NE(std::string(plan->GetMultipleScatteringMethodReason()).find("refraction can focus"),
        std::string::npos);
      EXPECT_EQ(plan->GetChosenScatteringOrders(), 7);
    }
  }
  auto sun = vtkSmartPointer<vtkLight>::New(); // a point light in the fog (box [-0.05, 0.95])
  sun->SetPositional(true);
  sun->SetConeAngle(180);
  sun->SetPosition(0.45, 0.5, 0.9);
  sun->SetFocalPoint(0.45, 0.5, 0.0);
  Plan(fog, sun, plan, analysis);
  EXPECT_EQ(analysis->GetNumberOfLightsInsideMedium(), 1);
  EXPECT_EQ(plan->GetChosenMultipleScatteringMethod(), vtkEffectPlan::FIRST_COLLISION_SPLIT);
  // Tolerance 0.01, D3Q6: 0.012 at k = 6 is above it, 0.0085 at k = 7 within.
  EXPECT_EQ(plan->GetChosenScatteringOrders(), 7) << plan->GetMultipleScatteringMethodReason();
  EXPECT_NE(plan->GetSummary().find("multiple scattering by split (k = 7)"), std::string::npos);
  plan->SetLatticeDirections(18); // 0.0076 at k = 3
  Plan(fog, sun, plan, analysis);
  EXPECT_EQ(plan->GetChosenScatteringOrders(), 3);
  plan->SetTolerance(0.05); // D3Q18: 0.028 at k = 2
  Plan(fog, sun, plan, analysis);
  EXPECT_EQ(plan->GetChosenScatteringOrders(), 2);
  plan->SetLatticeDirections(6); // D3Q6: 0.049 at k = 4
  Plan(fog, sun, plan, analysis);
  EXPECT_EQ(plan->GetChosenScatteringOrders(), 4);
  plan->SetTolerance(1e-6); // out of reach: the largest k the plan chooses
  Plan(fog, sun, plan, analysis);
  EXPECT_EQ(plan->GetChosenScatteringOrders(), 8);
  EXPECT_DOUBLE_EQ(vtkEffectPlan::GetRayEffectAnisotropy(6, 0), 2.57);
  EXPECT_DOUBLE_EQ(vtkEffectPlan::GetRayEffectAnisotropy(18, 50), 0.0016);

  // Next to the fog (within 2 voxels of a voxel with extinction) still counts: its single
  // scattering is as concentrated on the grid. Just outside the box (index 9.6) and 1.5 voxels
  // beyond the last node (index 10.5) it is the split; 3 voxels beyond (index 12), the lattice.
  for (double z : { 0.96, 1.05 })
  {
    sun->SetPosition(0.45, 0.5, z);
    Plan(fog, sun, plan, analysis);
    EXPECT_EQ(analysis->GetNumberOfLightsInsideMedium(), 1) << "z = " << z;
  }
  sun->SetPosition(0.45, 0.5, 1.2);
  Plan(fog, sun, plan, analysis);
  EXPECT_EQ(analysis->GetNumberOfLightsInsideMedium(), 0);
  EXPECT_EQ(plan->GetChosenMultipleScatteringMethod(), vtkEffectPlan::LATTICE_ONLY);
  // In the middle of a hollow of vacuum in the fog (voxels 2..7 empty on every axis): 2.5 voxels
  // from the nearest fog, the lattice; within 2 voxels of the hollow's wall, the split.
  auto hollow = MakeMedium(10, 10, 10, 0.1,
    [](int i, int j, int k)
    {
      Voxel v;
      const bool empty = i >= 2 && i <= 7 && j >= 2 && j <= 7 && k >= 2 && k <= 7;
      v.SigmaT = empty ? 0.0 : 2.0;
      v.Albedo = 0.95;
      return v;
    });
  sun->SetPosition(0.45, 0.45, 0.45);
  Plan(hollow, sun, plan, analysis);
  EXPECT_EQ(analysis->GetNumberOfLightsInsideMedium(), 0);
  sun->SetPosition(0.3, 0.45, 0.45);
  Plan(hollow, sun, plan, analysis);
  EXPECT_EQ(analysis->GetNumberOfLightsInsideMedium(), 1);
  sun->SetPosition(0.45, 0.5, 0.9);

  // The same fog with a non-zero extent, moved and turned 90 degrees about z: the light is found
  // in it through the grid's frame (index (4.5, 5, 9) from the first point), not by its bounds.
  auto turned = vtkSmartPointer<vtkImageData>::New();
  turned->DeepCopy(fog);
  turned->SetExtent(3, 12, -2, 7, 5, 14);
  turned->SetOrigin(5.0, -1.0, 2.0);
  turned->SetDirectionMatrix(0, -1, 0, 1, 0, 0, 0, 0, 1);
  double world[3];
  turned->TransformContinuousIndexToPhysicalPoint(3 + 4.5, -2 + 5.0, 5 + 9.0, world);
  sun->SetPosition(world);
  Plan(turned, sun, plan, analysis);
  EXPECT_EQ(analysis->GetNumberOfLightsInsideMedium(), 1);
  EXPECT_EQ(plan->GetChosenMultipleScatteringMethod(), vtkEffectPlan::FIRST_COLLISION_SPLIT);
  sun->SetPosition(0.45, 0.5, 0.9); // inside the unturned fog, outside the turned one
  Plan(turned, sun, plan, analysis);
  EXPECT_EQ(analysis->GetNumberOfLightsInsideMedium(), 0);

  // Forced methods and orders.
  plan->SetTolerance(0.01);
  plan->SetMultipleScatteringMethod(vtkEffectPlan::LATTICE_ONLY);
  Plan(fog, sun, plan, analysis);
  EXPECT_EQ(plan->GetChosenMultipleScatteringMethod(), vtkEffectPlan::LATTICE_ONLY);
  EXPECT_EQ(plan->GetChosenScatteringOrders(), 0);
  plan->SetMultipleScatteringMethod(vtkEffectPlan::PHOTONS_EVERY_ORDER);
  Plan(fog, sun, plan, analysis);
  EXPECT_EQ(plan->GetChosenScatteringOrders(), -1);
  plan->SetMultipleScatteringMethod(vtkEffectPlan::FIRST_COLLISION_SPLIT);
  plan->SetScatteringOrders(2);
  Plan(fog, sun, plan, analysis);
  EXPECT_EQ(plan->GetChosenScatteringOrders(), 2);
  EXPECT_STREQ(plan->GetMultipleScatteringMethodReason(), "k = 2 forced; D3Q6 forced");
  EXPECT_EQ(vtkEffectPlan::GetMultipleScatteringMethodFromName("split"),
    vtkEffectPlan::FIRST_COLLISION_SPLIT);
  EXPECT_EQ(vtkEffectPlan::GetMultipleScatteringMethodFromName("d3q7"), -1);
  EXPECT_EQ(vtkEffectPlan::GetMultipleScatteringMethodName(99), nullptr);

  // Lit surfaces: photons carry every order whatever was asked (the lattice knows none).
  vtkNew<vtkRefractaSurfaceSet> surfaces;
  vtkNew<vtkPlaneSource> floor;
  floor->Update();
  surfaces->AddSurface(floor->GetOutput());
  analysis->SetSurfaces(surfaces);
  Plan(fog, sun, plan, analysis);
  EXPECT_EQ(plan->GetChosenMultipleScatteringMethod(), vtkEffectPlan::PHOTONS_EVERY_ORDER);
  EXPECT_EQ(plan->GetChosenScatteringOrders(), -1);
  // The forced split is overridden, and the reason says so.
  EXPECT_NE(
    std::string(plan->GetMultipleScatteringMethodReason()).find("forced, but"), std::string::npos)
    << plan->GetMultipleScatteringMethodReason();
  vtkNew<vtkFieldData> fd;
  plan->RecordInFieldData(fd);
  auto* recorded =
    vtkStringArray::SafeDownCast(fd->GetAbstractArray("PlanMultipleScatteringMethod"));
  ASSERT_NE(recorded, nullptr);
  EXPECT_EQ(recorded->GetValue(0), "photons");
}
