// Tests of vtkRefractaSurfaceSet and vtkRefractaSurfaceMaterial: texel indexing covers every
// texel once and its corners map back to it; texel areas add up to the triangles' areas; a
// surface with a NaN vertex is rejected with a message naming it; zero-area triangles are dropped
// and counted; checker and scalar colours are baked as documented; matrices move surfaces;
// Build() is cached by MTime; the texel budget holds.
#include "SurfaceTestMeshes.h"

#include "vtkCellData.h"
#include "vtkCommand.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkRefractaBVH.h"
#include "vtkRefractaSurfaceMaterial.h"
#include "vtkRefractaSurfaceSet.h"
#include "vtkSphereSource.h"
#include "vtkTestErrorObserver.h"
#include "vtkUnsignedCharArray.h"

#include "refracta_surfaces.cl"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <set>

namespace
{
vtkSmartPointer<vtkPolyData> Plane(double size, int resolution = 1)
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(0, 0, 0);
  plane->SetPoint1(size, 0, 0);
  plane->SetPoint2(0, size, 0);
  plane->SetResolution(resolution, resolution);
  plane->Update();
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->DeepCopy(plane->GetOutput());
  return out;
}

// World position of barycentric (u, v) on BVH triangle k.
void PointOnTriangle(vtkRefractaBVH* bvh, vtkIdType k, double u, double v, double p[3])
{
  const double* t = &bvh->GetTriangles()[9 * k];
  for (int a = 0; a < 3; ++a)
  {
    p[a] = (1 - u - v) * t[a] + u * t[3 + a] + v * t[6 + a] + bvh->GetFrameOrigin()[a];
  }
}

// Albedo of the texel under world point (x, y) of a plane z = 0 (looking down).
const float* AlbedoAt(vtkRefractaSurfaceSet* set, double x, double y)
{
  const double origin[3] = { x, y, 1.0 }, dir[3] = { 0, 0, -1 };
  double hit[3];
  const vtkIdType k =
    set->GetBVH()->IntersectRay(origin, dir, std::numeric_limits<double>::infinity(), hit);
  if (k < 0)
  {
    return nullptr;
  }
  const int* info = &set->GetTriangleInfo()[REFRACTA_TRIANGLE_INFO_INTS * k];
  const int texel = info[REFRACTA_TRIANGLE_INFO_TEXEL] +
    vtkRefractaSurfaceSet::TexelIndex(static_cast<float>(hit[1]), static_cast<float>(hit[2]),
      info[REFRACTA_TRIANGLE_INFO_SUBDIVISION]);
  return &set->GetTexelAlbedo()[3 * texel];
}
}

TEST(RefractaSurfaceSet, TexelIndexCoversEveryTexelOnce)
{
  for (int n : { 1, 2, 3, 7, 64 })
  {
    std::set<int> seen;
    for (int texel = 0; texel < n * n; ++texel)
    {
      double c[6];
      ASSERT_TRUE(vtkRefractaSurfaceSet::GetTexelCorners(texel, n, c));
      // The centroid of the texel's corners maps back to the texel.
      const double u = (c[0] + c[2] + c[4]) / 3, v = (c[1] + c[3] + c[5]) / 3;
      EXPECT_EQ(vtkRefractaSurfaceSet::TexelIndex(float(u), float(v), n), texel) << "n " << n;
      seen.insert(texel);
      // Equal areas: every texel is a triangle of area 1 / (2 n^2) in (u, v).
      const double area =
        0.5 * std::fabs((c[2] - c[0]) * (c[5] - c[1]) - (c[4] - c[0]) * (c[3] - c[1]));
      EXPECT_NEAR(area, 0.5 / (n * n), 1e-12);
    }
    EXPECT_EQ(int(seen.size()), n * n);
    EXPECT_FALSE(vtkRefractaSurfaceSet::GetTexelCorners(n * n, n, nullptr));
    // Outside or on the boundary (rounding): clamped into range.
    for (float u : { -0.1f, 0.0f, 0.5f, 1.0f, 1.2f })
    {
      for (float v : { -0.1f, 0.0f, 0.5f, 1.0f, 1.2f })
      {
        const int t = vtkRefractaSurfaceSet::TexelIndex(u, v, n);
        EXPECT_GE(t, 0);
        EXPECT_LT(t, n * n);
      }
    }
  }
}

