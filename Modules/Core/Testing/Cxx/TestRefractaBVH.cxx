// Tests of vtkRefractaBVH on the host: the closest hit of the BVH is the brute-force closest hit
// (random triangle soups and a subdivided sphere far from the origin, random rays); rays aimed
// exactly at the shared edges and vertices of closed meshes never slip through (watertight
// test); any-hit agrees with closest hit; an empty hierarchy and degenerate centroids are safe.
#include "SurfaceTestMeshes.h"

#include "vtkRefractaBVH.h"
#include "vtkSphereSource.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace
{
constexpr double Far = std::numeric_limits<double>::infinity();

// Closest hit over all triangles of the BVH (its own order and frame): the reference.
vtkIdType BruteForce(
  vtkRefractaBVH* bvh, const double origin[3], const double dir[3], double hit[3])
{
  const double* o = bvh->GetFrameOrigin();
  const double shifted[3] = { origin[0] - o[0], origin[1] - o[1], origin[2] - o[2] };
  const std::vector<double>& tri = bvh->GetTriangles();
  vtkIdType found = -1;
  double best = Far;
  for (vtkIdType k = 0; k < bvh->GetNumberOfTriangles(); ++k)
  {
    double h[3];
    if (vtkRefractaBVH::IntersectTriangle(
          shifted, dir, &tri[9 * k], &tri[9 * k + 3], &tri[9 * k + 6], best, h))
    {
      best = h[0];
      std::copy(h, h + 3, hit);
      found = k;
    }
  }
  return found;
}

void CompareWithBruteForce(vtkRefractaBVH* bvh, int rays, unsigned seed)
{
  double b[6];
  bvh->GetBounds(b);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> gauss;
  int hits = 0;
  for (int r = 0; r < rays; ++r)
  {
    double origin[3], dir[3];
    for (int a = 0; a < 3; ++a)
    {
      const double extent = b[2 * a + 1] - b[2 * a];
      origin[a] = b[2 * a] - 0.25 * extent + 1.5 * extent * unit(rng);
      dir[a] = gauss(rng);
    }
    double expected[3] = { 0, 0, 0 }, actual[3] = { 0, 0, 0 };
    const vtkIdType want = BruteForce(bvh, origin, dir, expected);
    const vtkIdType got = bvh->IntersectRay(origin, dir, Far, actual);
    ASSERT_EQ(got < 0, want < 0) << "ray " << r;
    if (want >= 0)
    {
      ++hits;
      // Identical: the same test on the same numbers (a different triangle only on an exact tie).
      ASSERT_EQ(actual[0], expected[0]) << "ray " << r;
      if (got != want)
      {
        ASSERT_EQ(actual[0], expected[0]);
      }
      else
      {
        ASSERT_EQ(actual[1], expected[1]);
        ASSERT_EQ(actual[2], expected[2]);
      }
      EXPECT_TRUE(bvh->Occluded(origin, dir, 1.0000001 * actual[0]));
      EXPECT_FALSE(bvh->Occluded(origin, dir, 0.9999999 * actual[0]));
    }
    else
    {
      EXPECT_FALSE(bvh->Occluded(origin, dir, Far));
    }
  }
  EXPECT_GT(hits, rays / 10) << "the test rays should hit often enough to mean something";
}

// Counts the rays from `origin` aimed exactly at `targets` that miss the closed mesh; from
// outside, only targets where the ray crosses into the mesh (not its silhouette) count.
int CountLeaks(vtkRefractaBVH* bvh, const std::vector<double>& tri,
  const std::vector<double>& targets, const double origin[3], bool inside, int& counted)
{
  int leaks = 0;
  for (size_t i = 0; i < targets.size(); i += 3)
  {
    if (!inside && !surface_test::CrossesAt(tri, 9, &targets[i], origin))
    {
      continue;
    }
    ++counted;
    const double dir[3] = { targets[i] - origin[0], targets[i + 1] - origin[1],
      targets[i + 2] - origin[2] };
    double hit[3];
    if (bvh->IntersectRay(origin, dir, Far, hit) < 0)
    {
      ++leaks;
    }
  }
  return leaks;
}

// Every vertex and the midpoint of every edge of the triangles.
std::vector<double> VerticesAndEdgeMidpoints(const std::vector<double>& tri)
{
  std::vector<double> targets;
  for (size_t t = 0; t < tri.size(); t += 9)
  {
    for (int k = 0; k < 3; ++k)
    {
      const double* p = &tri[t + 3 * k];
      const double* q = &tri[t + 3 * ((k + 1) % 3)];
      targets.insert(targets.end(), p, p + 3);
      for (int a = 0; a < 3; ++a)
      {
        targets.push_back(0.5 * (p[a] + q[a]));
      }
    }
  }
  return targets;
}
}

