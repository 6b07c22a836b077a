// Refracta.MultipleScatteringDirectionAgainstReference: multiple scattering in a forward-scattering
// cloud (g = 0.8, albedo 0.99) by the render pipeline against the unbiased reference renderer (all
// orders), lit from behind (towards the camera, 34 degrees off its axis) and from the front. Most
// of what the camera sees there has scattered more than once and still travels roughly along the
// light: shaded as isotropic it is half of the truth from behind and twice it from the front. The
// view pass shades S_ms with the phase function of anisotropy g f about its flux over its fluence
// F (length f; Documentation/Physics.md, "The direction of multiple scattering"), which the lattice
// takes from its distributions and the photons from their deposits.
//
// Scene: a ball of radius 0.35 in [0, 1]^3 with a soft edge (sigma_t 8.6 inside r = 0.3, falling
// linearly to 0 at 0.35: an optical diameter of about 6) on 24^3 voxels; a directional light
// (angular radius 0.5 degrees in both renderers); a perspective camera, 32 x 32 pixels. The camera
// and the lights are turned together about the ball's centre (30 degrees about y, 25 about x) so
// that no lattice direction lines up with the view (Physics.md says what D3Q6 does where one
// does).
//
// Statistic (RegionComparison.h, as Refracta.SingleScatteringAgainstReference): regions of 4 x 4
// pixels, |P - R| <= K_SIGMA SE + B max(R, RMS_R), at most MAX_FAILED_REGIONS failed. Each method
// has the budget B it measured plus a margin; the same lighting volume shaded as isotropic (its
// MultipleScatteringDirection removed) must fail that budget: the test sees the direction.
#include "RefractaReferenceImages.h"
#include "RegionComparison.h"

#include "vtkCamera.h"
#include "vtkEffectPlan.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLatticeBoltzmannSolver.h"
#include "vtkLight.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkPhotonTracer.h"
#include "vtkPointData.h"
#include "vtkReferenceRenderer.h"
#include "vtkRefractaImageRenderer.h"
#include "vtkRefractaLightingVolume.h"
#include "vtkRefractaMedium.h"
#include "vtkRefractaRenderPipeline.h"
#include "vtkSmartPointer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>

