// Curved view rays and the bent background.
//
// A graded-index (GRIN) sphere n(r) = 1 + 0.5 (1 - r^2 / R^2)^2 (r < R; n = 1 outside) in a clear
// medium, seen by a parallel camera in front of an environment image whose colour encodes the
// direction it is looked up in (R = longitude u, G = latitude v, exactly linear under the
// kernel's bilinear lookup). Each pixel's colour therefore gives its ray's exit direction, which
// is checked against:
// - the ray equation integrated on the host in double precision (RK4, 2000 steps per unit, the
//   analytic n): deflection angle within 3% + 1 mrad away from the rim (the kernel samples a
//   48^3 grid with trilinear n and central-difference grad n, and steps one voxel with a
//   second-order scheme; measured worst 1.9% + 1 mrad; deflections reach 0.97 rad, so a wrong
//   sign, scale or missing 1/n in the ray equation fails by far more);
// - symmetry: the exit direction stays in the plane through the ray and the sphere's centre;
// - rays that miss the sphere, and rays through a constant index (n = 1.5 everywhere: no
//   interface, no bending) keep their direction; a clear medium has alpha 0.
// Then regression images (Testing/Baselines): the sphere in front of a checkerboard (bent
// pattern), and a non-refractive fog lit by a synthetic single-scattering volume.
#include "RenderingTestUtilities.h"

#include "vtkCamera.h"
#include "vtkMath.h"
#include "vtkRefractaEnvironmentMap.h"
#include "vtkRefractaImageRenderer.h"
#include "vtkRefractaLightingVolume.h"
#include "vtkRefractaViewPass.h"
#include "vtkTexture.h"
#include "vtkUnsignedCharArray.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace
{
const int N = 48;
const double Spacing = 1.0 / (N - 1);
const double Centre[3] = { 0.5, 0.5, 0.5 };
const double Radius = 0.4;

double Index(const double x[3])
{
  const double rho = vtkMath::Distance2BetweenPoints(x, Centre) / (Radius * Radius);
  return rho < 1 ? 1 + 0.5 * (1 - rho) * (1 - rho) : 1.0;
}

void IndexGradient(const double x[3], double g[3])
{
  const double rho = vtkMath::Distance2BetweenPoints(x, Centre) / (Radius * Radius);
  for (int a = 0; a < 3; ++a)
  {
    g[a] = rho < 1 ? -2 * (1 - rho) * (x[a] - Centre[a]) / (Radius * Radius) : 0.0;
  }
}

vtkSmartPointer<vtkImageData> GrinSphere(bool constant = false)
{
  auto medium = refracta_test::MakeGrid(N, N, N, Spacing);
  vtkFloatArray* n = refracta_test::AddConstant(medium, "RefractiveIndex", 1, 1.5);
  if (!constant)
  {
    for (vtkIdType p = 0; p < medium->GetNumberOfPoints(); ++p)
    {
      double x[3];
      medium->GetPoint(p, x);
      n->SetValue(p, static_cast<float>(Index(x)));
    }
  }
  return medium;
}

// Environment whose colour is (u, v, 0) at texel centres: bilinear lookup returns (u, v) exactly.
vtkSmartPointer<vtkImageData> DirectionEnvironment()
{
  auto env = refracta_test::MakeGrid(64, 32, 1, 1.0);
  vtkFloatArray* c = refracta_test::AddConstant(env, "uv", 3, 0);
  for (int j = 0; j < 32; ++j)
  {
    for (int i = 0; i < 64; ++i)
    {
      c->SetTuple3(i + 64 * j, (i + 0.5) / 64, (j + 0.5) / 32, 0);
    }
  }
  env->GetPointData()->SetScalars(c);
  return env;
}

// The world direction whose lookup (vtkRefractaEnvironmentMap, default up and right) is (u, v).
void DecodeDirection(const float* rgba, double d[3])
{
  const double uv[2] = { rgba[0], rgba[1] }, up[3] = { 0, 1, 0 }, right[3] = { 1, 0, 0 };
  vtkRefractaEnvironmentMap::TextureToDirection(uv, up, right, d);
}

// Host reference: RK4 on dx/ds = v / n, dv/ds = grad n from (x, y, 2) going -z, until far away.
void ReferenceExit(double x0, double y0, double d[3])
{
  double s[6] = { x0, y0, 2.0, 0, 0, -1 };
  auto deriv = [](const double* st, double* out)
  {
    const double n = Index(st);
    double g[3];
    IndexGradient(st, g);
    for (int a = 0; a < 3; ++a)
    {
      out[a] = st[3 + a] / n;
      out[3 + a] = g[a];
    }
  };
  const double h = 1.0 / 2000;
  for (int step = 0; step < 4 * 2000; ++step)
  {
    double k1[6], k2[6], k3[6], k4[6], t[6];
    deriv(s, k1);
    for (int i = 0; i < 6; ++i)
      t[i] = s[i] + 0.5 * h * k1[i];
    deriv(t, k2);
    for (int i = 0; i < 6; ++i)
      t[i] = s[i] + 0.5 * h * k2[i];
    deriv(t, k3);
    for (int i = 0; i < 6; ++i)
      t[i] = s[i] + h * k3[i];
    deriv(t, k4);
    for (int i = 0; i < 6; ++i)
      s[i] += h / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
  }
  for (int a = 0; a < 3; ++a)
  {
    d[a] = s[3 + a];
  }
  vtkMath::Normalize(d);
}

vtkSmartPointer<vtkCamera> TopCamera()
{
  auto camera = vtkSmartPointer<vtkCamera>::New();
  camera->SetFocalPoint(0.5, 0.5, 0.5);
  camera->SetPosition(0.5, 0.5, 3.0);
  camera->SetViewUp(0, 1, 0);
  camera->ParallelProjectionOn();
  camera->SetParallelScale(0.5);
  return camera;
}
}

