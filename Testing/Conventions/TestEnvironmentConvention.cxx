// One environment-map convention: the reference renderer (C++) and the view pass (OpenCL kernel)
// look a world direction up at the same (u, v), namely vtkRefractaEnvironmentMap's. A camera looks
// into a tiny empty medium in front of an environment whose texels encode their own texture
// coordinates (bilinear lookup of the ramp returns (u, v) itself); for every pixel, away from the
// seam and the poles, the decoded (u, v) of both renderers must match the C++ function applied to
// the pixel's world direction, and pick the same texel.
#include "vtkCamera.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkReferenceRenderer.h"
#include "vtkRefractaEnvironmentMap.h"
#include "vtkRefractaImageRenderer.h"
#include "vtkRefractaMedium.h"
#include "vtkSmartPointer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>

namespace
{
constexpr int EnvW = 64, EnvH = 32;
constexpr int Width = 48, Height = 36;
constexpr double ViewAngle = 100.0;

vtkSmartPointer<vtkImageData> CoordinateEnvironment()
{
  auto env = vtkSmartPointer<vtkImageData>::New();
  env->SetDimensions(EnvW, EnvH, 1);
  vtkNew<vtkFloatArray> c;
  c->SetName("uv");
  c->SetNumberOfComponents(3);
  c->SetNumberOfTuples(EnvW * EnvH);
  for (int j = 0; j < EnvH; ++j)
  {
    for (int i = 0; i < EnvW; ++i)
    {
      c->SetTuple3(i + EnvW * j, (i + 0.5) / EnvW, (j + 0.5) / EnvH, 0);
    }
  }
  env->GetPointData()->SetScalars(c);
  return env;
}

vtkSmartPointer<vtkImageData> EmptyMedium()
{
  auto medium = vtkSmartPointer<vtkImageData>::New();
  medium->SetDimensions(2, 2, 2);
  medium->SetSpacing(0.1, 0.1, 0.1);
  medium->SetOrigin(-0.05, -0.05, -0.05);
  vtkNew<vtkFloatArray> sigma;
  sigma->SetName(vtkRefractaMedium::ExtinctionName());
  sigma->SetNumberOfComponents(3);
  sigma->SetNumberOfTuples(8);
  for (int k = 0; k < 3; ++k)
  {
    sigma->FillComponent(k, 0.0);
  }
  medium->GetPointData()->AddArray(sigma);
  return medium;
}

// World direction through the centre of pixel (i, j) (vertical view angle, aspect W / H).
void PixelDirection(vtkCamera* camera, int i, int j, double d[3])
{
  double pos[3], fp[3], up[3], w[3], r[3], u[3];
  camera->GetPosition(pos);
  camera->GetFocalPoint(fp);
  camera->GetViewUp(up);
  vtkMath::Subtract(fp, pos, w);
  vtkMath::Normalize(w);
  vtkMath::Cross(w, up, r);
  vtkMath::Normalize(r);
  vtkMath::Cross(r, w, u);
  const double t = std::tan(vtkMath::RadiansFromDegrees(ViewAngle) / 2);
  const double sx = (2.0 * (i + 0.5) / Width - 1.0) * t * Width / Height;
  const double sy = (2.0 * (j + 0.5) / Height - 1.0) * t;
  for (int a = 0; a < 3; ++a)
  {
    d[a] = w[a] + sx * r[a] + sy * u[a];
  }
  vtkMath::Normalize(d);
}
} // namespace