namespace
{
using refracta::bench::Image;
using refracta::bench::ReadImage;
using refracta_test::Regions;

constexpr int SIZE = 32;
constexpr int BLOCK = 4;
constexpr double K_SIGMA = 4.0;
constexpr int MAX_FAILED_REGIONS = 1;
constexpr double ANGULAR_RADIUS = 0.5; // degrees
constexpr double G = 0.8;

struct Scene
{
  vtkSmartPointer<vtkImageData> Medium;
  vtkSmartPointer<vtkLight> Light;
  vtkSmartPointer<vtkCamera> Camera;
};

vtkSmartPointer<vtkImageData> Ball()
{
  const int n = 24;
  const double h = 1.0 / n;
  auto medium = vtkSmartPointer<vtkImageData>::New();
  medium->SetDimensions(n, n, n);
  medium->SetSpacing(h, h, h);
  medium->SetOrigin(0.5 * h, 0.5 * h, 0.5 * h);
  vtkNew<vtkFloatArray> ext, alb, ani;
  ext->SetName(vtkRefractaMedium::ExtinctionName());
  ext->SetNumberOfComponents(3);
  alb->SetName(vtkRefractaMedium::AlbedoName());
  alb->SetNumberOfComponents(3);
  ani->SetName(vtkRefractaMedium::AnisotropyName());
  for (vtkIdType id = 0; id < medium->GetNumberOfPoints(); ++id)
  {
    double p[3];
    medium->GetPoint(id, p);
    const double centre[3] = { 0.5, 0.5, 0.5 };
    const double r = std::sqrt(vtkMath::Distance2BetweenPoints(p, centre));
    const double sigma = (6.0 / 0.7) * std::min(1.0, std::max(0.0, (0.35 - r) / 0.05));
    for (int c = 0; c < 3; ++c)
    {
      ext->InsertNextValue(static_cast<float>(sigma));
      alb->InsertNextValue(0.99f);
    }
    ani->InsertNextValue(static_cast<float>(G));
  }
  medium->GetPointData()->AddArray(ext);
  medium->GetPointData()->AddArray(alb);
  medium->GetPointData()->AddArray(ani);
  return medium;
}

// p turned about the ball's centre (0.5, 0.5, 0.5) by 30 degrees about y, then 25 about x.
void Turn(const double in[3], double out[3])
{
  const double a = vtkMath::RadiansFromDegrees(30.0), b = vtkMath::RadiansFromDegrees(25.0);
  double x = in[0] - 0.5, y = in[1] - 0.5, z = in[2] - 0.5;
  const double x1 = x * std::cos(a) + z * std::sin(a), z1 = -x * std::sin(a) + z * std::cos(a);
  const double y2 = y * std::cos(b) - z1 * std::sin(b), z2 = y * std::sin(b) + z1 * std::cos(b);
  out[0] = x1 + 0.5;
  out[1] = y2 + 0.5;
  out[2] = z2 + 0.5;
}

// The ball lit from behind (`back`: the light travels towards the camera, 34 degrees off its axis)
// or from the front (above and to the side of the camera); turned (Turn()) or with the camera on
// the grid's z axis.
Scene LitBall(bool back, bool turned = true)
{
  Scene s;
  s.Medium = Ball();
  const double lightAt[3] = { back ? 0.5 + 3 * std::sin(0.6) : 2.0, back ? 0.5 : 2.0,
    back ? 0.5 - 3 * std::cos(0.6) : 3.0 };
  const double eye[3] = { 0.5, 0.5, 3.0 }, up[3] = { 0.5, 1.5, 0.5 };
  double p[3] = { lightAt[0], lightAt[1], lightAt[2] }, e[3] = { eye[0], eye[1], eye[2] },
         u[3] = { up[0], up[1], up[2] };
  if (turned)
  {
    Turn(lightAt, p);
    Turn(eye, e);
    Turn(up, u);
  }
  s.Light = vtkSmartPointer<vtkLight>::New();
  s.Light->SetLightTypeToSceneLight();
  s.Light->PositionalOff();
  s.Light->SetPosition(p);
  s.Light->SetFocalPoint(0.5, 0.5, 0.5);
  s.Light->SetIntensity(1.0);
  s.Camera = vtkSmartPointer<vtkCamera>::New();
  s.Camera->SetPosition(e);
  s.Camera->SetFocalPoint(0.5, 0.5, 0.5);
  s.Camera->SetViewUp(u[0] - 0.5, u[1] - 0.5, u[2] - 0.5);
  s.Camera->SetViewAngle(22);
  return s;
}

Regions RenderReference(const Scene& s, int spp)
{
  vtkNew<vtkReferenceRenderer> r;
  r->SetInputData(s.Medium);
  r->SetCamera(s.Camera);
  r->AddLight(s.Light);
  r->SetDirectionalLightAngularRadius(ANGULAR_RADIUS);
  r->SetImageSize(SIZE, SIZE);
  r->SetSamplesPerPixel(spp);
  r->SetSeed(3);
  r->Update();
  const Image image = ReadImage(r->GetOutput());
  std::cout << "reference " << image.Seconds << " s (" << spp << " samples per pixel)" << std::endl;
  return refracta_test::Pool(image, SIZE, BLOCK);
}

vtkSmartPointer<vtkRefractaImageRenderer> MakeRenderer(const Scene& s)
{
  auto renderer = vtkSmartPointer<vtkRefractaImageRenderer>::New();
  renderer->AddLight(s.Light);
  renderer->GetPipeline()->GetPhotonTracer()->SetDirectionalLightAngularRadius(ANGULAR_RADIUS);
  renderer->SetInputData(s.Medium);
  renderer->SetCamera(s.Camera);
  renderer->SetImageSize(SIZE, SIZE);
  return renderer;
}

struct Method
{
  const char* Name;
  int MultipleMethod;
  int Lattice;
  double Budget; // B, a fraction of max(R, RMS_R)
};

// The pipeline's image by `m` and the number of its regions outside the budget.
int FailedRegions(const Scene& s, const Regions& ref, const Method& m,
  vtkSmartPointer<vtkRefractaImageRenderer>& renderer)
{
  renderer = MakeRenderer(s);
  vtkRefractaRenderPipeline* pipeline = renderer->GetPipeline();
  pipeline->SetMultipleScatteringMethod(m.MultipleMethod);
  pipeline->SetLattice(m.Lattice);
  pipeline->GetPhotonTracer()->SetNumberOfPhotons(1 << 18);
  renderer->Update();
  const Regions image = refracta_test::Pool(ReadImage(renderer->GetOutput()), SIZE, BLOCK);
  EXPECT_EQ(image.Mean.size(), ref.Mean.size());
  return image.Mean.size() == ref.Mean.size()
    ? refracta_test::FailedRegions(image, ref, K_SIGMA, m.Budget, m.Name)
    : static_cast<int>(ref.Mean.size());
}

// The pipeline's image by `m`, checked against its budget; then the same lighting volume without
// S_ms's direction (shaded as isotropic), which must fail it.
void Check(const Scene& s, const Regions& ref, const Method& m)
{
  vtkSmartPointer<vtkRefractaImageRenderer> renderer;
  EXPECT_LE(FailedRegions(s, ref, m, renderer), MAX_FAILED_REGIONS);
  vtkRefractaRenderPipeline* pipeline = renderer->GetPipeline();

  vtkNew<vtkImageData> lighting;
  lighting->DeepCopy(pipeline->GetLighting());
  ASSERT_NE(lighting->GetPointData()->GetArray(
              vtkRefractaLightingVolume::MultipleScatteringDirectionName()),
    nullptr)
    << m.Name << ": no direction for S_ms";
  lighting->GetPointData()->RemoveArray(
    vtkRefractaLightingVolume::MultipleScatteringDirectionName());
  auto isotropic = MakeRenderer(s);
  isotropic->SetLightingData(lighting);
  isotropic->Update();
  EXPECT_GT(refracta_test::FailedRegions(
              refracta_test::Pool(ReadImage(isotropic->GetOutput()), SIZE, BLOCK), ref, K_SIGMA,
              m.Budget, std::string(m.Name) + ", S_ms isotropic"),
    MAX_FAILED_REGIONS)
    << m.Name << ": shaded as isotropic it passes too: the test cannot see the direction";
}

// Every method on the ball lit from behind or from the front, each within its budget B
// (lattice D3Q6, lattice D3Q18, photons carrying every order). The split, which merges the two
// (RefractaTransport.LatticeBoltzmannDirection checks the merge), measured 32.3% from behind and
// 11.5% from the front here; it is left out to keep the default suite within its time.
void CheckEveryMethod(bool back, const double (&budget)[3])
{
  const Method methods[3] = { { "lattice D3Q6", vtkEffectPlan::LATTICE_ONLY, 6, budget[0] },
    { "lattice D3Q18", vtkEffectPlan::LATTICE_ONLY, 18, budget[1] },
    { "photons, every order", vtkEffectPlan::PHOTONS_EVERY_ORDER, 6, budget[2] } };
  const Scene s = LitBall(back);
  const Regions ref = RenderReference(s, 2048);
  for (const Method& m : methods)
  {
    Check(s, ref, m);
  }
}
} // namespace