TEST(RefractaSurfaceSet, AtlasAreasAndResolution)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(1.0);
  sphere->SetThetaResolution(32);
  sphere->SetPhiResolution(16);
  vtkNew<vtkRefractaSurfaceSet> set;
  sphere->Update();
  set->AddSurface(sphere->GetOutput());
  set->AddSurface(Plane(4.0, 3));
  set->SetTexelSize(0.05);
  ASSERT_TRUE(set->Build());
  vtkRefractaBVH* bvh = set->GetBVH();
  const auto& info = set->GetTriangleInfo();
  const auto& areas = set->GetTexelAreas();
  vtkIdType texels = 0;
  double total = 0;
  for (vtkIdType k = 0; k < set->GetNumberOfTriangles(); ++k)
  {
    const double* t = &bvh->GetTriangles()[9 * k];
    const double e1[3] = { t[3] - t[0], t[4] - t[1], t[5] - t[2] };
    const double e2[3] = { t[6] - t[0], t[7] - t[1], t[8] - t[2] };
    const double c[3] = { e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
      e1[0] * e2[1] - e1[1] * e2[0] };
    const double area = 0.5 * std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    const int first = info[REFRACTA_TRIANGLE_INFO_INTS * k + REFRACTA_TRIANGLE_INFO_TEXEL];
    const int n = info[REFRACTA_TRIANGLE_INFO_INTS * k + REFRACTA_TRIANGLE_INFO_SUBDIVISION];
    EXPECT_EQ(first, texels);
    double sum = 0;
    for (int i = 0; i < n * n; ++i)
    {
      sum += areas[first + i];
    }
    EXPECT_NEAR(sum, area, 1e-12 * area);
    // n = ceil(longest edge / texel size).
    double longest = 0;
    for (int e = 0; e < 3; ++e)
    {
      const double* p = t + 3 * e;
      const double* q = t + 3 * ((e + 1) % 3);
      longest = std::max(longest,
        std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
          (p[2] - q[2]) * (p[2] - q[2])));
    }
    EXPECT_EQ(n, static_cast<int>(std::ceil(longest / 0.05)));
    texels += n * n;
    total += area;
  }
  EXPECT_EQ(texels, set->GetNumberOfTexels());
  EXPECT_NEAR(total, 16.0 + 4 * M_PI, 0.2); // the plane plus a sphere of 32 x 16 facets
  // The budget: far fewer texels allowed, at least one per triangle kept.
  set->SetMaximumNumberOfTexels(2000);
  ASSERT_TRUE(set->Build());
  EXPECT_LE(set->GetNumberOfTexels(), 2000);
  EXPECT_GT(set->GetEffectiveTexelSize(), 0.05);
  set->SetMaximumNumberOfTexels(1);
  ASSERT_TRUE(set->Build());
  EXPECT_EQ(set->GetNumberOfTexels(), set->GetNumberOfTriangles());
}

