// The view pass against closed-form answers. A cube of constant extinction sigma, emission eps,
// single-scattering source S1 (constant mean direction, HG g) and multiple-scattering source S_ms,
// seen by straight rays, has per pixel
//   L = Q (1 - exp(-sigma l)) / sigma + exp(-sigma l) L_bg,
//   Q = eps + p_HG(g, dot(dir, -d)) S1 + S_ms / (4 pi)
// (with a MultipleScatteringDirection F of length f: p_HG(g f, dot(F / f, -d)) S_ms, the phase
// function applied to light spread as p_HG(f) about F),
// with l the chord of the pixel's ray through the box [-s/2, (N - 1/2) s] (computed here in
// double precision). Because the kernel integrates each step exactly for a constant medium, the
// answer must hold for any step length, with perspective and parallel cameras, a rotated and
// shifted grid (direction matrix, origin far from zero), and the output's alpha must be
// 1 - mean transmittance; so must the same S1 held in volume-caustic bricks. Tolerance: 2e-5
// relative + 2e-6 absolute (float arithmetic over a few hundred steps; a wrong chord, phase sign or
// transmittance gives errors of 1e-2 or more).
#include "RenderingTestUtilities.h"

#include "vtkCamera.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkIntArray.h"
#include "vtkMath.h"
#include "vtkMatrix3x3.h"
#include "vtkRefractaImageRenderer.h"
#include "vtkRefractaLightingVolume.h"
#include "vtkRefractaViewPass.h"
#include "vtkTestErrorObserver.h"
#include "vtkUnsignedCharArray.h"

#include <gtest/gtest.h>

#include <limits>

#include <algorithm>
#include <cmath>
#include <memory>

namespace
{
// The cube's extinction: per channel, or grey (GreyExtinction: the packed medium, one gather).
const double ColouredSigma[3] = { 1.5, 3.0, 0.4 };
double Sigma[3] = { 1.5, 3.0, 0.4 };

// Makes the cube's extinction grey (2.2 in every channel) for its lifetime.
struct GreyExtinction
{
  GreyExtinction() { std::fill(Sigma, Sigma + 3, 2.2); }
  ~GreyExtinction() { std::copy(ColouredSigma, ColouredSigma + 3, Sigma); }
};
const double Eps[3] = { 0.3, 0.2, 0.1 };
const double S1[3] = { 0.8, 0.5, 0.3 };
const double Sms[3] = { 0.2, 0.4, 0.6 };
const double G = 0.6;
const double Background[3] = { 0.1, 0.25, 0.05 };

double HG(double cosTheta, double g)
{
  return (1 - g * g) / (4 * vtkMath::Pi() * std::pow(1 + g * g - 2 * g * cosTheta, 1.5));
}

struct Scene
{
  vtkSmartPointer<vtkImageData> Medium;
  vtkSmartPointer<vtkImageData> Lighting;
  double LightDirLocal[3];
};

// A 12 x 10 x 8 grid, spacing 0.125, with an optional rotation and a far origin.
Scene MakeScene(bool rotated)
{
  Scene scene;
  const double origin[3] = { rotated ? 1e5 : 0.0, rotated ? -2e5 : 0.0, rotated ? 3e4 : 0.0 };
  scene.Medium = refracta_test::MakeGrid(12, 10, 8, 0.125, origin);
  if (rotated)
  {
    // Rotation by 30 degrees about z, then 20 degrees about x.
    const double a = vtkMath::RadiansFromDegrees(30.0), b = vtkMath::RadiansFromDegrees(20.0);
    const double rz[9] = { std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a), 0, 0, 0, 1 };
    const double rx[9] = { 1, 0, 0, 0, std::cos(b), -std::sin(b), 0, std::sin(b), std::cos(b) };
    double m[9];
    vtkMatrix3x3::Multiply3x3(rx, rz, m);
    scene.Medium->SetDirectionMatrix(m);
  }
  refracta_test::AddConstant(scene.Medium, "Extinction", 3, Sigma[0], Sigma[1], Sigma[2]);
  refracta_test::AddConstant(scene.Medium, "Emission", 3, Eps[0], Eps[1], Eps[2]);
  refracta_test::AddConstant(scene.Medium, "Anisotropy", 1, G);
  scene.Lighting = vtkSmartPointer<vtkImageData>::New();
  scene.Lighting->CopyStructure(scene.Medium);
  refracta_test::AddConstant(
    scene.Lighting, vtkRefractaLightingVolume::RadianceName(), 3, S1[0], S1[1], S1[2]);
  double dir[3] = { 0.3, -0.8, 0.52 };
  vtkMath::Normalize(dir);
  refracta_test::AddConstant(
    scene.Lighting, vtkRefractaLightingVolume::RadianceDirectionName(), 3, dir[0], dir[1], dir[2]);
  refracta_test::AddConstant(
    scene.Lighting, vtkRefractaLightingVolume::MultipleScatteringName(), 3, Sms[0], Sms[1], Sms[2]);
  // The stored direction is in the grid-local frame (Physics.md).
  std::copy(dir, dir + 3, scene.LightDirLocal);
  return scene;
}