TEST(ViewPassRefraction, GrinSphereDeflectionMatchesRayEquation)
{
  auto medium = GrinSphere();
  vtkNew<vtkRefractaImageRenderer> renderer;
  renderer->SetInputData(medium);
  renderer->SetCamera(TopCamera());
  renderer->SetImageSize(40, 40);
  renderer->SetEnvironmentMap(DirectionEnvironment());
  renderer->Update();
  EXPECT_TRUE(renderer->GetViewPass()->GetLastCurved()) << "n varies: AUTO must curve rays";
  auto* hdr = vtkFloatArray::SafeDownCast(renderer->GetOutput()->GetPointData()->GetArray("HDR"));
  ASSERT_NE(hdr, nullptr);
  int checked = 0, bent = 0;
  double worst = 0, worstPlane = 0;
  for (int j = 0; j < 40; ++j)
  {
    for (int i = 0; i < 40; ++i)
    {
      const float* px = hdr->GetPointer(4 * (i + 40 * j));
      const double x0 = (i + 0.5) / 40, y0 = (j + 0.5) / 40;
      double got[3], want[3];
      DecodeDirection(px, got);
      ReferenceExit(x0, y0, want);
      const double alphaGot = std::acos(std::min(1.0, -got[2]));
      const double alphaWant = std::acos(std::min(1.0, -want[2]));
      const double radial[2] = { x0 - 0.5, y0 - 0.5 };
      const double r = std::hypot(radial[0], radial[1]);
      // Within two voxels of the rim the sampled field differs from the analytic one by more
      // than the step error (the grid's half-voxel of support): not a test of the integrator.
      const bool rim = std::abs(r - Radius) < 2 * Spacing;
      const double err = std::abs(alphaGot - alphaWant) / (0.03 * alphaWant + 1e-3);
      worst = rim ? worst : std::max(worst, err);
      if (r > 1e-9)
      {
        // Out-of-plane component: the plane holds (0, 0, -1) and the radial offset.
        const double outOfPlane = std::abs(got[0] * radial[1] - got[1] * radial[0]) / r;
        worstPlane = rim ? worstPlane : std::max(worstPlane, outOfPlane);
        // Converging lens: the exit direction leans towards the axis.
        if (alphaWant > 0.01)
        {
          ++bent;
          EXPECT_LT((got[0] * radial[0] + got[1] * radial[1]) / r, 0.0) << i << "," << j;
        }
      }
      if (r > Radius + 2 * Spacing)
      {
        EXPECT_LT(alphaGot, 1e-4) << "ray missing the sphere bent at pixel " << i << "," << j;
      }
      EXPECT_NEAR(px[3], 0.0f, 1e-6f) << "clear medium must be transparent";
      ++checked;
    }
  }
  std::cout << "worst deflection error " << worst << " (units of 3% + 1 mrad), worst out-of-plane "
            << worstPlane << ", " << bent << " bent rays\n";
  EXPECT_LE(worst, 1.0);
  EXPECT_LT(worstPlane, 2e-3);
  EXPECT_GT(bent, 400);
  EXPECT_EQ(checked, 1600);
}

TEST(ViewPassRefraction, ConstantIndexDoesNotBend)
{
  vtkNew<vtkRefractaImageRenderer> renderer;
  renderer->SetInputData(GrinSphere(true));
  renderer->SetCamera(TopCamera());
  renderer->SetImageSize(16, 16);
  // The environment given as a vtkTexture this time (its input image is used).
  vtkNew<vtkTexture> texture;
  texture->SetInputData(DirectionEnvironment());
  renderer->SetEnvironmentTexture(texture);
  renderer->SetRayModeToCurved();
  renderer->Update();
  EXPECT_FALSE(renderer->GetViewPass()->GetLastCurved());
  auto* hdr = vtkFloatArray::SafeDownCast(renderer->GetOutput()->GetPointData()->GetArray("HDR"));
  for (int p = 0; p < 256; ++p)
  {
    double d[3];
    DecodeDirection(hdr->GetPointer(4 * p), d);
    EXPECT_NEAR(d[2], -1.0, 1e-6);
  }
}

