// Honesty of the effect plan, end to end: one scene per effect combination goes through the
// scene analysis, the plan, and the passes the plan keeps (photon tracer, Lattice-Boltzmann
// lighting, view pass). The plan's decisions are asserted, and for every effect it turns off the
// scene is rendered again with that effect forced on: the image must not change by more than the
// estimate the plan gave (relative L2 difference of the HDR image), which is below the tolerance.
#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkEffectPlan.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkPhotonTracer.h"
#include "vtkPointData.h"
#include "vtkRefractaImageRenderer.h"
#include "vtkRefractaRenderPipeline.h"
#include "vtkSceneAnalysis.h"
#include "vtkSmartPointer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

namespace
{
struct Voxel
{
  double N = 1.0, SigmaT = 0.0, Albedo = 0.0, Emission = 0.0;
};

struct Scene
{
  vtkSmartPointer<vtkImageData> Medium;
  vtkSmartPointer<vtkLight> Light; // may be null
  double Background = 0.0;
};

Scene MakeScene(const std::function<Voxel(double, double, double)>& f, bool lit, double background)
{
  const int n = 20;
  const double h = 1.0 / n;
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(n, n, n);
  image->SetSpacing(h, h, h);
  image->SetOrigin(0.5 * h, 0.5 * h, 0.5 * h);
  auto add = [&](const char* name, int comps)
  {
    vtkNew<vtkFloatArray> a;
    a->SetName(name);
    a->SetNumberOfComponents(comps);
    a->SetNumberOfTuples(image->GetNumberOfPoints());
    image->GetPointData()->AddArray(a);
    return a.GetPointer();
  };
  vtkFloatArray* index = add("RefractiveIndex", 1);
  vtkFloatArray* ext = add("Extinction", 3);
  vtkFloatArray* alb = add("Albedo", 3);
  vtkFloatArray* emi = add("Emission", 3);
  for (int k = 0; k < n; ++k)
  {
    for (int j = 0; j < n; ++j)
    {
      for (int i = 0; i < n; ++i)
      {
        const vtkIdType p = i + n * (j + n * k);
        const Voxel v = f((i + 0.5) * h, (j + 0.5) * h, (k + 0.5) * h);
        index->SetValue(p, v.N);
        for (int c = 0; c < 3; ++c)
        {
          ext->SetComponent(p, c, v.SigmaT);
          alb->SetComponent(p, c, v.Albedo);
          emi->SetComponent(p, c, v.Emission);
        }
      }
    }
  }
  Scene scene;
  scene.Medium = image;
  scene.Background = background;
  if (lit)
  {
    scene.Light = vtkSmartPointer<vtkLight>::New();
    scene.Light->SetPositional(false);
    scene.Light->SetPosition(0.5, 3.0, 0.8);
    scene.Light->SetFocalPoint(0.5, 0.5, 0.5);
    scene.Light->SetIntensity(1.0);
  }
  return scene;
}

// Decide the plan for a scene, with `forced` (an effect, or -1) forced on.
void Decide(const Scene& scene, vtkEffectPlan* plan, int forced)
{
  vtkNew<vtkSceneAnalysis> analysis;
  analysis->SetMedium(scene.Medium);
  if (scene.Light)
  {
    analysis->AddLight(scene.Light);
  }
  ASSERT_TRUE(analysis->Analyze());
  for (int e = 0; e < vtkEffectPlan::NUMBER_OF_EFFECTS; ++e)
  {
    plan->SetEffectMode(e, e == forced ? vtkEffectPlan::FORCE_ON : vtkEffectPlan::AUTOMATIC);
  }
  ASSERT_TRUE(plan->Decide(analysis));
}

// Render the scene through the render pipeline with the plan's settings (tolerance and the
// per-effect modes), so that the passes the plan keeps are exactly the shipping ones; returns the
// HDR RGB values.
std::vector<double> Render(const Scene& scene, vtkEffectPlan* plan)
{
  vtkNew<vtkRefractaImageRenderer> renderer;
  vtkRefractaRenderPipeline* pipeline = renderer->GetPipeline();
  pipeline->GetEffectPlan()->SetTolerance(plan->GetTolerance());
  for (int e = 0; e < vtkEffectPlan::NUMBER_OF_EFFECTS; ++e)
  {
    pipeline->GetEffectPlan()->SetEffectMode(e, plan->GetEffectMode(e));
  }
  if (scene.Light)
  {
    renderer->AddLight(scene.Light);
  }
  pipeline->GetPhotonTracer()->SetNumberOfPhotons(1 << 15);
  pipeline->GetPhotonTracer()->SetSeed(3);
  vtkNew<vtkCamera> camera;
  camera->SetPosition(0.5, 0.5, 3.0);
  camera->SetFocalPoint(0.5, 0.5, 0.5);
  camera->SetViewAngle(25);
  renderer->SetInputData(scene.Medium);
  renderer->SetCamera(camera);
  renderer->SetImageSize(32, 32);
  renderer->SetBackgroundColor(scene.Background, scene.Background, scene.Background);
  renderer->Update();
  for (int e = 0; e < vtkEffectPlan::NUMBER_OF_EFFECTS; ++e)
  {
    EXPECT_EQ(pipeline->GetEffectPlan()->IsEnabled(e), plan->IsEnabled(e))
      << "the pipeline decides " << vtkEffectPlan::GetEffectName(e) << " as the test's plan";
  }
  vtkDataArray* hdr = renderer->GetOutput()->GetPointData()->GetArray("HDR");
  std::vector<double> rgb;
  if (!hdr)
  {
    ADD_FAILURE() << "no HDR output";
    return rgb;
  }
  for (vtkIdType p = 0; p < hdr->GetNumberOfTuples(); ++p)
  {
    for (int c = 0; c < 3; ++c)
    {
      rgb.push_back(hdr->GetComponent(p, c));
    }
  }
  return rgb;
}

double RelativeDifference(const std::vector<double>& a, const std::vector<double>& b)
{
  double diff = 0.0, norm = 0.0;
  for (size_t i = 0; i < a.size() && i < b.size(); ++i)
  {
    diff += (a[i] - b[i]) * (a[i] - b[i]);
    norm += b[i] * b[i];
  }
  return norm > 0 ? std::sqrt(diff / norm) : std::sqrt(diff);
}

// Assert the plan's decisions, then that forcing each skipped effect on changes the image by no
// more than the plan's estimate (and the tolerance).
void CheckHonesty(const Scene& scene, const std::vector<bool>& expected, const std::string& name)
{
  // One decision per effect (the last, SurfaceLighting, is off: these scenes have no surfaces).
  ASSERT_EQ(expected.size(), size_t(vtkEffectPlan::NUMBER_OF_EFFECTS)) << name;
  vtkNew<vtkEffectPlan> plan;
  Decide(scene, plan, -1);
  for (int e = 0; e < vtkEffectPlan::NUMBER_OF_EFFECTS; ++e)
  {
    EXPECT_EQ(plan->IsEnabled(e), expected[e])
      << name << ": " << vtkEffectPlan::GetEffectName(e) << " " << plan->GetReason(e);
  }
  const std::vector<double> planned = Render(scene, plan);
  for (int e = 0; e < vtkEffectPlan::NUMBER_OF_EFFECTS; ++e)
  {
    if (plan->IsEnabled(e))
    {
      continue;
    }
    const double estimate = plan->GetEstimatedContribution(e);
    vtkNew<vtkEffectPlan> forced;
    Decide(scene, forced, e);
    const double change = RelativeDifference(planned, Render(scene, forced));
    std::cout << name << ": " << vtkEffectPlan::GetEffectName(e) << " skipped, estimate "
              << estimate << ", measured change " << change << "\n";
    EXPECT_LE(change, std::max(estimate, 1e-6)) << name << ": " << vtkEffectPlan::GetEffectName(e);
    EXPECT_LE(change, plan->GetTolerance()) << name << ": " << vtkEffectPlan::GetEffectName(e);
  }
}

double Ball(double x, double y, double z, double r)
{
  return std::sqrt((x - 0.5) * (x - 0.5) + (y - 0.5) * (y - 0.5) + (z - 0.5) * (z - 0.5)) - r;
}
}

