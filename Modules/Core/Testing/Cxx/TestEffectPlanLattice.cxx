// The effect plan's choice of the Lattice-Boltzmann lattice: vtkSceneAnalysis's scattering-weighted
// mean |g| (an analytic value) and the plan's D3Q6 / D3Q18 decision around its threshold, forced
// lattices, bad values, the memory guard and the split's k, which follows the chosen lattice.
#include "EffectPlanTestMedium.h"

#include "vtkEffectPlan.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkSceneAnalysis.h"
#include "vtkSmartPointer.h"
#include "vtkTestErrorObserver.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace
{
// A fog of 8^3 voxels of 0.1: the half with i < 4 of extinction `sigmaLow`, anisotropy `gLow`,
// the other half `sigmaHigh`, `gHigh`; albedo 0.9 everywhere.
vtkSmartPointer<vtkImageData> TwoHalves(
  double sigmaLow, double gLow, double sigmaHigh, double gHigh)
{
  return refracta_test::MakeMedium(8, 8, 8, 0.1,
    [=](int i, int, int)
    {
      refracta_test::Voxel v;
      v.SigmaT = i < 4 ? sigmaLow : sigmaHigh;
      v.Anisotropy = i < 4 ? gLow : gHigh;
      v.Albedo = 0.9;
      return v;
    });
}

vtkSmartPointer<vtkLight> Light(bool inside)
{
  auto light = vtkSmartPointer<vtkLight>::New();
  light->SetPositional(inside);
  light->SetConeAngle(180);
  light->SetPosition(inside ? 0.35 : -10.0, 0.35, 0.35);
  light->SetFocalPoint(inside ? 0.35 : 0.0, inside ? 0.0 : 0.35, 0.35);
  return light;
}

// Analyse `medium` under one light and let `plan` decide.
void Decide(vtkImageData* medium, bool lightInside, vtkEffectPlan* plan)
{
  vtkNew<vtkSceneAnalysis> analysis;
  analysis->SetMedium(medium);
  analysis->AddLight(Light(lightInside));
  ASSERT_TRUE(analysis->Analyze());
  ASSERT_TRUE(plan->Decide(analysis));
}

bool Says(vtkEffectPlan* plan, const char* text)
{
  return std::string(plan->GetMultipleScatteringMethodReason()).find(text) != std::string::npos;
}
}

// sum sigma_s |g| / sum sigma_s: halves of sigma_s 0.9 (g 0.8) and 2.7 (g -0.2) give
// (0.9 * 0.8 + 2.7 * 0.2) / 3.6 = 0.35; the field data and the summary carry it.
TEST(SceneAnalysis, MeanAnisotropyIsWeightedByScattering)
{
  vtkNew<vtkSceneAnalysis> analysis;
  analysis->SetMedium(TwoHalves(1.0, 0.8, 3.0, -0.2));
  ASSERT_TRUE(analysis->Analyze());
  EXPECT_NEAR(analysis->GetMeanAnisotropy(), 0.35, 1e-6);
  vtkNew<vtkFieldData> fd;
  analysis->RecordInFieldData(fd);
  ASSERT_NE(fd->GetArray("AnalysisMeanAnisotropy"), nullptr);
  EXPECT_NEAR(fd->GetArray("AnalysisMeanAnisotropy")->GetComponent(0, 0), 0.35, 1e-6);
  EXPECT_NE(analysis->GetSummary().find("mean |g| 0.35"), std::string::npos)
    << analysis->GetSummary();

  // A clear half with g = 0.9 weighs nothing; nothing scattering at all gives 0.
  analysis->SetMedium(TwoHalves(0.0, 0.9, 1.0, 0.5));
  ASSERT_TRUE(analysis->Analyze());
  EXPECT_NEAR(analysis->GetMeanAnisotropy(), 0.5, 1e-6);
  analysis->SetMedium(TwoHalves(0.0, 0.9, 0.0, 0.9));
  ASSERT_TRUE(analysis->Analyze());
  EXPECT_EQ(analysis->GetMeanAnisotropy(), 0.0);
}