// Expected RGBA for every pixel, in double, from the same camera frame definition.
// `index`: the medium's uniform refractive index; sources count 1 / n^2 (basic radiance).
// `msFlux` (grid-local, length f <= 1): MultipleScatteringDirection, S_ms shaded with the phase
// function of anisotropy g f about it (nullptr: all isotropic).
// `lobes`: S1 in lobes, fraction k of S1 about direction k (grid-local), instead of all of it
// about the scene's direction.
struct Lobe
{
  double Fraction;
  double Direction[3];
};
std::vector<double> Expected(const Scene& scene, vtkCamera* camera, int w, int h,
  double index = 1.0, const double* msFlux = nullptr, const std::vector<Lobe>& lobes = {})
{
  vtkRefractaViewPass::RayFrame f;
  EXPECT_TRUE(vtkRefractaViewPass::ComputeRayFrame(camera, scene.Medium, nullptr, w, h, f));
  int dims[3];
  scene.Medium->GetDimensions(dims);
  const double s = 0.125;
  std::vector<double> result(size_t(w) * h * 4);
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      const double sx = 2.0 * (i + 0.5) / w - 1.0, sy = 2.0 * (j + 0.5) / h - 1.0;
      double o[3], d[3];
      for (int a = 0; a < 3; ++a)
      {
        o[a] = f.Parallel ? f.Eye[a] + sx * f.U[a] + sy * f.V[a] : f.Eye[a];
        d[a] = f.Parallel ? f.W[a] : f.W[a] + sx * f.U[a] + sy * f.V[a];
      }
      vtkMath::Normalize(d);
      double t0 = 0, t1 = 1e300;
      for (int a = 0; a < 3; ++a)
      {
        const double lo = -0.5 * s, hi = (dims[a] - 0.5) * s;
        const double ta = (lo - o[a]) / d[a], tb = (hi - o[a]) / d[a];
        t0 = std::max(t0, std::min(ta, tb));
        t1 = std::min(t1, std::max(ta, tb));
      }
      const double chord = std::max(t1 - t0, 0.0);
      double phase = HG(-vtkMath::Dot(scene.LightDirLocal, d), G);
      if (!lobes.empty())
      {
        phase = 0;
        for (const Lobe& lobe : lobes)
        {
          phase += lobe.Fraction * HG(-vtkMath::Dot(lobe.Direction, d), G);
        }
      }
      const double f = msFlux ? vtkMath::Norm(msFlux) : 0.0;
      const double msPhase =
        f > 0 ? HG(-vtkMath::Dot(msFlux, d) / f, G * f) : 1 / (4 * vtkMath::Pi());
      double meanT = 0;
      for (int c = 0; c < 3; ++c)
      {
        const double q = (Eps[c] + phase * S1[c] + msPhase * Sms[c]) / (index * index);
        const double tr = std::exp(-Sigma[c] * chord);
        result[(i + size_t(w) * j) * 4 + c] = q * (1 - tr) / Sigma[c] + tr * Background[c];
        meanT += tr / 3;
      }
      result[(i + size_t(w) * j) * 4 + 3] = 1 - meanT;
    }
  }
  return result;
}

