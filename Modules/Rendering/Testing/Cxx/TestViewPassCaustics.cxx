// The caustic atlas in the view pass (vtkRefractaViewPass::CausticPhotonsPerFineTexel,
// Kernels/view_surfaces.cl, Documentation/Physics.md "Caustic atlas").
//
// - A plane under uniform light (E = 1 per atlas texel) whose lighting volume also holds caustic
//   light in three atlas texels, c = 2 finer, with a pattern that differs from fine texel to
//   fine texel (each atlas texel's SurfaceIrradiance includes the mean of its fine texels, as the
//   photon pass writes it). Seen with the NEAREST_TEXEL filter, so every pixel has an exact value:
//   in texel A (exactly CausticPhotonsPerFineTexel c^2 photons) and C (more) each pixel shows
//   (1 + its fine texel's caustic) rho / pi, the pattern resolved; in texel B (one photon fewer)
//   the atlas value (1 + mean) rho / pi; everywhere else rho / pi. Pixels within 1e-4 (in u, v)
//   of a fine texel's edge are not judged (their centre ray may land on either side).
// - With the threshold raised above every count, the image is bit-identical to the render of a
//   lighting volume without the caustic arrays (LINEAR_TEXEL), and so is the sum of light shown.
// - Bad caustic arrays are errors naming the array and what is valid.
#include "SurfaceTestScene.h"

#include "vtkCamera.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkMath.h"
#include "vtkRefractaViewPass.h"
#include "vtkTestErrorObserver.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <vector>

namespace
{
constexpr int Sides = vtkRefractaLightingVolume::NUMBER_OF_SURFACE_SIDES;
const int C = 2;                 // the caustic atlas's subdivision in these tests
const double PhotonsPerFine = 8; // the view pass's threshold set by the tests

// The fine texels' caustic irradiance: 2 + (local fine index mod 5), in the hot atlas texels.
double FinePattern(int localFine)
{
  return 2.0 + localFine % 5;
}

struct CausticScene
{
  vtkNew<vtkRefractaSurfaceSet> Set;
  vtkSmartPointer<vtkImageData> Medium;
  vtkSmartPointer<vtkImageData> Lighting;
  // Hot atlas texels (absolute index) -> caustic photons counted there.
  std::map<int, double> Hot;
  int First = 0, N = 0; // the first triangle's texels
  double Focus[3] = { 0, 0, 0 };

  CausticScene()
  {
    const double o0[3] = { -1, -1, 0 }, p1[3] = { 1, -1, 0 }, p2[3] = { -1, 1, 0 };
    this->Set->SetTexelSize(0.25);
    this->Set->AddSurface(refracta_test::Plane(o0, p1, p2), refracta_test::Material(0.6, 0.6, 0.6));
    const double origin[3] = { -0.2, -0.2, 0.55 };
    this->Medium = refracta_test::ClearMedium(5, 0.1, origin);
    this->Lighting = refracta_test::Lighting(
      this->Medium, this->Set, [](const double*, double e[3]) { e[0] = e[1] = e[2] = 1.0; });
    const std::vector<int>& info = this->Set->GetTriangleInfo();
    this->First = info[0]; // triangle 0 in BVH order: (first texel, subdivision, ...)
    this->N = info[1];
    // Three texels of the first triangle near its middle: A at the threshold, B one photon
    // short, C well above.
    const double needed = PhotonsPerFine * C * C;
    this->Hot[this->First + this->Texel(this->N / 3, this->N / 3)] = needed;
    this->Hot[this->First + this->Texel(this->N / 3 + 1, this->N / 3)] = needed - 1;
    this->Hot[this->First + this->Texel(this->N / 3, this->N / 3 + 1)] = 10 * needed;
    this->AddCausticArrays();
    // The camera looks at texel A's corner shared with B and C.
    const std::vector<double>& tri = this->Set->GetBVH()->GetTriangles();
    const double* frameOrigin = this->Set->GetBVH()->GetFrameOrigin();
    const double u = double(this->N / 3 + 1) / this->N, v = double(this->N / 3 + 1) / this->N;
    for (int c = 0; c < 3; ++c)
    {
      this->Focus[c] = frameOrigin[c] + (1 - u - v) * tri[c] + u * tri[3 + c] + v * tri[6 + c];
    }
  }