// The automatic lattice switches to D3Q18 at mean |g| = D3Q18Anisotropy, forward or backward.
TEST(EffectPlan, AutomaticLatticeFollowsTheAnisotropy)
{
  vtkNew<vtkEffectPlan> plan;
  EXPECT_EQ(plan->GetLatticeDirections(), vtkEffectPlan::AUTOMATIC_LATTICE);
  const double threshold = vtkEffectPlan::D3Q18Anisotropy;
  for (const double g : { 0.0, 0.3, threshold - 0.01, threshold + 0.01, 0.8, -0.8 })
  {
    Decide(TwoHalves(1.0, g, 1.0, g), false, plan);
    EXPECT_EQ(plan->GetChosenMultipleScatteringMethod(), vtkEffectPlan::LATTICE_ONLY);
    const int expected = std::abs(g) >= threshold ? 18 : 6;
    EXPECT_EQ(plan->GetChosenLatticeDirections(), expected)
      << "g " << g << ": " << plan->GetMultipleScatteringMethodReason();
    EXPECT_TRUE(Says(plan, expected == 18 ? "D3Q18: the medium's mean |g|" : "D3Q6: the medium's"))
      << plan->GetMultipleScatteringMethodReason();
    EXPECT_NE(plan->GetSummary().find(expected == 18 ? "on D3Q18" : "on D3Q6"), std::string::npos)
      << plan->GetSummary();
    vtkNew<vtkFieldData> fd;
    plan->RecordInFieldData(fd);
    ASSERT_NE(fd->GetArray("PlanLatticeDirections"), nullptr);
    EXPECT_EQ(fd->GetArray("PlanLatticeDirections")->GetComponent(0, 0), expected);
  }
}

// A forced lattice is kept whatever the medium; the split's k follows the lattice that runs; a
// device that cannot hold D3Q18 keeps the automatic lattice on D3Q6 and says so.
TEST(EffectPlan, ForcedLatticeMemoryGuardAndTheSplit)
{
  vtkNew<vtkEffectPlan> plan;
  auto forward = TwoHalves(1.0, 0.8, 1.0, 0.8);
  plan->SetLatticeDirections(6);
  Decide(forward, false, plan);
  EXPECT_EQ(plan->GetChosenLatticeDirections(), 6);
  EXPECT_TRUE(Says(plan, "D3Q6 forced")) << plan->GetMultipleScatteringMethodReason();
  plan->SetLatticeDirections(18);
  Decide(TwoHalves(1.0, 0.0, 1.0, 0.0), false, plan);
  EXPECT_EQ(plan->GetChosenLatticeDirections(), 18);

  // A light inside: the split, k from the chosen lattice's table at tolerance 0.01 (D3Q18: 3,
  // D3Q6: 7).
  plan->SetLatticeDirections(vtkEffectPlan::AUTOMATIC_LATTICE);
  Decide(forward, true, plan);
  EXPECT_EQ(plan->GetChosenMultipleScatteringMethod(), vtkEffectPlan::FIRST_COLLISION_SPLIT);
  EXPECT_EQ(plan->GetChosenLatticeDirections(), 18);
  EXPECT_EQ(plan->GetChosenScatteringOrders(), 3) << plan->GetMultipleScatteringMethodReason();

  plan->SetD3Q18FitsInMemory(false);
  Decide(forward, true, plan);
  EXPECT_EQ(plan->GetChosenLatticeDirections(), 6);
  EXPECT_EQ(plan->GetChosenScatteringOrders(), 7);
  EXPECT_TRUE(Says(plan, "does not fit the device")) << plan->GetMultipleScatteringMethodReason();
  plan->SetLatticeDirections(18); // forced: the solver's memory plan reports what does not fit
  Decide(forward, true, plan);
  EXPECT_EQ(plan->GetChosenLatticeDirections(), 18);

  // Photons carrying every order run no lattice: the reason does not speak of one.
  plan->SetMultipleScatteringMethod(vtkEffectPlan::PHOTONS_EVERY_ORDER);
  Decide(forward, false, plan);
  EXPECT_FALSE(Says(plan, "D3Q")) << plan->GetMultipleScatteringMethodReason();
  EXPECT_EQ(plan->GetSummary().find("on D3Q"), std::string::npos) << plan->GetSummary();
}

TEST(EffectPlan, BadLatticeIsRefused)
{
  vtkNew<vtkEffectPlan> plan;
  vtkNew<vtkTest::ErrorObserver> errors;
  plan->AddObserver(vtkCommand::ErrorEvent, errors);
  for (const int bad : { 7, -6, 27 })
  {
    plan->SetLatticeDirections(bad);
    EXPECT_NE(errors->GetErrorMessage().find("use 0 (automatic), 6 or 18"), std::string::npos);
    errors->Clear();
    EXPECT_EQ(plan->GetLatticeDirections(), vtkEffectPlan::AUTOMATIC_LATTICE);
  }
}