TEST(RefractaSurfaceSet, RejectsNaNAndDropsZeroArea)
{
  vtkNew<vtkRefractaSurfaceSet> set;
  vtkNew<vtkTest::ErrorObserver> errors;
  set->AddObserver(vtkCommand::ErrorEvent, errors);
  set->AddObserver(vtkCommand::WarningEvent, errors);
  auto good = Plane(1.0);
  auto bad = Plane(1.0);
  bad->GetPoints()->SetPoint(2, std::nan(""), 0, 0);
  EXPECT_EQ(set->AddSurface(good), 0);
  EXPECT_EQ(set->AddSurface(bad), 1);
  EXPECT_EQ(set->AddSurface(nullptr), -1);
  EXPECT_NE(errors->GetErrorMessage().find("null"), std::string::npos);
  errors->Clear();
  ASSERT_TRUE(set->Build());
  EXPECT_NE(errors->GetErrorMessage().find("Surface 1"), std::string::npos)
    << errors->GetErrorMessage();
  EXPECT_NE(errors->GetErrorMessage().find("NaN"), std::string::npos);
  EXPECT_EQ(set->GetNumberOfRejectedSurfaces(), 1);
  EXPECT_EQ(set->GetNumberOfTriangles(), 2); // the good plane's quad
  errors->Clear();

  // A matrix that makes a finite mesh infinite is rejected the same way.
  set->RemoveAllSurfaces();
  vtkNew<vtkMatrix4x4> infinite;
  infinite->SetElement(0, 0, std::numeric_limits<double>::infinity());
  set->AddSurface(good, nullptr, infinite);
  ASSERT_TRUE(set->Build());
  EXPECT_NE(errors->GetErrorMessage().find("after its matrix"), std::string::npos);
  EXPECT_EQ(set->GetNumberOfTriangles(), 0);
  errors->Clear();

  // Zero-area triangles: a repeated point, three collinear points; one good triangle.
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(0, 0, 0);
  points->InsertNextPoint(1, 0, 0);
  points->InsertNextPoint(2, 0, 0);
  points->InsertNextPoint(0, 1, 0);
  vtkNew<vtkCellArray> polys;
  const vtkIdType repeated[3] = { 0, 1, 1 }, collinear[3] = { 0, 1, 2 }, fine[3] = { 0, 1, 3 };
  polys->InsertNextCell(3, repeated);
  polys->InsertNextCell(3, collinear);
  polys->InsertNextCell(3, fine);
  vtkNew<vtkPolyData> mesh;
  mesh->SetPoints(points);
  mesh->SetPolys(polys);
  set->RemoveAllSurfaces();
  set->AddSurface(mesh);
  ASSERT_TRUE(set->Build());
  EXPECT_EQ(set->GetNumberOfDroppedTriangles(), 2);
  EXPECT_EQ(set->GetNumberOfTriangles(), 1);
  EXPECT_FALSE(errors->GetError());
}

