// vtkRefractaGridCuts: the links a wall cuts in a grid and the voxels near it, exactly where they
// must be, the same under a rigid placement, a wall through centres, glass cutting nothing, bad
// grids, and the kept result found again only when the set, the grid or the placement change.
#include "vtkCommand.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPlaneSource.h"
#include "vtkPolyData.h"
#include "vtkRefractaBVH.h"
#include "vtkRefractaGridCuts.h"
#include "vtkRefractaSurfaceMaterial.h"
#include "vtkRefractaSurfaceSet.h"
#include "vtkSphereSource.h"
#include "vtkTestErrorObserver.h"
#include "vtkTransform.h"
#include "vtkTransformPolyDataFilter.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

namespace
{
constexpr int N = 24;
const int Dims[3] = { N, N, N };
const double Spacing[3] = { 1.0 / (N - 1), 1.0 / (N - 1), 1.0 / (N - 1) };

// A wall x = `x` reaching beyond the grid [0, 1]^3, moved by `placement` (nullptr: none).
vtkSmartPointer<vtkPolyData> Wall(double x, vtkTransform* placement = nullptr)
{
  vtkNew<vtkPlaneSource> wall;
  wall->SetOrigin(x, -1, -1);
  wall->SetPoint1(x, 2, -1);
  wall->SetPoint2(x, -1, 2);
  wall->Update();
  vtkSmartPointer<vtkPolyData> out = wall->GetOutput();
  if (placement)
  {
    vtkNew<vtkTransformPolyDataFilter> move;
    move->SetInputData(out);
    move->SetTransform(placement);
    move->Update();
    out = move->GetOutput();
  }
  return out;
}

vtkSmartPointer<vtkRefractaSurfaceSet> Set(vtkPolyData* mesh, bool glass = false)
{
  auto set = vtkSmartPointer<vtkRefractaSurfaceSet>::New();
  vtkNew<vtkRefractaSurfaceMaterial> material;
  if (glass)
  {
    material->SetKindToDielectric();
  }
  set->AddSurface(mesh, material);
  EXPECT_TRUE(set->Build());
  return set;
}

size_t Voxel(int i, int j, int k)
{
  return i + size_t(N) * (j + size_t(N) * k);
}
}

TEST(RefractaGridCuts, AWallCutsTheLinksAcrossItAndNoOthers)
{
  // x = 0.53 lies between the centres i = 12 (0.5217) and 13 (0.5652): the x links of i = 12 are
  // cut, and the voxels within one voxel of the wall (i = 12 and 13, at 0.19 and 0.81 voxels) are
  // near it.
  auto set = Set(Wall(0.53));
  vtkNew<vtkMatrix4x4> identity;
  vtkNew<vtkRefractaGridCuts> cuts;
  EXPECT_TRUE(cuts->Update(set, Dims, Spacing, identity));
  ASSERT_TRUE(cuts->HasCuts());
  const auto& links = cuts->GetLinks();
  int wrong = 0;
  for (int k = 0; k < N; ++k)
  {
    for (int j = 0; j < N; ++j)
    {
      for (int i = 0; i < N; ++i)
      {
        const size_t v = Voxel(i, j, k);
        wrong += (links[v] & 7) != (i == 12 ? 1 : 0);
        wrong += cuts->IsNear(i, j, k) != (i == 12 || i == 13);
      }
    }
  }
  EXPECT_EQ(wrong, 0);
  EXPECT_FALSE(cuts->IsNear(-1, 0, 0));
  EXPECT_FALSE(cuts->IsNear(12, N, 0));
}