  // Upright texel (i, j) of subdivision N: refracta_texel_index's layout.
  int Texel(int i, int j) const { return j * (2 * this->N - j) + 2 * i; }

  // The fine texels (first triangle, local index in subdivision N C) inside atlas texel `local`.
  std::vector<int> FineTexelsOf(int local) const
  {
    std::vector<int> fine;
    for (int f = 0; f < this->N * C * this->N * C; ++f)
    {
      double corners[6];
      vtkRefractaSurfaceSet::GetTexelCorners(f, this->N * C, corners);
      const float u = static_cast<float>((corners[0] + corners[2] + corners[4]) / 3);
      const float v = static_cast<float>((corners[1] + corners[3] + corners[5]) / 3);
      if (vtkRefractaSurfaceSet::TexelIndex(u, v, this->N) == local)
      {
        fine.push_back(f);
      }
    }
    return fine;
  }

  void AddCausticArrays()
  {
    const vtkIdType texels = this->Set->GetNumberOfTexels();
    vtkNew<vtkFloatArray> caustic;
    caustic->SetName(vtkRefractaLightingVolume::SurfaceCausticIrradianceName());
    caustic->SetNumberOfComponents(3);
    caustic->SetNumberOfTuples(texels * C * C);
    caustic->Fill(0.0);
    vtkNew<vtkIdTypeArray> photons;
    photons->SetName(vtkRefractaLightingVolume::SurfaceCausticPhotonsName());
    photons->SetNumberOfTuples(texels);
    photons->Fill(0);
    auto* e = vtkFloatArray::SafeDownCast(
      this->Lighting->GetFieldData()->GetArray(vtkRefractaLightingVolume::SurfaceIrradianceName()));
    for (const auto& hot : this->Hot)
    {
      double sum = 0;
      const std::vector<int> fine = this->FineTexelsOf(hot.first - this->First);
      EXPECT_EQ(fine.size(), static_cast<size_t>(C * C));
      for (int f : fine)
      {
        const double value = FinePattern(f);
        const double rgb[3] = { value, value, value };
        caustic->SetTuple(C * C * this->First + f, rgb);
        sum += value;
      }
      // The atlas keeps all the light: its texel gains the fine texels' mean.
      const double total = 1.0 + sum / (C * C);
      const double rgb[3] = { total, total, total };
      e->SetTuple(hot.first, rgb);
      photons->SetValue(hot.first, static_cast<vtkIdType>(hot.second));
    }
    this->Lighting->GetFieldData()->AddArray(caustic);
    this->Lighting->GetFieldData()->AddArray(photons);
  }

  enum Kind
  {
    Plain,
    Fine,
    AtlasMean
  };

  // The irradiance the NEAREST_TEXEL view should show at barycentric (u, v) of triangle 0, and
  // what it comes from; -1 where (u, v) is within eps of a fine texel's edge.
  double Expected(double u, double v, Kind& kind) const
  {
    const float eps = 1e-4f;
    const int fine = vtkRefractaSurfaceSet::TexelIndex(float(u), float(v), this->N * C);
    for (float du : { -eps, eps })
    {
      for (float dv : { -eps, eps })
      {
        if (vtkRefractaSurfaceSet::TexelIndex(float(u) + du, float(v) + dv, this->N * C) != fine)
        {
          return -1;
        }
      }
    }
    const int coarse = this->First + vtkRefractaSurfaceSet::TexelIndex(float(u), float(v), this->N);
    const auto hot = this->Hot.find(coarse);
    kind = Plain;
    if (hot == this->Hot.end())
    {
      return 1.0;
    }
    kind = Fine;
    if (hot->second >= PhotonsPerFine * C * C)
    {
      return 1.0 + FinePattern(fine);
    }
    kind = AtlasMean;
    double sum = 0;
    for (int f : this->FineTexelsOf(coarse - this->First))
    {
      sum += FinePattern(f);
    }
    return 1.0 + sum / (C * C);
  }
};

void SetCamera(vtkCamera* camera, const double focus[3])
{
  camera->SetPosition(focus[0], focus[1], 1.0);
  camera->SetFocalPoint(focus[0], focus[1], 0.0);
  camera->SetViewUp(0, 1, 0);
  camera->SetViewAngle(30);
}
}