// A camera looking at the box centre from an oblique direction (world coordinates), and a 48 x 36
// renderer of the scene through it with the test's background and no cutoff.
vtkSmartPointer<vtkRefractaImageRenderer> ObliqueRenderer(const Scene& scene, vtkCamera* camera)
{
  double centre[3];
  scene.Medium->TransformContinuousIndexToPhysicalPoint(5.5, 4.5, 3.5, centre);
  camera->SetFocalPoint(centre);
  camera->SetPosition(centre[0] + 1.7, centre[1] + 1.1, centre[2] + 2.3);
  camera->SetViewUp(0, 1, 0);
  camera->SetViewAngle(40);
  auto renderer = vtkSmartPointer<vtkRefractaImageRenderer>::New();
  renderer->SetInputData(scene.Medium);
  renderer->SetLightingData(scene.Lighting);
  renderer->SetCamera(camera);
  renderer->SetImageSize(48, 36);
  renderer->SetBackgroundColor(Background[0], Background[1], Background[2]);
  renderer->SetTransmittanceCutoff(0.0);
  return renderer;
}

void CheckImage(vtkImageData* image, const std::vector<double>& expected, const char* what)
{
  ASSERT_NE(image->GetPointData()->GetArray("HDR"), nullptr) << what;
  auto* hdr = vtkFloatArray::SafeDownCast(image->GetPointData()->GetArray("HDR"));
  ASSERT_NE(hdr, nullptr);
  ASSERT_EQ(hdr->GetNumberOfValues(), static_cast<vtkIdType>(expected.size()));
  double worst = 0;
  int inside = 0;
  for (size_t k = 0; k < expected.size(); ++k)
  {
    const double got = hdr->GetValue(static_cast<vtkIdType>(k));
    const double err = std::abs(got - expected[k]) / (2e-5 * std::abs(expected[k]) + 2e-6);
    worst = std::max(worst, err);
    if (k % 4 == 3 && expected[k] > 0.01)
    {
      ++inside;
    }
  }
  EXPECT_LE(worst, 1.0) << what << ": worst error in units of the tolerance";
  // The camera must see the box in a good part of the image, and miss it elsewhere.
  EXPECT_GT(inside, static_cast<int>(expected.size() / 4 / 10)) << what;
  EXPECT_LT(inside, static_cast<int>(expected.size() / 4)) << what;
}
}

// Step lengths 0.25, 1 and 3.7 voxels put the optical depth of a step on both sides of 1/2, where
// the kernel switches from the series of (1 - exp(-tau)) / tau to expm1; the grey cube runs the
// packed (sigma, emission) medium.
TEST(ViewPassAnalytic, HomogeneousCubeMatchesClosedForm)
{
  for (bool grey : { false, true })
  {
    std::unique_ptr<GreyExtinction> greyed(grey ? new GreyExtinction : nullptr);
    for (bool rotated : { false, true })
    {
      Scene scene = MakeScene(rotated);
      vtkNew<vtkCamera> camera;
      auto renderer = ObliqueRenderer(scene, camera);
      for (double step : { 1.0, 3.7, 0.25 })
      {
        renderer->SetStepSize(step);
        renderer->Update();
        CheckImage(renderer->GetOutput(), Expected(scene, camera, 48, 36),
          rotated ? "rotated perspective" : "perspective");
        EXPECT_EQ(renderer->GetViewPass()->GetMediumIsPacked(), grey);
        EXPECT_FALSE(renderer->GetViewPass()->GetLastCurved());
        EXPECT_GT(renderer->GetOutput()->GetFieldData()->GetArray("TotalSteps")->GetTuple1(0), 0);
      }
      camera->ParallelProjectionOn();
      camera->SetParallelScale(0.9);
      renderer->SetStepSize(1.0);
      renderer->Update();
      CheckImage(renderer->GetOutput(), Expected(scene, camera, 48, 36),
        rotated ? "rotated parallel" : "parallel");
    }
  }
}