TEST(RefractaGridCuts, AnObliqueWallCutsExactlyTheLinksItSeparates)
{
  // A wall through (0.5, 0.47, 0.52) with normal n = (0.3, -0.5, 0.81), far larger than the grid
  // (the search visits only the voxels within reach of its plane): a link is cut where the plane
  // separates its ends, a voxel is near where its centre lies within |n_x| + |n_y| + |n_z| voxels
  // of the plane (n unit). Centres within 1e-4 voxel of either rule's boundary are skipped.
  const double n0[3] = { 0.3, -0.5, 0.81 }, c[3] = { 0.5, 0.47, 0.52 };
  const double length = std::sqrt(n0[0] * n0[0] + n0[1] * n0[1] + n0[2] * n0[2]);
  const double n[3] = { n0[0] / length, n0[1] / length, n0[2] / length };
  double u[3] = { n[1], -n[0], 0.0 }; // in the plane
  const double ul = std::sqrt(u[0] * u[0] + u[1] * u[1]);
  u[0] /= ul;
  u[1] /= ul;
  const double w[3] = { n[1] * u[2] - n[2] * u[1], n[2] * u[0] - n[0] * u[2],
    n[0] * u[1] - n[1] * u[0] };
  vtkNew<vtkPlaneSource> wall;
  wall->SetOrigin(
    c[0] - 3 * u[0] - 3 * w[0], c[1] - 3 * u[1] - 3 * w[1], c[2] - 3 * u[2] - 3 * w[2]);
  wall->SetPoint1(
    c[0] + 3 * u[0] - 3 * w[0], c[1] + 3 * u[1] - 3 * w[1], c[2] + 3 * u[2] - 3 * w[2]);
  wall->SetPoint2(
    c[0] - 3 * u[0] + 3 * w[0], c[1] - 3 * u[1] + 3 * w[1], c[2] - 3 * u[2] + 3 * w[2]);
  wall->Update();
  vtkNew<vtkMatrix4x4> identity;
  vtkNew<vtkRefractaGridCuts> cuts;
  cuts->Update(Set(wall->GetOutput()), Dims, Spacing, identity);
  ASSERT_TRUE(cuts->HasCuts());
  // Signed distance in voxels of centre (i, j, k) (isotropic spacing).
  auto distance = [&](double i, double j, double k)
  {
    return (n[0] * (i * Spacing[0] - c[0]) + n[1] * (j * Spacing[1] - c[1]) +
             n[2] * (k * Spacing[2] - c[2])) /
      Spacing[0];
  };
  const double reach = std::fabs(n[0]) + std::fabs(n[1]) + std::fabs(n[2]);
  int wrong = 0, cut = 0, near = 0, checked = 0;
  for (int k = 0; k < N; ++k)
  {
    for (int j = 0; j < N; ++j)
    {
      for (int i = 0; i < N; ++i)
      {
        const double here = distance(i, j, k);
        if (std::fabs(std::fabs(here) - reach) < 1e-4 || std::fabs(here) < 1e-4)
        {
          continue;
        }
        ++checked;
        const bool expectNear = std::fabs(here) <= reach;
        near += expectNear;
        wrong += cuts->IsNear(i, j, k) != expectNear;
        const double next[3] = { distance(i + 1, j, k), distance(i, j + 1, k),
          distance(i, j, k + 1) };
        const int ijk[3] = { i, j, k };
        for (int a = 0; a < 3; ++a)
        {
          const bool expectCut = ijk[a] + 1 < N && (here < 0) != (next[a] < 0);
          cut += expectCut;
          wrong += ((cuts->GetLinks()[Voxel(i, j, k)] >> a) & 1) != (expectCut ? 1 : 0);
        }
      }
    }
  }
  std::cout << checked << " voxels checked, " << near << " near, " << cut << " links cut\n";
  EXPECT_GT(near, 1000);
  EXPECT_GT(cut, 1000);
  EXPECT_EQ(wrong, 0);
}