//------------------------------------------------------------------------------
TEST(ViewPassCaustics, FineTexelsShowTheCausticWhereEnoughPhotonsLanded)
{
  CausticScene scene;
  vtkNew<vtkRefractaViewPass> pass;
  ASSERT_TRUE(pass->SetMedium(scene.Medium));
  ASSERT_TRUE(pass->SetLighting(scene.Lighting));
  pass->SetSurfaces(scene.Set);
  pass->SetSurfaceFilter(vtkRefractaViewPass::NEAREST_TEXEL);
  pass->SetCausticPhotonsPerFineTexel(PhotonsPerFine);
  vtkNew<vtkCamera> camera;
  SetCamera(camera, scene.Focus);
  const int w = 160, h = 160;
  std::vector<float> hdr;
  ASSERT_TRUE(pass->Render(camera, w, h, nullptr, nullptr, hdr));
  // The hand-made arrays give one value for both sides: each texel counts twice.
  EXPECT_EQ(pass->GetLastNumberOfFineCausticTexels(), 2 * Sides) << "texels A and C, not B";
  vtkRefractaViewPass::RayFrame frame;
  ASSERT_TRUE(vtkRefractaViewPass::ComputeRayFrame(camera, scene.Medium, nullptr, w, h, frame));

  // Triangle 0's corners (BVH order, in the BVH's frame).
  const std::vector<double>& tri = scene.Set->GetBVH()->GetTriangles();
  const double* frameOrigin = scene.Set->GetBVH()->GetFrameOrigin();
  double a[3], e1[3], e2[3];
  for (int c = 0; c < 3; ++c)
  {
    a[c] = frameOrigin[c] + tri[c];
    e1[c] = tri[3 + c] - tri[c];
    e2[c] = tri[6 + c] - tri[c];
  }
  const double rho = 0.6 / vtkMath::Pi();
  int judged = 0, resolved = 0, atlas = 0;
  double worst = 0;
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      double o[3], d[3];
      refracta_test::PixelRay(frame, scene.Medium, i, j, w, h, o, d);
      const double t = -o[2] / d[2];
      // (u, v) of the hit in the first triangle (in the plane z = 0: a 2 x 2 solve).
      const double px = o[0] + t * d[0] - a[0], py = o[1] + t * d[1] - a[1];
      const double det = e1[0] * e2[1] - e1[1] * e2[0];
      const double u = (px * e2[1] - py * e2[0]) / det, v = (e1[0] * py - e1[1] * px) / det;
      if (u < 1e-3 || v < 1e-3 || u + v > 1 - 1e-3)
      {
        continue;
      }
      CausticScene::Kind kind;
      const double want = scene.Expected(u, v, kind);
      if (want < 0)
      {
        continue;
      }
      ++judged;
      resolved += kind == CausticScene::Fine;
      atlas += kind == CausticScene::AtlasMean;
      const double got = hdr[4 * (i + static_cast<size_t>(w) * j)] / rho;
      worst = std::max(worst, std::abs(got - want) / want);
      EXPECT_NEAR(got, want, 1e-5 * want)
        << "pixel " << i << "," << j << " (u " << u << ", v " << v << ")";
    }
  }
  std::cout << "caustic atlas in the view pass: " << judged << " pixels judged, " << resolved
            << " showing fine texels, " << atlas << " the atlas's caustic mean; worst relative "
            << worst << "\n";
  EXPECT_GT(judged, 10000);
  EXPECT_GT(resolved, 1500);
  EXPECT_GT(atlas, 800);
}