// MultipleScatteringDirection (F / phi_ms, length f = 0.6 here): the view pass shades S_ms with
// the phase function of anisotropy g f about it, on the plain and the rotated, far-off grid, with
// a perspective and a parallel camera. (An isotropic S_ms, f = 0, is the cube above.)
TEST(ViewPassAnalytic, MultipleScatteringWithAFluxMatchesTheClosedForm)
{
  double flux[3] = { -0.5, 0.2, 0.7 };
  vtkMath::Normalize(flux);
  for (double& x : flux)
  {
    x *= 0.6;
  }
  for (bool rotated : { false, true })
  {
    Scene scene = MakeScene(rotated);
    refracta_test::AddConstant(scene.Lighting,
      vtkRefractaLightingVolume::MultipleScatteringDirectionName(), 3, flux[0], flux[1], flux[2]);
    vtkNew<vtkCamera> camera;
    auto renderer = ObliqueRenderer(scene, camera);
    renderer->Update();
    CheckImage(renderer->GetOutput(), Expected(scene, camera, 48, 36, 1.0, flux),
      rotated ? "rotated perspective, S_ms with a flux" : "perspective, S_ms with a flux");
    camera->ParallelProjectionOn();
    camera->SetParallelScale(0.9);
    renderer->Update();
    CheckImage(renderer->GetOutput(), Expected(scene, camera, 48, 36, 1.0, flux),
      rotated ? "rotated parallel, S_ms with a flux" : "parallel, S_ms with a flux");
  }
}

// S1 in two lobes (vtkRefractaLightingVolume::RadianceLobeName), 70% of it along one direction and
// 30% along a nearly opposite one: each shaded about its own direction (Radiance, their sum, and
// RadianceDirection, their mean, are then not read for the shading).
TEST(ViewPassAnalytic, RadianceLobesMatchTheClosedForm)
{
  std::vector<Lobe> lobes = { { 0.7, { 0.3, -0.8, 0.52 } }, { 0.3, { -0.4, 0.7, -0.3 } } };
  for (Lobe& lobe : lobes)
  {
    vtkMath::Normalize(lobe.Direction);
  }
  for (bool rotated : { false, true })
  {
    Scene scene = MakeScene(rotated);
    for (int k = 0; k < 2; ++k)
    {
      const double f = lobes[k].Fraction;
      const double* d = lobes[k].Direction;
      refracta_test::AddConstant(scene.Lighting, vtkRefractaLightingVolume::RadianceLobeName(k), 3,
        f * S1[0], f * S1[1], f * S1[2]);
      refracta_test::AddConstant(scene.Lighting,
        vtkRefractaLightingVolume::RadianceLobeDirectionName(k), 3, d[0], d[1], d[2]);
    }
    vtkNew<vtkCamera> camera;
    auto renderer = ObliqueRenderer(scene, camera);
    renderer->Update();
    CheckImage(renderer->GetOutput(), Expected(scene, camera, 48, 36, 1.0, nullptr, lobes),
      rotated ? "rotated perspective, S1 in lobes" : "perspective, S1 in lobes");
  }
}