TEST(RefractaBVH, MatchesBruteForceOnRandomSoups)
{
  for (int trial = 0; trial < 3; ++trial)
  {
    const double offset[3] = { trial * 1000.25, -trial * 37.5, 3.0 };
    const auto soup = surface_test::RandomSoup(500 + 1500 * trial, 0.2, offset, 11 + trial);
    vtkNew<vtkRefractaBVH> bvh;
    bvh->Build(soup.data(), static_cast<vtkIdType>(soup.size() / 9));
    EXPECT_EQ(bvh->GetNumberOfTriangles(), static_cast<vtkIdType>(soup.size() / 9));
    EXPECT_LE(bvh->GetDepth(), 60);
    EXPECT_GT(bvh->GetNumberOfNodes(), 1);
    CompareWithBruteForce(bvh, 3000, 100 + trial);
  }
}

TEST(RefractaBVH, MatchesBruteForceOnSphere)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(1e5, 2.5, -3);
  sphere->SetRadius(2.0);
  sphere->SetThetaResolution(60);
  sphere->SetPhiResolution(40);
  sphere->Update();
  const auto tri = surface_test::Triangles(sphere->GetOutput());
  vtkNew<vtkRefractaBVH> bvh;
  bvh->Build(tri.data(), static_cast<vtkIdType>(tri.size() / 9));
  EXPECT_NEAR(bvh->GetFrameOrigin()[0], 1e5, 1e-6);
  CompareWithBruteForce(bvh, 3000, 5);
}

TEST(RefractaBVH, WatertightOnSharedEdgesAndVertices)
{
  // A sphere (fan poles, shared points) and a box, hit from inside and from outside, including
  // axis-aligned rays (zero direction components) through the box's edges and corners.
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(10.5, -4.25, 7);
  sphere->SetRadius(1.5);
  sphere->SetThetaResolution(24);
  sphere->SetPhiResolution(13);
  sphere->Update();
  const double lo[3] = { -1, -2, -0.5 }, hi[3] = { 1, 2, 0.5 };
  auto box = surface_test::ClosedBox(lo, hi);
  for (vtkPolyData* mesh : { sphere->GetOutput(), box.GetPointer() })
  {
    const auto tri = surface_test::Triangles(mesh);
    vtkNew<vtkRefractaBVH> bvh;
    bvh->Build(tri.data(), static_cast<vtkIdType>(tri.size() / 9));
    const auto targets = VerticesAndEdgeMidpoints(tri);
    double b[6];
    bvh->GetBounds(b);
    std::mt19937 rng(3);
    std::normal_distribution<double> gauss;
    int counted = 0;
    for (int o = 0; o < 12; ++o)
    {
      // Four origins near the centre (inside), eight far outside.
      const bool inside = o < 4;
      double origin[3];
      for (int a = 0; a < 3; ++a)
      {
        origin[a] = 0.5 * (b[2 * a] + b[2 * a + 1]) + (inside ? 0.1 : 10.0) * gauss(rng);
      }
      EXPECT_EQ(CountLeaks(bvh, tri, targets, origin, inside, counted), 0) << "origin " << o;
    }
    EXPECT_GT(counted, int(targets.size() / 3) * 6) << "most rays must be counted";
  }
  // Axis-aligned rays (zero direction components) exactly through the shared diagonal of the
  // box's bottom and top faces: the edge functions are exactly 0 there.
  const auto tri = surface_test::Triangles(box);
  vtkNew<vtkRefractaBVH> bvh;
  bvh->Build(tri.data(), static_cast<vtkIdType>(tri.size() / 9));
  int leaks = 0;
  for (double s : { 0.25, 0.5, 0.75 })
  {
    {
      const double x = s * lo[0] + (1 - s) * hi[0], y = s * lo[1] + (1 - s) * hi[1];
      const double origin[3] = { x, y, -5.0 };
      const double dir[3] = { 0, 0, 1 };
      double hit[3];
      leaks += bvh->IntersectRay(origin, dir, Far, hit) < 0 ? 1 : 0;
      EXPECT_NEAR(hit[0], 5.0 + lo[2], 1e-12);
    }
  }
  EXPECT_EQ(leaks, 0);
}

TEST(RefractaBVH, EmptyAndDegenerateInputs)
{
  vtkNew<vtkRefractaBVH> bvh;
  bvh->Build(nullptr, 0);
  const double o[3] = { 0, 0, 0 }, d[3] = { 0, 0, 1 };
  double hit[3];
  EXPECT_EQ(bvh->IntersectRay(o, d, Far, hit), -1);
  EXPECT_FALSE(bvh->Occluded(o, d, Far));
  EXPECT_EQ(bvh->GetNumberOfNodes(), 0);
  // 1000 copies of one triangle: centroids cannot be binned, the depth must stay bounded.
  std::vector<double> same;
  const double t[9] = { -1, -1, 1, 1, -1, 1, 0, 1, 1 };
  for (int k = 0; k < 1000; ++k)
  {
    same.insert(same.end(), t, t + 9);
  }
  bvh->Build(same.data(), 1000);
  EXPECT_LE(bvh->GetDepth(), 60);
  EXPECT_GE(bvh->IntersectRay(o, d, Far, hit), 0);
  EXPECT_DOUBLE_EQ(hit[0], 1.0);
  EXPECT_GE(bvh->GetBuildSeconds(), 0.0);
}