//------------------------------------------------------------------------------
TEST(ViewPassCaustics, BelowTheThresholdTheImageIsTheAtlasAlone)
{
  CausticScene scene;
  vtkNew<vtkRefractaViewPass> pass;
  ASSERT_TRUE(pass->SetMedium(scene.Medium));
  pass->SetSurfaces(scene.Set);
  pass->SetCausticPhotonsPerFineTexel(1e9);
  vtkNew<vtkCamera> camera;
  SetCamera(camera, scene.Focus);
  std::vector<float> withArrays, without, resolved;
  ASSERT_TRUE(pass->SetLighting(scene.Lighting));
  ASSERT_TRUE(pass->Render(camera, 64, 64, nullptr, nullptr, withArrays));
  EXPECT_EQ(pass->GetLastNumberOfFineCausticTexels(), 0);
  // The threshold is read at each render: lowering it shows the fine texels.
  pass->SetCausticPhotonsPerFineTexel(PhotonsPerFine);
  ASSERT_TRUE(pass->Render(camera, 64, 64, nullptr, nullptr, resolved));
  EXPECT_NE(resolved, withArrays);
  EXPECT_EQ(pass->GetLastNumberOfFineCausticTexels(), 2 * Sides);
  auto plain = vtkSmartPointer<vtkImageData>::New();
  plain->ShallowCopy(scene.Lighting);
  vtkNew<vtkFieldData> fields;
  fields->AddArray(
    scene.Lighting->GetFieldData()->GetArray(vtkRefractaLightingVolume::SurfaceIrradianceName()));
  plain->SetFieldData(fields);
  ASSERT_TRUE(pass->SetLighting(plain));
  ASSERT_TRUE(pass->Render(camera, 64, 64, nullptr, nullptr, without));
  pass->SetCausticPhotonsPerFineTexel(1e9);
  ASSERT_TRUE(pass->SetLighting(scene.Lighting));
  ASSERT_TRUE(pass->Render(camera, 64, 64, nullptr, nullptr, withArrays));
  EXPECT_EQ(withArrays, without);
}

//------------------------------------------------------------------------------
TEST(ViewPassCaustics, BadCausticArraysAreErrorsNamingTheArray)
{
  vtkNew<vtkTest::ErrorObserver> errors;
  vtkNew<vtkRefractaViewPass> pass;
  pass->AddObserver(vtkCommand::ErrorEvent, errors);
  vtkNew<vtkCamera> camera;
  const double focus[3] = { 0, 0, 0 };
  SetCamera(camera, focus);
  std::vector<float> hdr;
  auto expectError =
    [&](const char* what, const std::function<void(CausticScene&)>& spoil, bool atRender)
  {
    CausticScene scene;
    spoil(scene);
    ASSERT_TRUE(pass->SetMedium(scene.Medium));
    pass->SetSurfaces(scene.Set);
    const bool set = pass->SetLighting(scene.Lighting);
    EXPECT_EQ(set, atRender) << what;
    if (set)
    {
      EXPECT_FALSE(pass->Render(camera, 16, 16, nullptr, nullptr, hdr)) << what;
    }
    EXPECT_NE(errors->GetErrorMessage().find(what), std::string::npos)
      << "wanted '" << what << "' in: " << errors->GetErrorMessage();
    errors->Clear();
  };
  vtkFieldData* (*fields)(CausticScene&) = [](CausticScene& s)
  { return s.Lighting->GetFieldData(); };
  // The caustic light without its photon counts.
  expectError(
    "SurfaceCausticPhotons",
    [&](CausticScene& s)
    { fields(s)->RemoveArray(vtkRefractaLightingVolume::SurfaceCausticPhotonsName()); },
    false);
  // A negative count and a NaN caustic value.
  expectError(
    "SurfaceCausticPhotons",
    [&](CausticScene& s)
    {
      fields(s)
        ->GetArray(vtkRefractaLightingVolume::SurfaceCausticPhotonsName())
        ->SetComponent(0, 0, -1);
    },
    false);
  expectError(
    "SurfaceCausticIrradiance",
    [&](CausticScene& s)
    {
      fields(s)
        ->GetArray(vtkRefractaLightingVolume::SurfaceCausticIrradianceName())
        ->SetComponent(5, 2, std::nan(""));
    },
    false);
  // Fine tuples that are not c^2 per texel; counts for fewer texels than the set has.
  expectError(
    "c^2",
    [&](CausticScene& s)
    {
      auto* a = fields(s)->GetArray(vtkRefractaLightingVolume::SurfaceCausticIrradianceName());
      a->SetNumberOfTuples(a->GetNumberOfTuples() - 1);
    },
    true);
  expectError(
    "SurfaceCausticPhotons",
    [&](CausticScene& s)
    {
      auto* a = fields(s)->GetArray(vtkRefractaLightingVolume::SurfaceCausticPhotonsName());
      a->SetNumberOfTuples(a->GetNumberOfTuples() - 1);
    },
    true);
}