// The volume caustic (vtkRefractaLightingVolume::VolumeCaustic*Name()) with every voxel bricked
// (c = 3), its fine voxels holding S1 and its direction and Radiance holding 0: the same light
// as the cube above, so the same closed form, on the plain and the rotated, far-off grid.
TEST(ViewPassAnalytic, VolumeCausticBricksEverywhereMatchTheClosedForm)
{
  const int c = 3;
  for (bool rotated : { false, true })
  {
    Scene scene = MakeScene(rotated);
    vtkPointData* pd = scene.Lighting->GetPointData();
    const vtkIdType voxels = scene.Lighting->GetNumberOfPoints();
    vtkNew<vtkIntArray> bricks;
    bricks->SetName(vtkRefractaLightingVolume::VolumeCausticBricksName());
    bricks->SetNumberOfTuples(voxels);
    vtkNew<vtkFloatArray> fine, direction;
    fine->SetName(vtkRefractaLightingVolume::VolumeCausticRadianceName());
    direction->SetName(vtkRefractaLightingVolume::VolumeCausticRadianceDirectionName());
    for (vtkFloatArray* a : { fine.Get(), direction.Get() })
    {
      a->SetNumberOfComponents(3);
      a->SetNumberOfTuples(voxels * c * c * c);
    }
    for (vtkIdType v = 0; v < voxels; ++v)
    {
      bricks->SetValue(v, static_cast<int>(voxels - 1 - v)); // any order of bricks
    }
    for (int k = 0; k < 3; ++k)
    {
      fine->FillComponent(k, S1[k]);
      direction->FillComponent(k, scene.LightDirLocal[k]);
    }
    pd->GetArray(vtkRefractaLightingVolume::RadianceName())->Fill(0.0);
    scene.Lighting->GetFieldData()->AddArray(bricks);
    scene.Lighting->GetFieldData()->AddArray(fine);
    scene.Lighting->GetFieldData()->AddArray(direction);
    vtkNew<vtkCamera> camera;
    auto renderer = ObliqueRenderer(scene, camera);
    renderer->Update();
    EXPECT_EQ(renderer->GetViewPass()->GetLightingVolumeCausticSubdivision(), c);
    CheckImage(renderer->GetOutput(), Expected(scene, camera, 48, 36),
      rotated ? "volume caustic, rotated" : "volume caustic");
  }
}

// Sources are physical radiance per length and the camera sits in n = 1, so a source inside an
// index n counts 1 / n^2 (the basic radiance L / n^2 is what a ray conserves). Checked with a
// uniform n = 1.5 (a constant factor) and with an index that varies by 2e-6 (so that it is
// sampled per step) but has a zero gradient: AUTO then traces straight rays (nothing bends them).
TEST(ViewPassAnalytic, SourcesCountOneOverIndexSquared)
{
  for (bool varying : { false, true })
  {
    Scene scene = MakeScene(false);
    refracta_test::AddConstant(scene.Medium, "RefractiveIndex", 1, 1.5);
    if (varying)
    {
      scene.Medium->GetPointData()->GetArray("RefractiveIndex")->SetTuple1(0, 1.5 + 2e-6);
      refracta_test::AddConstant(scene.Medium, "RefractiveIndexGradient", 3, 0, 0, 0);
    }
    vtkNew<vtkCamera> camera;
    auto renderer = ObliqueRenderer(scene, camera);
    renderer->Update();
    EXPECT_FALSE(renderer->GetViewPass()->GetLastCurved());
    EXPECT_EQ(renderer->GetViewPass()->GetMediumIsRefractive(), varying);
    CheckImage(renderer->GetOutput(), Expected(scene, camera, 48, 36, 1.5),
      varying ? "varying index" : "uniform index");
  }
}