TEST(RefractaSurfaceSet, BakesCheckerAndScalarColours)
{
  // A 1 x 1 plane, 4 x 4 checker: texels inside a square take its colour exactly.
  vtkNew<vtkRefractaSurfaceMaterial> checker;
  checker->UseCheckerOn();
  checker->SetCheckerSquares(4, 4);
  checker->SetCheckerColor1(1, 0, 0);
  checker->SetCheckerColor2(0, 0, 1);
  vtkNew<vtkRefractaSurfaceSet> set;
  set->AddSurface(Plane(1.0), checker);
  set->SetTexelSize(1.0 / 64);
  ASSERT_TRUE(set->Build());
  int checked = 0;
  for (double x = 0.03; x < 1.0; x += 0.0625)
  {
    for (double y = 0.03; y < 1.0; y += 0.0625)
    {
      const float* rgb = AlbedoAt(set, x, y);
      ASSERT_NE(rgb, nullptr);
      const bool even = (int(x * 4) + int(y * 4)) % 2 == 0;
      EXPECT_FLOAT_EQ(rgb[0], even ? 1.0f : 0.0f) << x << " " << y;
      EXPECT_FLOAT_EQ(rgb[2], even ? 0.0f : 1.0f) << x << " " << y;
      ++checked;
    }
  }
  EXPECT_EQ(checked, 256);
  // Texels cut by a checker edge blend the two colours (mean over four points), no more red than
  // the coverage allows: the overall mean is 1/2 red.
  double red = 0, area = 0;
  for (vtkIdType t = 0; t < set->GetNumberOfTexels(); ++t)
  {
    red += set->GetTexelAlbedo()[3 * t] * set->GetTexelAreas()[t];
    area += set->GetTexelAreas()[t];
  }
  EXPECT_NEAR(red / area, 0.5, 0.01);

  // Point colours (unsigned char) interpolated; cell colours (float) per cell.
  auto plane = Plane(1.0, 2); // 9 points, 4 quads
  vtkNew<vtkUnsignedCharArray> pointColors;
  pointColors->SetNumberOfComponents(4);
  for (vtkIdType p = 0; p < plane->GetNumberOfPoints(); ++p)
  {
    double x[3];
    plane->GetPoint(p, x);
    const unsigned char c[4] = { static_cast<unsigned char>(255 * x[0]), 51, 0, 255 };
    pointColors->InsertNextTypedTuple(c);
  }
  plane->GetPointData()->SetScalars(pointColors);
  vtkNew<vtkRefractaSurfaceMaterial> scalars;
  scalars->UseScalarColorsOn();
  set->RemoveAllSurfaces();
  set->AddSurface(plane, scalars);
  ASSERT_TRUE(set->Build());
  for (double x : { 0.1, 0.37, 0.5, 0.81 })
  {
    const float* rgb = AlbedoAt(set, x, 0.4);
    ASSERT_NE(rgb, nullptr);
    EXPECT_NEAR(rgb[0], x, 1.5 / 64 + 1.0 / 255); // linear in x, within a texel's width
    EXPECT_NEAR(rgb[1], 0.2, 1e-6);
  }
  vtkNew<vtkFloatArray> cellColors;
  cellColors->SetNumberOfComponents(3);
  for (vtkIdType c = 0; c < plane->GetNumberOfCells(); ++c)
  {
    cellColors->InsertNextTuple3(0.25 * c, 0.5, 1.0);
  }
  plane->GetPointData()->SetScalars(nullptr);
  plane->GetCellData()->SetScalars(cellColors);
  plane->Modified();
  ASSERT_TRUE(set->Build());
  EXPECT_NEAR(AlbedoAt(set, 0.2, 0.2)[0], 0.0, 1e-6);
  EXPECT_NEAR(AlbedoAt(set, 0.7, 0.2)[0], 0.25, 1e-6);
  EXPECT_NEAR(AlbedoAt(set, 0.2, 0.7)[0], 0.5, 1e-6);
  EXPECT_NEAR(AlbedoAt(set, 0.7, 0.7)[0], 0.75, 1e-6);

  // Scalar colours asked for but absent: a warning, and the albedo.
  plane->GetCellData()->SetScalars(nullptr);
  plane->Modified();
  scalars->SetAlbedo(0.3, 0.6, 0.9);
  vtkNew<vtkTest::ErrorObserver> warnings;
  set->AddObserver(vtkCommand::WarningEvent, warnings);
  ASSERT_TRUE(set->Build());
  EXPECT_TRUE(warnings->GetWarning());
  EXPECT_NEAR(AlbedoAt(set, 0.5, 0.5)[2], 0.9, 1e-6);
  // Colours are clamped to [0, 1]; a NaN is an error naming the setter that keeps the colour.
  scalars->SetAlbedo(2.0, -1.0, 0.5);
  double a[3];
  scalars->GetAlbedo(a);
  EXPECT_EQ(a[0], 1.0);
  EXPECT_EQ(a[1], 0.0);
  EXPECT_EQ(a[2], 0.5);
  vtkNew<vtkTest::ErrorObserver> errors;
  scalars->AddObserver(vtkCommand::ErrorEvent, errors);
  scalars->SetAlbedo(0.1, 0.2, std::nan(""));
  EXPECT_EQ(errors->CheckErrorMessage("SetAlbedo"), 0);
  scalars->GetAlbedo(a);
  EXPECT_EQ(a[2], 0.5);
  scalars->SetInsideExtinction(1.0, std::numeric_limits<double>::infinity(), 1.0);
  EXPECT_EQ(errors->CheckErrorMessage("SetInsideExtinction"), 0);
}