TEST(EnvironmentConvention, ReferenceAndViewPassPickTheSameTexel)
{
  struct View
  {
    double Direction[3];
    double Up[3];
    double EnvUp[3];
    double EnvRight[3];
  };
  const View views[] = { { { 0, 0, -1 }, { 0, 1, 0 }, { 0, 1, 0 }, { 1, 0, 0 } },
    { { 1, 1, 0 }, { 0, 0, 1 }, { 0, 1, 0 }, { 1, 0, 0 } },
    { { -1, 0.2, 0.5 }, { 0, 1, 0 }, { 0, 1, 0 }, { 1, 0, 0 } },
    { { 0, 0.3, 1 }, { 0, 1, 0 }, { 0, 1, 0 }, { 1, 0, 0 } },
    { { 0.3, -1, 0.2 }, { 1, 0, 0 }, { 0, 1, 0 }, { 1, 0, 0 } },
    { { 1, 0.5, -0.5 }, { 0, 0, 1 }, { 0, 0, 1 }, { 0, 1, 0 } } };
  auto env = CoordinateEnvironment();
  auto medium = EmptyMedium();
  int compared = 0;
  double worstView = 0, worstReference = 0;
  for (const View& view : views)
  {
    vtkNew<vtkCamera> camera;
    camera->SetFocalPoint(0, 0, 0);
    double dir[3] = { view.Direction[0], view.Direction[1], view.Direction[2] };
    vtkMath::Normalize(dir);
    camera->SetPosition(-0.5 * dir[0], -0.5 * dir[1], -0.5 * dir[2]);
    camera->SetViewUp(view.Up[0], view.Up[1], view.Up[2]);
    camera->SetViewAngle(ViewAngle);

    vtkNew<vtkRefractaImageRenderer> pass;
    pass->SetInputData(medium);
    pass->SetCamera(camera);
    pass->SetImageSize(Width, Height);
    pass->SetEnvironmentMap(env);
    pass->SetEnvironmentUp(view.EnvUp[0], view.EnvUp[1], view.EnvUp[2]);
    pass->SetEnvironmentRight(view.EnvRight[0], view.EnvRight[1], view.EnvRight[2]);
    pass->Update();
    vtkDataArray* hdrPass = pass->GetOutput()->GetPointData()->GetArray("HDR");

    vtkNew<vtkReferenceRenderer> reference;
    reference->SetInputData(medium);
    reference->SetCamera(camera);
    reference->SetImageSize(Width, Height);
    reference->SetSamplesPerPixel(1);
    reference->SetEnvironmentMap(env);
    reference->SetEnvironmentUp(view.EnvUp[0], view.EnvUp[1], view.EnvUp[2]);
    reference->SetEnvironmentRight(view.EnvRight[0], view.EnvRight[1], view.EnvRight[2]);
    reference->Update();
    vtkDataArray* hdrReference = reference->GetOutput()->GetPointData()->GetArray("HDR");
    ASSERT_NE(hdrPass, nullptr);
    ASSERT_NE(hdrReference, nullptr);

    for (int j = 0; j < Height; ++j)
    {
      for (int i = 0; i < Width; ++i)
      {
        double d[3], uv[2];
        PixelDirection(camera, i, j, d);
        vtkRefractaEnvironmentMap::DirectionToTexture(d, view.EnvUp, view.EnvRight, uv);
        // Away from the seam (the ramp jumps there) and the clamped polar half texels.
        if (uv[0] < 1.5 / EnvW || uv[0] > 1 - 1.5 / EnvW || uv[1] < 1.0 / EnvH ||
          uv[1] > 1 - 1.0 / EnvH)
        {
          continue;
        }
        const vtkIdType p = i + static_cast<vtkIdType>(Width) * j;
        const int want = vtkRefractaEnvironmentMap::NearestTexel(EnvW, EnvH, uv[0], uv[1]);
        for (int which = 0; which < 2; ++which)
        {
          vtkDataArray* hdr = which == 0 ? hdrPass : hdrReference;
          const double got[2] = { hdr->GetComponent(p, 0), hdr->GetComponent(p, 1) };
          const double err = std::max(std::abs(got[0] - uv[0]), std::abs(got[1] - uv[1]));
          (which == 0 ? worstView : worstReference) =
            std::max(which == 0 ? worstView : worstReference, err);
          EXPECT_LT(err, which == 0 ? 2e-3 : 1e-6)
            << (which == 0 ? "view pass" : "reference") << " pixel " << i << "," << j;
          // Same texel, unless the direction lies within float rounding of a texel border.
          const double bu = uv[0] * EnvW - std::floor(uv[0] * EnvW);
          const double bv = uv[1] * EnvH - std::floor(uv[1] * EnvH);
          if (std::min(bu, 1 - bu) > 0.05 && std::min(bv, 1 - bv) > 0.05)
          {
            EXPECT_EQ(vtkRefractaEnvironmentMap::NearestTexel(EnvW, EnvH, got[0], got[1]), want)
              << (which == 0 ? "view pass" : "reference") << " pixel " << i << "," << j;
          }
        }
        ++compared;
      }
    }
  }
  std::cout << compared << " pixels compared; worst |uv - C++| view pass " << worstView
            << ", reference " << worstReference << "\n";
  EXPECT_GT(compared, 6 * Width * Height / 2);
}