TEST(ViewPassAnalytic, StepsScaleWithStepSize)
{
  Scene scene = MakeScene(false);
  vtkNew<vtkCamera> camera;
  camera->SetFocalPoint(0.7, 0.6, 0.45);
  camera->SetPosition(0.7, 0.6, 5);
  vtkNew<vtkRefractaImageRenderer> renderer;
  renderer->SetInputData(scene.Medium);
  renderer->SetCamera(camera);
  renderer->SetImageSize(32, 32);
  renderer->SetTransmittanceCutoff(0.0);
  renderer->SetStepSize(1.0);
  renderer->Update();
  const double steps1 = renderer->GetViewPass()->GetLastTotalSteps();
  renderer->SetStepSize(0.5);
  renderer->Update();
  const double steps05 = renderer->GetViewPass()->GetLastTotalSteps();
  // Halving the step roughly doubles the steps (each ray's last step is partial).
  EXPECT_NEAR(steps05 / steps1, 2.0, 0.15);
  // The lighting volume was optional: emission only (no 'Radiance' contribution).
  auto* hdr = vtkFloatArray::SafeDownCast(renderer->GetOutput()->GetPointData()->GetArray("HDR"));
  const float* centre = hdr->GetPointer(4 * (16 + 32 * 16));
  const double chord = 1.0; // 8 voxels of 0.125 along z
  EXPECT_NEAR(centre[0], Eps[0] / Sigma[0] * (1 - std::exp(-Sigma[0] * chord)), 2e-5);
}

TEST(ViewPassAnalytic, ToneMappingOperators)
{
  const float hdr[8] = { 0.0f, 0.5f, 2.0f, 1.0f, 0.0031308f, 1.0f, 100.0f, 1.0f };
  vtkNew<vtkUnsignedCharArray> rgb;
  vtkRefractaImageRenderer::ToneMap(hdr, 2, vtkRefractaImageRenderer::CLAMP, 1.0, rgb);
  EXPECT_EQ(rgb->GetValue(0), 0);
  EXPECT_EQ(rgb->GetValue(1), 188); // sRGB(0.5) = 0.7354 -> 187.5 -> 188
  EXPECT_EQ(rgb->GetValue(2), 255);
  EXPECT_EQ(rgb->GetValue(3), 10); // 12.92 * 0.0031308 * 255 = 10.3
  vtkRefractaImageRenderer::ToneMap(hdr, 2, vtkRefractaImageRenderer::REINHARD, 2.0, rgb);
  EXPECT_EQ(rgb->GetValue(1), 188); // 2 * 0.5 -> 1 / (1 + 1) = 0.5
  vtkRefractaImageRenderer::ToneMap(hdr, 2, vtkRefractaImageRenderer::EXPONENTIAL, 1.0, rgb);
  EXPECT_EQ(rgb->GetValue(5), 255); // 1 - exp(-100)
}