// From behind: the light the camera sees has scattered forwards, towards it. Measured (PoCL on
// the CPU; the smallest B with no region failed, bias; shaded as isotropic): lattice D3Q6 30.7%,
// -14.9% (60.2%, -54.9%); D3Q18 25.4%, +0.4% (58.0%, -54.6%); the split (D3Q6, k = 7) 32.3%,
// +10.7% (58.8%, -52.8%); photons carrying every order (2^18) 32.6%, +11.3% (58.6%, -52.4%). The
// largest region errors are at the limb the light enters by, where the light has scattered only a
// few times and is narrower than the lobe p_HG(f) about F (Physics.md). B: the measured + 5%.
TEST(MultipleScatteringDirectionAgainstReference, ForwardScatteringBallLitFromBehind)
{
  CheckEveryMethod(true, { 0.36, 0.31, 0.38 });
}

// From the front: most of the light scatters away from the camera. Measured as above: lattice
// D3Q6 52.5%, +26.6% (160.9%, +110.2%); D3Q18 11.2%, -6.5% (102.6%, +75.7%); the split 11.5%,
// -12.4% (175.4%, +122.1%); photons 8.4%, -9.6% (179.7%, +124.5%). D3Q6's six directions carry
// the light along the lattice's axes, not along the light. B: the measured + 5%.
TEST(MultipleScatteringDirectionAgainstReference, ForwardScatteringBallLitFromTheFront)
{
  CheckEveryMethod(false, { 0.58, 0.17, 0.14 });
}

// Lit from behind with the camera and the light's mean direction on the grid's z axis, D3Q6's
// worst case: its six directions pull the multiply scattered light's direction onto the axis,
// straight into the camera (Physics.md: +84% over the image). The plan's automatic lattice
// (vtkEffectPlan::AUTOMATIC_LATTICE) sees the medium's mean |g| of 0.8 and runs D3Q18. Measured
// as above: automatic (D3Q18) 19.6%, -17.9%; D3Q6 forced 167.6%, +80.0%. B: the measured + 5%,
// which D3Q6 must fail.
TEST(MultipleScatteringDirectionAgainstReference, AutomaticLatticeAlongTheGridAxis)
{
  const Scene s = LitBall(true, false);
  const Regions ref = RenderReference(s, 2048);
  const double budget = 0.25;
  const Method automatic = { "lattice, automatic", vtkEffectPlan::LATTICE_ONLY,
    vtkEffectPlan::AUTOMATIC_LATTICE, budget };
  vtkSmartPointer<vtkRefractaImageRenderer> renderer;
  EXPECT_LE(FailedRegions(s, ref, automatic, renderer), MAX_FAILED_REGIONS);
  EXPECT_EQ(renderer->GetPipeline()->GetEffectPlan()->GetChosenLatticeDirections(), 18);
  EXPECT_EQ(renderer->GetPipeline()->GetLatticeSolver()->GetLattice(), 18);
  const Method d3q6 = { "lattice D3Q6", vtkEffectPlan::LATTICE_ONLY, 6, budget };
  EXPECT_GT(FailedRegions(s, ref, d3q6, renderer), MAX_FAILED_REGIONS)
    << "D3Q6 passes the automatic lattice's budget: the test cannot see the lattice's choice";
}