TEST(RefractaSurfaceSet, MatricesAndCaching)
{
  vtkNew<vtkRefractaSurfaceSet> set;
  vtkNew<vtkMatrix4x4> matrix;
  auto plane = Plane(2.0);
  set->AddSurface(plane, nullptr, matrix);
  ASSERT_TRUE(set->Build());
  EXPECT_EQ(set->GetNumberOfBuilds(), 1);
  ASSERT_TRUE(set->Build());
  EXPECT_EQ(set->GetNumberOfBuilds(), 1) << "nothing changed: no rebuild";
  // Moving the surface through its matrix rebuilds and moves the hit.
  const vtkMTimeType before = set->GetMTime();
  matrix->SetElement(2, 3, 5.0);
  EXPECT_GT(set->GetMTime(), before);
  ASSERT_TRUE(set->Build());
  EXPECT_EQ(set->GetNumberOfBuilds(), 2);
  double b[6];
  set->GetBounds(b);
  EXPECT_DOUBLE_EQ(b[4], 5.0);
  EXPECT_DOUBLE_EQ(b[5], 5.0);
  const double origin[3] = { 1, 1, 10 }, dir[3] = { 0, 0, -1 };
  double hit[3];
  ASSERT_GE(set->GetBVH()->IntersectRay(origin, dir, 100, hit), 0);
  EXPECT_NEAR(hit[0], 5.0, 1e-12);
  // The automatic texel size: diagonal / 128.
  EXPECT_NEAR(set->GetEffectiveTexelSize(), std::sqrt(8.0) / 128, 1e-12);
  // A material change rebuilds too.
  set->GetMaterial(0)->SetAlbedo(0.1, 0.2, 0.3);
  ASSERT_TRUE(set->Build());
  EXPECT_EQ(set->GetNumberOfBuilds(), 3);
  EXPECT_FLOAT_EQ(set->GetTexelAlbedo()[1], 0.2f);
}