TEST(ViewPassAnalytic, BadInputsAreReported)
{
  Scene scene = MakeScene(false);
  vtkNew<vtkCamera> camera;
  camera->SetPosition(0.7, 0.6, 5);
  camera->SetFocalPoint(0.7, 0.6, 0.45);
  vtkNew<vtkTest::ErrorObserver> errors;
  vtkNew<vtkRefractaImageRenderer> renderer;
  renderer->AddObserver(vtkCommand::ErrorEvent, errors);
  renderer->GetViewPass()->AddObserver(vtkCommand::ErrorEvent, errors);
  renderer->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, errors);
  renderer->SetInputData(scene.Medium);
  renderer->SetImageSize(8, 8);

  // No camera.
  renderer->Update();
  EXPECT_TRUE(errors->GetError());
  EXPECT_NE(errors->GetErrorMessage().find("No camera"), std::string::npos);
  EXPECT_EQ(renderer->GetOutput()->GetNumberOfPoints(), 0);
  errors->Clear();

  // Invalid medium: negative extinction.
  renderer->SetCamera(camera);
  vtkNew<vtkImageData> bad;
  bad->DeepCopy(scene.Medium);
  vtkFloatArray::SafeDownCast(bad->GetPointData()->GetArray("Extinction"))->SetValue(5, -1.0f);
  renderer->SetInputData(bad);
  renderer->Update();
  EXPECT_NE(errors->GetErrorMessage().find("Extinction"), std::string::npos);
  EXPECT_EQ(renderer->GetOutput()->GetNumberOfPoints(), 0);
  errors->Clear();

  // Lighting volume on another grid.
  renderer->SetInputData(scene.Medium);
  vtkNew<vtkImageData> other;
  other->SetDimensions(3, 3, 3);
  refracta_test::AddConstant(other, vtkRefractaLightingVolume::RadianceName(), 3, 1, 1, 1);
  refracta_test::AddConstant(other, vtkRefractaLightingVolume::RadianceDirectionName(), 3, 0, 0, 1);
  renderer->SetLightingData(other);
  renderer->Update();
  EXPECT_NE(errors->GetErrorMessage().find("medium's grid"), std::string::npos);
  EXPECT_EQ(renderer->GetOutput()->GetNumberOfPoints(), 0);
  errors->Clear();

  // Radiance without its direction; NaN in the lighting volume.
  vtkNew<vtkImageData> noDir;
  noDir->CopyStructure(scene.Medium);
  refracta_test::AddConstant(noDir, vtkRefractaLightingVolume::RadianceName(), 3, 1, 1, 1);
  renderer->SetLightingData(noDir);
  renderer->Update();
  EXPECT_NE(errors->GetErrorMessage().find(vtkRefractaLightingVolume::RadianceDirectionName()),
    std::string::npos);
  errors->Clear();
  refracta_test::AddConstant(noDir, vtkRefractaLightingVolume::RadianceDirectionName(), 3, 0, 0, 1)
    ->SetValue(7, std::nanf(""));
  renderer->Update();
  EXPECT_NE(errors->GetErrorMessage().find("invalid value"), std::string::npos);
  errors->Clear();

  // A lobe's S1 negative: an error naming it.
  vtkNew<vtkImageData> badLobe;
  badLobe->DeepCopy(scene.Lighting);
  for (int k = 0; k < 2; ++k)
  {
    refracta_test::AddConstant(
      badLobe, vtkRefractaLightingVolume::RadianceLobeName(k), 3, k == 1 ? -1.0 : 0.5, 0.5, 0.5);
    refracta_test::AddConstant(
      badLobe, vtkRefractaLightingVolume::RadianceLobeDirectionName(k), 3, 0, 0, 1);
  }
  renderer->SetLightingData(badLobe);
  // The render fails with an error naming `array` and an empty output.
  auto expectRefused = [&](const char* array)
  {
    renderer->Update();
    EXPECT_NE(errors->GetErrorMessage().find(array), std::string::npos)
      << errors->GetErrorMessage();
    EXPECT_EQ(renderer->GetOutput()->GetNumberOfPoints(), 0);
    errors->Clear();
  };
  expectRefused(vtkRefractaLightingVolume::RadianceLobeName(1));
  // An incomplete set: lobe 2's S1 without its direction would drop out of the image.
  refracta_test::AddConstant(
    badLobe, vtkRefractaLightingVolume::RadianceLobeName(1), 3, 0.5, 0.5, 0.5);
  refracta_test::AddConstant(
    badLobe, vtkRefractaLightingVolume::RadianceLobeName(2), 3, 0.1, 0.1, 0.1);
  expectRefused(vtkRefractaLightingVolume::RadianceLobeName(2));

  // MultipleScatteringDirection with 2 components, then with a NaN: errors naming it.
  const char* msDirection = vtkRefractaLightingVolume::MultipleScatteringDirectionName();
  vtkNew<vtkImageData> badFlux;
  badFlux->CopyStructure(scene.Medium);
  refracta_test::AddConstant(
    badFlux, vtkRefractaLightingVolume::MultipleScatteringName(), 3, 1, 1, 1);
  refracta_test::AddConstant(badFlux, msDirection, 2, 0.1, 0.2);
  renderer->SetLightingData(badFlux);
  renderer->Update();
  EXPECT_NE(errors->GetErrorMessage().find(msDirection), std::string::npos)
    << errors->GetErrorMessage();
  EXPECT_EQ(renderer->GetOutput()->GetNumberOfPoints(), 0);
  errors->Clear();
  refracta_test::AddConstant(badFlux, msDirection, 3, 0.1, 0.2, 0.3)->SetValue(5, std::nanf(""));
  renderer->Update();
  EXPECT_NE(errors->GetErrorMessage().find("invalid value"), std::string::npos)
    << errors->GetErrorMessage();
  EXPECT_EQ(renderer->GetOutput()->GetNumberOfPoints(), 0);
  errors->Clear();

  // Degenerate camera; bad environment image.
  renderer->SetLightingData(nullptr);
  camera->SetFocalPoint(camera->GetPosition());
  renderer->Update();
  EXPECT_NE(errors->GetErrorMessage().find("The camera cannot render"), std::string::npos);
  errors->Clear();
  camera->SetFocalPoint(0.7, 0.6, 0.45);
  vtkNew<vtkImageData> env;
  env->SetDimensions(4, 4, 2);
  refracta_test::AddConstant(env, "colour", 3, 1, 1, 1);
  env->GetPointData()->SetActiveScalars("colour");
  renderer->SetEnvironmentMap(env);
  renderer->Update();
  EXPECT_NE(errors->GetErrorMessage().find("environment map"), std::string::npos);
  EXPECT_EQ(renderer->GetOutput()->GetNumberOfPoints(), 0);
  errors->Clear();
  // A NaN, an infinite and a negative texel: refused with the texel named (they used to read as
  // black without a word).
  env->SetDimensions(4, 4, 1);
  for (float bad : { std::nanf(""), std::numeric_limits<float>::infinity(), -1.0f })
  {
    refracta_test::AddConstant(env, "colour", 3, 1, 1, 1)->SetComponent(5, 1, bad);
    env->GetPointData()->SetActiveScalars("colour");
    renderer->SetEnvironmentMap(env);
    renderer->Update();
    EXPECT_NE(errors->GetErrorMessage().find("environment map's texel 5 (channel 1)"),
      std::string::npos)
      << errors->GetErrorMessage();
    EXPECT_EQ(renderer->GetOutput()->GetNumberOfPoints(), 0);
    errors->Clear();
  }

  // And it recovers once the input is fixed.
  renderer->SetEnvironmentMap(nullptr);
  renderer->Update();
  EXPECT_FALSE(errors->GetError());
  EXPECT_EQ(renderer->GetOutput()->GetNumberOfPoints(), 64);
}