TEST(RefractaGridCuts, ARigidPlacementGivesTheSameCuts)
{
  // The grid placed by a rotation and a translation, the wall moved alike: the same cuts.
  vtkNew<vtkTransform> placement;
  placement->Translate(10, -5, 3);
  placement->RotateWXYZ(40, 1, 2, 0.5);
  vtkNew<vtkMatrix4x4> identity;
  vtkNew<vtkRefractaGridCuts> plain, placed;
  plain->Update(Set(Wall(0.53)), Dims, Spacing, identity);
  placed->Update(Set(Wall(0.53, placement)), Dims, Spacing, placement->GetMatrix());
  EXPECT_EQ(plain->GetLinks(), placed->GetLinks());
}

TEST(RefractaGridCuts, AWallThroughCentresCutsTheLinksOnBothSides)
{
  // x = 12 / 23 passes through the centres i = 12: both of their x links are cut (a touch
  // counts, within the float rounding of the set's vertices), and they are near the wall.
  auto set = Set(Wall(12.0 / 23));
  vtkNew<vtkMatrix4x4> identity;
  vtkNew<vtkRefractaGridCuts> cuts;
  cuts->Update(set, Dims, Spacing, identity);
  ASSERT_TRUE(cuts->HasCuts());
  EXPECT_EQ(cuts->GetLinks()[Voxel(11, 3, 4)] & 7, 1);
  EXPECT_EQ(cuts->GetLinks()[Voxel(12, 3, 4)] & 7, 1);
  EXPECT_EQ(cuts->GetLinks()[Voxel(13, 3, 4)] & 7, 0);
  EXPECT_TRUE(cuts->IsNear(12, 3, 4));
  EXPECT_FALSE(cuts->IsNear(14, 3, 4));
}

TEST(RefractaGridCuts, GlassCutsNothing)
{
  vtkNew<vtkMatrix4x4> identity;
  vtkNew<vtkRefractaGridCuts> cuts;
  cuts->Update(Set(Wall(0.53), true), Dims, Spacing, identity);
  EXPECT_FALSE(cuts->HasCuts());
  EXPECT_TRUE(cuts->GetLinks().empty());
  cuts->Update(nullptr, Dims, Spacing, identity);
  EXPECT_FALSE(cuts->HasCuts());
}

TEST(RefractaGridCuts, KeptUntilTheSetTheGridOrThePlacementChange)
{
  vtkNew<vtkRefractaSurfaceSet> set;
  vtkNew<vtkRefractaSurfaceMaterial> material;
  set->AddSurface(Wall(0.53), material);
  ASSERT_TRUE(set->Build());
  vtkNew<vtkMatrix4x4> placement;
  vtkNew<vtkRefractaGridCuts> cuts;
  EXPECT_TRUE(cuts->Update(set, Dims, Spacing, placement));
  EXPECT_FALSE(cuts->Update(set, Dims, Spacing, placement));
  EXPECT_EQ(cuts->GetNumberOfSearches(), 1);
  // The wall moves: a new build of the set.
  set->RemoveAllSurfaces();
  set->AddSurface(Wall(0.3), material);
  ASSERT_TRUE(set->Build());
  EXPECT_TRUE(cuts->Update(set, Dims, Spacing, placement));
  EXPECT_EQ(cuts->GetLinks()[Voxel(6, 0, 0)] & 7, 1); // 0.3 * 23 = 6.9
  EXPECT_EQ(cuts->GetLinks()[Voxel(12, 0, 0)], 0);
  const int finer[3] = { 2 * N - 1, 2 * N - 1, 2 * N - 1 };
  const double half[3] = { Spacing[0] / 2, Spacing[1] / 2, Spacing[2] / 2 };
  EXPECT_TRUE(cuts->Update(set, finer, half, placement));
  EXPECT_EQ(cuts->GetLinks()[13] & 7, 1); // 0.3 * 46 = 13.8
  placement->SetElement(0, 3, 0.25);  // the grid moves by +0.25 in x: the wall at local 0.05
  EXPECT_TRUE(cuts->Update(set, finer, half, placement));
  EXPECT_EQ(cuts->GetLinks()[2] & 7, 1); // 0.05 * 46 = 2.3
  EXPECT_EQ(cuts->GetNumberOfSearches(), 4);
}