TEST(ViewPassRefraction, RegressionImages)
{
  // 1. The GRIN sphere, perspective, in front of a checkerboard environment.
  vtkNew<vtkImageData> checker;
  checker->SetDimensions(256, 128, 1);
  vtkNew<vtkUnsignedCharArray> colours;
  colours->SetNumberOfComponents(3);
  colours->SetNumberOfTuples(256 * 128);
  for (int j = 0; j < 128; ++j)
  {
    for (int i = 0; i < 256; ++i)
    {
      const bool odd = ((i / 8) + (j / 8)) % 2;
      colours->SetTuple3(i + 256 * j, odd ? 230 : 30, odd ? 220 : 60, odd ? 200 : 120);
    }
  }
  checker->GetPointData()->SetScalars(colours);
  vtkNew<vtkCamera> camera;
  camera->SetFocalPoint(0.5, 0.5, 0.5);
  camera->SetPosition(0.5, 0.7, 2.2);
  camera->SetViewAngle(40);
  vtkNew<vtkRefractaImageRenderer> renderer;
  renderer->SetInputData(GrinSphere());
  renderer->SetCamera(camera);
  renderer->SetImageSize(128, 128);
  renderer->SetEnvironmentMap(checker);
  renderer->Update();
  // Where the sphere is the pattern is bent: the image differs from the straight-ray one there,
  // and is identical far from it.
  vtkNew<vtkImageData> bentImage;
  bentImage->DeepCopy(renderer->GetOutput());
  EXPECT_TRUE(refracta_test::MatchesBaseline(bentImage, "RefractiveSphereBentBackground"));
  renderer->SetRayModeToStraight();
  renderer->Update();
  auto* bent = vtkUnsignedCharArray::SafeDownCast(bentImage->GetPointData()->GetScalars());
  auto* straight =
    vtkUnsignedCharArray::SafeDownCast(renderer->GetOutput()->GetPointData()->GetScalars());
  int changedCentre = 0, changedCorner = 0;
  for (int j = 0; j < 128; ++j)
  {
    for (int i = 0; i < 128; ++i)
    {
      const bool differs =
        bent->GetValue(3 * (i + 128 * j)) != straight->GetValue(3 * (i + 128 * j));
      const double r = std::hypot(i - 63.5, j - 63.5);
      changedCentre += (r < 30 && differs) ? 1 : 0;
      changedCorner += (r > 62 && differs) ? 1 : 0;
    }
  }
  EXPECT_GT(changedCentre, 500) << "the sphere must bend the checkerboard";
  EXPECT_EQ(changedCorner, 0) << "far from the sphere rays are straight";

  // 2. A non-refractive fog lit from +x by a synthetic single-scattering volume:
  //    S1 = sigma_s E exp(-sigma_t (x_max - x)), travelling along -x.
  auto fog = refracta_test::MakeGrid(32, 32, 32, 1.0 / 31);
  const double sigma = 2.0, albedo = 0.8, irradiance = 4.0;
  refracta_test::AddConstant(fog, "Extinction", 3, sigma, sigma, sigma);
  refracta_test::AddConstant(fog, "Albedo", 3, albedo, albedo, albedo);
  refracta_test::AddConstant(fog, "Anisotropy", 1, 0.5);
  vtkNew<vtkImageData> light;
  light->CopyStructure(fog);
  vtkFloatArray* s1 =
    refracta_test::AddConstant(light, vtkRefractaLightingVolume::RadianceName(), 3, 0);
  refracta_test::AddConstant(
    light, vtkRefractaLightingVolume::RadianceDirectionName(), 3, -1, 0, 0);
  for (vtkIdType p = 0; p < fog->GetNumberOfPoints(); ++p)
  {
    double x[3];
    fog->GetPoint(p, x);
    const double v = sigma * albedo * irradiance * std::exp(-sigma * (1 + 0.5 / 31 - x[0]));
    s1->SetTuple3(p, v, 0.8 * v, 0.6 * v);
  }
  vtkNew<vtkCamera> fogCamera;
  fogCamera->SetFocalPoint(0.5, 0.5, 0.5);
  fogCamera->SetPosition(0.5, 0.9, 3.0);
  fogCamera->SetViewAngle(30);
  renderer->SetInputData(fog);
  renderer->SetLightingData(light);
  renderer->SetCamera(fogCamera);
  renderer->SetEnvironmentMap(nullptr);
  renderer->SetBackgroundColor(0.05, 0.05, 0.1);
  renderer->SetRayModeToAuto();
  renderer->Update();
  EXPECT_TRUE(refracta_test::MatchesBaseline(renderer->GetOutput(), "FogSingleScattering"));
  // The lit side (+x, right half of the image) is brighter than the far side.
  auto* hdr = vtkFloatArray::SafeDownCast(renderer->GetOutput()->GetPointData()->GetArray("HDR"));
  double left = 0, right = 0;
  for (int j = 48; j < 80; ++j)
  {
    left += hdr->GetValue(4 * (40 + 128 * j));
    right += hdr->GetValue(4 * (88 + 128 * j));
  }
  EXPECT_GT(right, 1.5 * left);
}