// The procedural checkerboard (vtkRefractaEnvironmentMap::MakeChecker): both renderers evaluate
// it per ray, so every pixel takes exactly the colour of the square its direction falls in (a
// square edge is sharp: the neighbouring pixels across it take the two colours, nothing between),
// and the texels the image carries for its other users are the pattern's exact area means.
TEST(EnvironmentConvention, ProceduralCheckerIsExactInBothRenderers)
{
  const int squares[2] = { 24, 12 };
  const double color1[3] = { 0.9, 0.85, 0.75 }, color2[3] = { 0.08, 0.12, 0.3 };
  auto env = vtkRefractaEnvironmentMap::MakeChecker(squares[0], squares[1], color1, color2);
  int got[2];
  double c1[3], c2[3];
  ASSERT_TRUE(vtkRefractaEnvironmentMap::GetChecker(env, got, c1, c2));
  EXPECT_EQ(got[0], squares[0]);
  EXPECT_EQ(got[1], squares[1]);
  // An even number of squares along u: every row of texels averages to the mean colour.
  vtkDataArray* texels = env->GetPointData()->GetScalars();
  double mean = 0;
  for (vtkIdType t = 0; t < texels->GetNumberOfTuples(); ++t)
  {
    mean += texels->GetComponent(t, 0) / texels->GetNumberOfTuples();
  }
  EXPECT_NEAR(mean, 0.5 * (color1[0] + color2[0]), 1e-6);
  // A texel across a square edge holds the blend of the two colours by area.
  auto coarse = vtkRefractaEnvironmentMap::MakeChecker(3, 1, color1, color2);
  int dims[3];
  coarse->GetDimensions(dims);
  ASSERT_EQ(dims[0], 64); // 3 squares over 64 texels: texel 21 straddles u = 1 / 3
  const double f = 1.0 - (64.0 / 3.0 - 21.0); // its share of square 1 (odd: colour 1)
  EXPECT_NEAR(coarse->GetPointData()->GetScalars()->GetComponent(21, 0),
    (1 - f) * color2[0] + f * color1[0], 1e-6);

  auto medium = EmptyMedium();
  vtkNew<vtkCamera> camera;
  camera->SetFocalPoint(0, 0, 0);
  camera->SetPosition(0.2, 0.1, 0.5);
  camera->SetViewUp(0, 1, 0);
  camera->SetViewAngle(ViewAngle);
  vtkNew<vtkRefractaImageRenderer> pass;
  pass->SetInputData(medium);
  pass->SetCamera(camera);
  pass->SetImageSize(Width, Height);
  pass->SetEnvironmentMap(env);
  pass->Update();
  vtkNew<vtkReferenceRenderer> reference;
  reference->SetInputData(medium);
  reference->SetCamera(camera);
  reference->SetImageSize(Width, Height);
  reference->SetSamplesPerPixel(1);
  reference->SetEnvironmentMap(env);
  reference->Update();
  vtkDataArray* hdr[2] = { pass->GetOutput()->GetPointData()->GetArray("HDR"),
    reference->GetOutput()->GetPointData()->GetArray("HDR") };
  ASSERT_NE(hdr[0], nullptr);
  ASSERT_NE(hdr[1], nullptr);
  const double up[3] = { 0, 1, 0 }, right[3] = { 1, 0, 0 };
  int judged = 0, edges = 0;
  for (int j = 0; j < Height; ++j)
  {
    for (int i = 0; i < Width; ++i)
    {
      double d[3], uv[2], want[3];
      PixelDirection(camera, i, j, d);
      vtkRefractaEnvironmentMap::DirectionToTexture(d, up, right, uv);
      // Not within float rounding of a square edge.
      const double fu = uv[0] * squares[0] - std::floor(uv[0] * squares[0]);
      const double fv = uv[1] * squares[1] - std::floor(uv[1] * squares[1]);
      if (std::min(fu, 1 - fu) < 1e-3 || std::min(fv, 1 - fv) < 1e-3)
      {
        continue;
      }
      vtkRefractaEnvironmentMap::EvaluateChecker(uv[0], uv[1], squares, color1, color2, want);
      const vtkIdType p = i + static_cast<vtkIdType>(Width) * j;
      for (int which = 0; which < 2; ++which)
      {
        for (int c = 0; c < 3; ++c)
        {
          EXPECT_NEAR(hdr[which]->GetComponent(p, c), want[c], 1e-5)
            << (which == 0 ? "view pass" : "reference") << " pixel " << i << "," << j;
        }
      }
      ++judged;
      // A pixel whose right neighbour lies in another square: the edge is one pixel wide.
      if (i + 1 < Width)
      {
        double dn[3], uvn[2];
        PixelDirection(camera, i + 1, j, dn);
        vtkRefractaEnvironmentMap::DirectionToTexture(dn, up, right, uvn);
        if (std::floor(uvn[0] * squares[0]) != std::floor(uv[0] * squares[0]))
        {
          ++edges;
        }
      }
    }
  }
  std::cout << judged << " pixels judged, " << edges << " of them next to a square edge\n";
  EXPECT_GT(judged, Width * Height * 9 / 10);
  EXPECT_GT(edges, 20);
}