TEST(RefractaGridCuts, BadGridsAreErrorsThatLeaveNoCuts)
{
  // Dimensions below 1, zero or non-finite spacings: an error naming the grid, no cuts; an
  // unbuilt set is built; a null placement is the identity.
  vtkNew<vtkRefractaSurfaceSet> set;
  vtkNew<vtkRefractaSurfaceMaterial> material;
  set->AddSurface(Wall(0.53), material);
  vtkNew<vtkRefractaGridCuts> cuts;
  EXPECT_TRUE(cuts->Update(set, Dims, Spacing, nullptr));
  ASSERT_TRUE(cuts->HasCuts()) << "the set was not built, or the null placement not the identity";
  vtkNew<vtkTest::ErrorObserver> errors;
  cuts->AddObserver(vtkCommand::ErrorEvent, errors);
  const int badDims[3] = { 0, -3, 24 };
  EXPECT_FALSE(cuts->Update(set, badDims, Spacing, nullptr));
  EXPECT_FALSE(cuts->HasCuts());
  const double zero[3] = { 0, 0, 0 }, nan[3] = { NAN, 1, 1 };
  EXPECT_FALSE(cuts->Update(set, Dims, zero, nullptr));
  EXPECT_FALSE(cuts->Update(set, Dims, nan, nullptr));
  EXPECT_FALSE(cuts->HasCuts());
  EXPECT_NE(errors->GetErrorMessage().find("spacings finite and > 0"), std::string::npos)
    << errors->GetErrorMessage();
  EXPECT_TRUE(cuts->Update(set, Dims, Spacing, nullptr)); // a good grid again: searched
  EXPECT_TRUE(cuts->HasCuts());
}

TEST(RefractaGridCuts, OwnedVolumesCountTheSliversAWallMoves)
{
  // x = 0.51 lies at u = 11.73: the box of a centre at i = 12 (dark side) holds a lit sliver
  // 0.23 voxel wide, whose pieces deposit into the lit centres at i = 11. The owned volumes:
  // 1.23 boxes for i = 11, 0.77 for i = 12 (64 points per box: to about 2/64), and the total over
  // the grid is the grid's (a point's share only moves).
  vtkNew<vtkMatrix4x4> identity;
  vtkNew<vtkRefractaGridCuts> cuts;
  cuts->Update(Set(Wall(0.51)), Dims, Spacing, identity);
  const auto& voxels = cuts->GetScaledVoxels();
  const auto& scales = cuts->GetVolumeScales();
  ASSERT_EQ(voxels.size(), scales.size());
  std::vector<double> owned(size_t(N) * N * N, 1.0);
  for (size_t k = 0; k < voxels.size(); ++k)
  {
    owned[voxels[k]] = scales[k] > 0 ? 1.0 / scales[k] : 0.0;
  }
  const double fraction = 0.51 * (N - 1) - 11.5; // the sliver, in boxes
  EXPECT_NEAR(owned[Voxel(11, 10, 10)], 1.0 + fraction, 0.035);
  EXPECT_NEAR(owned[Voxel(12, 10, 10)], 1.0 - fraction, 0.035);
  EXPECT_EQ(owned[Voxel(13, 10, 10)], 1.0);
  EXPECT_EQ(owned[Voxel(10, 10, 10)], 1.0);
  double total = 0;
  for (double v : owned)
  {
    total += v;
  }
  EXPECT_NEAR(total, double(N) * N * N, 1e-6);
}