// The view pass keeps what SetMedium() and SetLighting() were given: a caller may hand it
// temporaries and let them go (here they are released before Render(), which reads the medium's
// grid), and the image is the one rendered with the inputs still alive.
TEST(ViewPassAnalytic, InputsMayBeReleasedAfterUpload)
{
  vtkNew<vtkCamera> camera;
  camera->SetPosition(0.7, 0.6, 5);
  camera->SetFocalPoint(0.7, 0.6, 0.45);
  std::vector<float> kept, released;
  {
    Scene scene = MakeScene(true);
    vtkNew<vtkRefractaViewPass> pass;
    ASSERT_TRUE(pass->SetMedium(scene.Medium));
    ASSERT_TRUE(pass->SetLighting(scene.Lighting));
    ASSERT_TRUE(pass->Render(camera, 16, 12, nullptr, nullptr, kept));
  }
  vtkNew<vtkRefractaViewPass> pass;
  {
    Scene scene = MakeScene(true);
    ASSERT_TRUE(pass->SetMedium(scene.Medium));
  }
  {
    Scene scene = MakeScene(true); // the same grid, a new object: still matches the medium
    ASSERT_TRUE(pass->SetLighting(scene.Lighting));
  }
  ASSERT_TRUE(pass->Render(camera, 16, 12, nullptr, nullptr, released));
  ASSERT_EQ(kept.size(), released.size());
  EXPECT_EQ(kept, released);
}