namespace
{
// The share of texel [u0, u1] x [v0, v1] (in square units) covered by odd squares (colour 1):
// the overlap areas of the squares it touches, summed directly.
double OddShareOfTexel(double u0, double u1, double v0, double v1)
{
  double odd = 0;
  for (int a = static_cast<int>(std::floor(u0)); a < u1; ++a)
  {
    for (int b = static_cast<int>(std::floor(v0)); b < v1; ++b)
    {
      const double du = std::min(u1, a + 1.0) - std::max(u0, double(a));
      const double dv = std::min(v1, b + 1.0) - std::max(v0, double(b));
      odd += ((a + b) % 2) ? du * dv : 0.0;
    }
  }
  return odd / ((u1 - u0) * (v1 - v0));
}
}

// The checker image's texels are the exact area means of the pattern (each against the direct
// overlap sum above; texels sampled at their centres miss by up to half the colour difference),
// and, weighted by their solid angles, integrate to the pattern's exact mean radiance over the
// sphere (what the photon pass emits from the background), computed band by band. Odd square
// counts: texels straddle u edges; with 301 bands the image holds 2048 rows, so texels straddle
// v edges too.
TEST(EnvironmentConvention, CheckerTexelsAreExactAreaMeans)
{
  const double color1[3] = { 1.0, 0.5, 0.25 }, color2[3] = { 0.0, 0.125, 2.0 };
  const int cases[3][2] = { { 3, 5 }, { 7, 3 }, { 5, 301 } };
  for (const auto& squares : cases)
  {
    // Band k (latitudes from k/nv to (k+1)/nv of the way up) has solid-angle share
    // (sin lat1 - sin lat0) / 2, and its odd squares take their count / nu of it.
    double oddShare = 0;
    for (int k = 0; k < squares[1]; ++k)
    {
      const double lat0 = (double(k) / squares[1] - 0.5) * vtkMath::Pi();
      const double lat1 = (double(k + 1) / squares[1] - 0.5) * vtkMath::Pi();
      int odd = 0;
      for (int i = 0; i < squares[0]; ++i)
      {
        odd += (i + k) % 2;
      }
      oddShare += 0.5 * (std::sin(lat1) - std::sin(lat0)) * odd / squares[0];
    }
    auto env = vtkRefractaEnvironmentMap::MakeChecker(squares[0], squares[1], color1, color2);
    int dims[3];
    env->GetDimensions(dims);
    vtkDataArray* texels = env->GetPointData()->GetScalars();
    double mean[3] = { 0, 0, 0 }, worst = 0;
    for (int j = 0; j < dims[1]; ++j)
    {
      const double lat0 = (double(j) / dims[1] - 0.5) * vtkMath::Pi();
      const double lat1 = (double(j + 1) / dims[1] - 0.5) * vtkMath::Pi();
      const double omega = 0.5 * (std::sin(lat1) - std::sin(lat0)) / dims[0];
      for (int i = 0; i < dims[0]; ++i)
      {
        const double f1 =
          OddShareOfTexel(double(i) * squares[0] / dims[0], double(i + 1) * squares[0] / dims[0],
            double(j) * squares[1] / dims[1], double(j + 1) * squares[1] / dims[1]);
        for (int c = 0; c < 3; ++c)
        {
          const double texel = texels->GetComponent(i + static_cast<vtkIdType>(dims[0]) * j, c);
          worst = std::max(worst, std::abs(texel - (f1 * color1[c] + (1 - f1) * color2[c])));
          mean[c] += omega * texel;
        }
      }
    }
    EXPECT_LT(worst, 1e-6) << squares[0] << " x " << squares[1];
    for (int c = 0; c < 3; ++c)
    {
      const double exact = oddShare * color1[c] + (1 - oddShare) * color2[c];
      EXPECT_NEAR(mean[c], exact, 1e-6) << squares[0] << " x " << squares[1] << ", channel " << c
                                        << " (" << dims[0] << " x " << dims[1] << " texels)";
    }
  }
}