// Effects in enum order: refraction, absorption, single, multiple, emission.
TEST(EffectPlanHonesty, PureAbsorption)
{
  CheckHonesty(MakeScene(
                 [](double x, double y, double z)
                 {
                   Voxel v;
                   v.SigmaT = Ball(x, y, z, 0.3) < 0 ? 3.0 : 0.0;
                   return v;
                 },
                 false, 0.6),
    { false, true, false, false, false, false }, "pure absorption");
}

TEST(EffectPlanHonesty, AbsorptionAndSingleScattering)
{
  // Thin, dark fog: q = 0.15 (1 - exp(-0.05)) = 0.0073 < 0.01, so multiple scattering is skipped.
  CheckHonesty(MakeScene(
                 [](double, double, double)
                 {
                   Voxel v;
                   v.SigmaT = 0.05;
                   v.Albedo = 0.15;
                   return v;
                 },
                 true, 0.0),
    { false, true, true, false, false, false }, "absorption + single scattering");
}

TEST(EffectPlanHonesty, MultipleScattering)
{
  CheckHonesty(MakeScene(
                 [](double x, double y, double z)
                 {
                   Voxel v;
                   v.SigmaT = Ball(x, y, z, 0.35) < 0 ? 8.0 : 0.0;
                   v.Albedo = 0.9;
                   return v;
                 },
                 true, 0.0),
    { false, true, true, true, false, false }, "+ multiple scattering");
}