//------------------------------------------------------------------------------
// Build step 7: each Lambertian corner averages the corner texels of the triangles of its surface
// that share the mesh point within 30 degrees, weighted by area. Checked against a brute-force
// search by world position and face normal: on a flat 4 x 4 plane (an interior point links the 6
// triangles around it), on a box whose 8 points every face shares (the 90-degree edges must keep
// the faces apart) and on a sphere, where the faces that meet at a point do not all lie within 30
// degrees of each other.
TEST(RefractaSurfaceSet, CornersAverageTheTrianglesSharingAPoint)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(5, 0, 0);
  sphere->SetThetaResolution(10);
  sphere->SetPhiResolution(6);
  sphere->Update();
  const double lo[3] = { 2, 0, 0 }, hi[3] = { 3, 1, 2 };
  // The meshes, and the most texels a corner links on each: 6 on the plane, the 2 of a box face,
  // at least 3 on the sphere (0 here: checked as a lower bound).
  const std::pair<vtkSmartPointer<vtkPolyData>, int> meshes[] = { { Plane(1.0, 4), 6 },
    { surface_test::ClosedBox(lo, hi), 2 }, { sphere->GetOutput(), 0 } };
  for (const auto& entry : meshes)
  {
    vtkPolyData* mesh = entry.first;
    vtkNew<vtkRefractaSurfaceSet> set;
    set->AddSurface(mesh);
    set->SetTexelSize(0.2); // some triangles subdivided, some not
    ASSERT_TRUE(set->Build());
    const vtkIdType triangles = set->GetNumberOfTriangles();
    const std::vector<int>& info = set->GetTriangleInfo();
    const std::vector<double>& areas = set->GetTexelAreas();
    ASSERT_EQ(set->GetCornerOffsets().size(), size_t(3 * triangles + 1));
    // Irradiance that differs per texel: E = texel index + 1 in red, 2 in green, 0 in blue.
    std::vector<float> e(3 * areas.size());
    for (size_t t = 0; t < areas.size(); ++t)
    {
      e[3 * t] = static_cast<float>(t + 1);
      e[3 * t + 1] = 2.0f;
      e[3 * t + 2] = 0.0f;
    }
    std::vector<float> corners;
    set->ComputeCornerIrradiance(e.data(), corners);
    ASSERT_EQ(corners.size(), size_t(9 * triangles));
    auto face = [&](vtkIdType k, double n[3])
    {
      double p[3][3];
      PointOnTriangle(set->GetBVH(), k, 0, 0, p[0]);
      PointOnTriangle(set->GetBVH(), k, 1, 0, p[1]);
      PointOnTriangle(set->GetBVH(), k, 0, 1, p[2]);
      double e1[3], e2[3];
      vtkMath::Subtract(p[1], p[0], e1);
      vtkMath::Subtract(p[2], p[0], e2);
      vtkMath::Cross(e1, e2, n);
      vtkMath::Normalize(n);
    };
    int maxLinks = 0;
    for (vtkIdType k = 0; k < triangles; ++k)
    {
      double nk[3];
      face(k, nk);
      const double corner[3][2] = { { 0, 0 }, { 1, 0 }, { 0, 1 } };
      for (int c = 0; c < 3; ++c)
      {
        double x[3];
        PointOnTriangle(set->GetBVH(), k, corner[c][0], corner[c][1], x);
        double sum = 0, area = 0;
        int links = 0;
        for (vtkIdType j = 0; j < triangles; ++j)
        {
          double nj[3];
          face(j, nj);
          for (int cj = 0; cj < 3; ++cj)
          {
            double y[3];
            PointOnTriangle(set->GetBVH(), j, corner[cj][0], corner[cj][1], y);
            if (vtkMath::Distance2BetweenPoints(x, y) < 1e-18 && vtkMath::Dot(nk, nj) >= 0.866)
            {
              const int n = info[4 * j + 1];
              const int texel =
                info[4 * j] + vtkRefractaSurfaceSet::TexelIndex(corner[cj][0], corner[cj][1], n);
              sum += areas[texel] * (texel + 1);
              area += areas[texel];
              ++links;
            }
          }
        }
        ASSERT_GE(links, 1);
        maxLinks = std::max(maxLinks, links);
        EXPECT_EQ(
          set->GetCornerOffsets()[3 * k + c + 1] - set->GetCornerOffsets()[3 * k + c], links)
          << "triangle " << k << " corner " << c;
        EXPECT_NEAR(corners[9 * k + 3 * c], sum / area, 1e-5 * sum / area);
        EXPECT_FLOAT_EQ(corners[9 * k + 3 * c + 1], 2.0f) << "a uniform irradiance stays uniform";
        EXPECT_EQ(corners[9 * k + 3 * c + 2], 0.0f);
      }
    }
    std::cout << triangles << " triangles, up to " << maxLinks << " texels per corner\n";
    if (entry.second > 0)
    {
      EXPECT_EQ(maxLinks, entry.second);
    }
    else
    {
      EXPECT_GE(maxLinks, 3);
    }
  }
}