TEST(RefractaGridCuts, OwnedVolumesMatchACountAgainstEveryTriangle)
{
  // A closed sphere, oblique and curved, in the 24^3 grid: the owned volumes counted against the
  // few triangles noted for the boxes a segment passes equal those counted point by point against
  // every triangle (the set's BVH) by the same rule, for every voxel of the grid.
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(0.48, 0.51, 0.5);
  sphere->SetRadius(0.31);
  sphere->SetThetaResolution(14);
  sphere->SetPhiResolution(11);
  sphere->Update();
  auto set = Set(sphere->GetOutput());
  vtkNew<vtkMatrix4x4> identity;
  vtkNew<vtkRefractaGridCuts> cuts;
  cuts->Update(set, Dims, Spacing, identity);
  std::vector<double> owned(size_t(N) * N * N, 1.0);
  for (size_t k = 0; k < cuts->GetScaledVoxels().size(); ++k)
  {
    const float scale = cuts->GetVolumeScales()[k];
    owned[cuts->GetScaledVoxels()[k]] = scale > 0 ? 1.0 / scale : 0.0;
  }
  // The brute-force count: every point of every box, the same 64 points, the same order of
  // neighbours (nearest first, the box's own centre before them), the same 0.1% touch.
  const vtkRefractaBVH* bvh = set->GetBVH();
  auto separated = [&](const double p[3], const int to[3])
  {
    double origin[3], direction[3];
    for (int c = 0; c < 3; ++c)
    {
      origin[c] = p[c] * Spacing[c];
      direction[c] = (to[c] - p[c]) * Spacing[c];
    }
    return bvh->Occluded(origin, direction, 1.001);
  };
  const double phi3 = 1.2207440846057596;
  const double alpha[3] = { 1.0 / phi3, 1.0 / (phi3 * phi3), 1.0 / (phi3 * phi3 * phi3) };
  std::vector<double> expected(owned.size(), 1.0);
  for (int z = 0; z < N; ++z)
  {
    for (int y = 0; y < N; ++y)
    {
      for (int x = 0; x < N; ++x)
      {
        const int cell[3] = { x, y, z };
        for (int k = 0; k < 64; ++k)
        {
          double p[3];
          for (int a = 0; a < 3; ++a)
          {
            const double u = 0.5 + (k + 1) * alpha[a];
            p[a] = cell[a] + u - std::floor(u) - 0.5;
          }
          if (!separated(p, cell))
          {
            continue;
          }
          // Neighbours by distance from p, the first one p sees (none: p stays in its box).
          std::vector<std::pair<double, int>> order;
          for (int n = 0; n < 27; ++n)
          {
            const int to[3] = { x + n % 3 - 1, y + (n / 3) % 3 - 1, z + n / 9 - 1 };
            if (n != 13 && to[0] >= 0 && to[0] < N && to[1] >= 0 && to[1] < N && to[2] >= 0 &&
              to[2] < N)
            {
              double d = 0;
              for (int a = 0; a < 3; ++a)
              {
                d += (to[a] - p[a]) * (to[a] - p[a]);
              }
              order.emplace_back(d, n);
            }
          }
          std::stable_sort(order.begin(), order.end(),
            [](const std::pair<double, int>& a, const std::pair<double, int>& b)
            { return a.first < b.first; });
          for (const auto& candidate : order)
          {
            const int n = candidate.second;
            const int to[3] = { x + n % 3 - 1, y + (n / 3) % 3 - 1, z + n / 9 - 1 };
            if (!separated(p, to))
            {
              expected[Voxel(x, y, z)] -= 1.0 / 64;
              expected[Voxel(to[0], to[1], to[2])] += 1.0 / 64;
              break;
            }
          }
        }
      }
    }
  }
  int differing = 0, moved = 0;
  for (size_t v = 0; v < owned.size(); ++v)
  {
    differing += std::fabs(owned[v] - expected[v]) > 1e-5 ? 1 : 0; // the scales are floats
    moved += std::fabs(expected[v] - 1.0) > 1e-9 ? 1 : 0;
  }
  std::cout << moved << " voxels own another volume than their box; " << differing
            << " counted differently" << std::endl;
  EXPECT_GT(moved, 100);
  EXPECT_EQ(differing, 0);
}