TEST(EffectPlanHonesty, RefractionWithoutScattering)
{
  CheckHonesty(MakeScene(
                 [](double x, double y, double z)
                 {
                   Voxel v;
                   v.N = 1.0 + 0.3 * 0.5 * (1.0 - std::tanh(Ball(x, y, z, 0.3) / 0.05));
                   return v;
                 },
                 true, 0.5),
    { true, false, false, false, false, false }, "refraction without scattering");
}

TEST(EffectPlanHonesty, Everything)
{
  CheckHonesty(MakeScene(
                 [](double x, double y, double z)
                 {
                   Voxel v;
                   const double inside = 0.5 * (1.0 - std::tanh(Ball(x, y, z, 0.25) / 0.05));
                   v.N = 1.0 + 0.4 * inside;
                   v.SigmaT = 1.0 + 3.0 * inside;
                   v.Albedo = 0.8;
                   v.Emission = 0.2 * inside;
                   return v;
                 },
                 true, 0.1),
    { true, true, true, true, true, false }, "everything");
}

TEST(EffectPlanHonesty, EmissionOnly)
{
  // A glowing ball in a nearly clear medium: tau = 1e-3, so absorption is skipped (estimate
  // 1e-3 < 0.01); forcing it on may change the image by at most that.
  CheckHonesty(MakeScene(
                 [](double x, double y, double z)
                 {
                   Voxel v;
                   v.SigmaT = 1e-3;
                   v.Emission = Ball(x, y, z, 0.3) < 0 ? 1.0 : 0.0;
                   return v;
                 },
                 false, 0.0),
    { false, false, false, false, true, false }, "emission only");
}

TEST(EffectPlanHonesty, RefractionJustPastTheThreshold)
{
  // A faint index bump: the plan's displacement bound sits just above or below the tolerance
  // depending on its height, and the plan switches refraction on exactly when it is above.
  auto bump = [](double height)
  {
    return MakeScene(
      [height](double x, double y, double z)
      {
        Voxel v;
        v.N = 1.0 + height * std::exp(-std::pow(Ball(x, y, z, 0.0) / 0.2, 2));
        return v;
      },
      false, 0.5);
  };
  vtkNew<vtkEffectPlan> plan;
  Decide(bump(1e-3), plan, -1);
  const double estimate = plan->GetEstimatedContribution(vtkEffectPlan::REFRACTION);
  ASSERT_GT(estimate, 0.0);
  // The estimate is proportional to the bump's height (for small bumps): put the tolerance's
  // threshold at 1e-3 * 0.01 / estimate and step just across it.
  const double threshold = 1e-3 * plan->GetTolerance() / estimate;
  Decide(bump(threshold * 0.9), plan, -1);
  EXPECT_FALSE(plan->IsEnabled(vtkEffectPlan::REFRACTION)) << plan->GetReason(0);
  Decide(bump(threshold * 1.1), plan, -1);
  EXPECT_TRUE(plan->IsEnabled(vtkEffectPlan::REFRACTION)) << plan->GetReason(0);
  // And just below the threshold the plan is honest: curved rays change the image less.
  const Scene below = bump(threshold * 0.9);
  Decide(below, plan, -1);
  const std::vector<double> straight = Render(below, plan);
  vtkNew<vtkEffectPlan> forced;
  Decide(below, forced, vtkEffectPlan::REFRACTION);
  EXPECT_LE(RelativeDifference(straight, Render(below, forced)), plan->GetTolerance());
}