//------------------------------------------------------------------------------
// A texture is sampled at the texture coordinates as vtkTexture maps them (pixel (i, j) covers
// u in [i, i + 1) / width), nearest by default and bilinear with TextureInterpolate, wrapped or
// clamped outside [0, 1], times the albedo; a new image rebuilds the set.
TEST(RefractaSurfaceSet, TexturesAreSampledAtTheTextureCoordinates)
{
  vtkNew<vtkImageData> image;
  image->SetDimensions(2, 2, 1);
  vtkNew<vtkUnsignedCharArray> colours;
  colours->SetNumberOfComponents(3);
  colours->InsertNextTuple3(255, 0, 0);     // (0, 0): red
  colours->InsertNextTuple3(0, 255, 0);     // (1, 0): green
  colours->InsertNextTuple3(0, 0, 255);     // (0, 1): blue
  colours->InsertNextTuple3(255, 255, 255); // (1, 1): white
  image->GetPointData()->SetScalars(colours);
  vtkNew<vtkRefractaSurfaceMaterial> material;
  material->SetAlbedo(0.5, 1.0, 1.0);
  material->SetTexture(image);
  double rgb[3];
  ASSERT_TRUE(material->EvaluateTexture(0.2, 0.7, rgb)); // nearest: pixel (0, 1), blue
  EXPECT_EQ(rgb[2], 1.0);
  EXPECT_EQ(rgb[0], 0.0);
  ASSERT_TRUE(material->EvaluateTexture(1.2, -0.3, rgb)); // wraps to (0.2, 0.7)
  EXPECT_EQ(rgb[2], 1.0);
  material->TextureRepeatOff();
  ASSERT_TRUE(material->EvaluateTexture(1.2, -0.3, rgb)); // clamped: pixel (1, 0), green
  EXPECT_EQ(rgb[1], 1.0);
  EXPECT_EQ(rgb[2], 0.0);
  material->TextureInterpolateOn();
  ASSERT_TRUE(material->EvaluateTexture(0.5, 0.25, rgb)); // between red and green at v's centre
  EXPECT_NEAR(rgb[0], 0.5, 1e-12);
  EXPECT_NEAR(rgb[1], 0.5, 1e-12);
  material->TextureInterpolateOff();
  material->TextureRepeatOn();

  // Through the set on a unit plane (vtkPlaneSource's texture coordinates are x and y).
  vtkNew<vtkRefractaSurfaceSet> set;
  set->AddSurface(Plane(1.0), material);
  set->SetTexelSize(0.05);
  ASSERT_TRUE(set->Build());
  const float* red = AlbedoAt(set, 0.25, 0.25);
  const float* white = AlbedoAt(set, 0.75, 0.75);
  ASSERT_NE(red, nullptr);
  ASSERT_NE(white, nullptr);
  EXPECT_NEAR(red[0], 0.5, 1e-6) << "red times the albedo's 0.5";
  EXPECT_NEAR(red[1], 0.0, 1e-6);
  EXPECT_NEAR(white[0], 0.5, 1e-6);
  EXPECT_NEAR(white[2], 1.0, 1e-6);
  const int builds = set->GetNumberOfBuilds();
  colours->SetTuple3(3, 0, 0, 0);
  colours->Modified();
  ASSERT_TRUE(set->Build());
  EXPECT_EQ(set->GetNumberOfBuilds(), builds + 1) << "the texture's change rebuilds";
  EXPECT_NEAR(AlbedoAt(set, 0.75, 0.75)[2], 0.0, 1e-6);

  // A texture that cannot be sampled (a volume, or scalars that do not fit the pixels) is a
  // warning naming the surface, and the albedo is used.
  vtkNew<vtkImageData> volume;
  volume->SetDimensions(2, 2, 2);
  volume->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  material->SetTexture(volume);
  EXPECT_FALSE(material->HasUsableTexture());
  EXPECT_FALSE(material->EvaluateTexture(0.5, 0.5, rgb));
  vtkNew<vtkTest::ErrorObserver> warnings;
  set->AddObserver(vtkCommand::WarningEvent, warnings);
  ASSERT_TRUE(set->Build());
  EXPECT_EQ(warnings->CheckWarningMessage("Surface 0 has a texture that cannot be sampled"), 0);
  EXPECT_NEAR(AlbedoAt(set, 0.75, 0.75)[0], 0.5, 1e-6);
  EXPECT_NEAR(AlbedoAt(set, 0.75, 0.75)[1], 1.0, 1e-6);
}
