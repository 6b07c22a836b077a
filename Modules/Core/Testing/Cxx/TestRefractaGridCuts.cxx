// vtkRefractaGridCuts: the links and planes a wall cuts in a grid, exactly where they must be,
// the same under a rigid placement, a centre on the wall belonging to one side, glass cutting
// nothing, and the kept result found again only when the set, the grid or the placement change.
#include "vtkCommand.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPlaneSource.h"
#include "vtkPolyData.h"
#include "vtkRefractaGridCuts.h"
#include "vtkRefractaSurfaceMaterial.h"
#include "vtkRefractaSurfaceSet.h"
#include "vtkTestErrorObserver.h"
#include "vtkTransform.h"
#include "vtkTransformPolyDataFilter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

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
  // x = 0.53 lies between the centres i = 12 (0.5217) and 13 (0.5652).
  auto set = Set(Wall(0.53));
  vtkNew<vtkMatrix4x4> identity;
  vtkNew<vtkRefractaGridCuts> cuts;
  EXPECT_TRUE(cuts->Update(set, Dims, Spacing, identity));
  ASSERT_TRUE(cuts->HasCuts());
  const auto& links = cuts->GetLinks();
  const auto& planes = cuts->GetVoxelPlanes();
  int wrong = 0;
  for (int k = 0; k < N; ++k)
  {
    for (int j = 0; j < N; ++j)
    {
      for (int i = 0; i < N; ++i)
      {
        const size_t v = Voxel(i, j, k);
        wrong += links[v] != (i == 12 ? 1 : 0);
        wrong += (planes[v] >= 0) != (i == 12 || i == 13);
      }
    }
  }
  EXPECT_EQ(wrong, 0);
  // Across: voxel 12's surface is at u = 0.53 * 23 = 12.19.
  const double nearSide[3] = { 12.1, 5.0, 5.0 }, farSide[3] = { 12.4, 5.0, 5.0 };
  EXPECT_FALSE(cuts->IsAcross(12, 5, 5, nearSide));
  EXPECT_TRUE(cuts->IsAcross(12, 5, 5, farSide));
  EXPECT_TRUE(cuts->IsAcross(13, 5, 5, nearSide));
  EXPECT_FALSE(cuts->IsAcross(13, 5, 5, farSide));
  EXPECT_FALSE(cuts->IsAcross(11, 5, 5, farSide)) << "a voxel without a plane";
  // The plane in voxel coordinates: n = +-x, n . u + d = 0 at u = 12.19.
  ASSERT_GE(cuts->GetPlanes().size(), 4u); // one of the wall's two triangles, or both
  const float* p = cuts->GetPlanes().data();
  EXPECT_NEAR(std::abs(p[0]), 1.0, 1e-6);
  EXPECT_NEAR(-p[3] / p[0], 0.53 * 23, 1e-5);
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
  // The same plane per voxel (a tie between the wall's two triangles may pick the other one).
  int differ = 0;
  for (size_t v = 0; v < plain->GetVoxelPlanes().size(); ++v)
  {
    const int a = plain->GetVoxelPlanes()[v], b = placed->GetVoxelPlanes()[v];
    differ += (a < 0) != (b < 0);
    for (int c = 0; a >= 0 && b >= 0 && c < 4; ++c)
    {
      differ += std::abs(plain->GetPlanes()[4 * a + c] - placed->GetPlanes()[4 * b + c]) > 1e-4;
    }
  }
  EXPECT_EQ(differ, 0);
}

TEST(RefractaGridCuts, ACentreOnTheWallBelongsToItsFront)
{
  // x = 12 / 23 passes through the centres i = 12: both of their x links are cut (a touch
  // counts, within the float rounding of the set's vertices), and each such voxel belongs to one
  // side (the front where its centre is on the plane; float rounding may put it just behind).
  auto set = Set(Wall(12.0 / 23));
  vtkNew<vtkMatrix4x4> identity;
  vtkNew<vtkRefractaGridCuts> cuts;
  cuts->Update(set, Dims, Spacing, identity);
  ASSERT_TRUE(cuts->HasCuts());
  EXPECT_EQ(cuts->GetLinks()[Voxel(11, 3, 4)], 1);
  EXPECT_EQ(cuts->GetLinks()[Voxel(12, 3, 4)], 1);
  const float* plane = &cuts->GetPlanes()[4 * cuts->GetVoxelPlanes()[Voxel(12, 3, 4)]];
  const double front[3] = { 12.0 + 0.3 * plane[0], 3, 4 },
               back[3] = { 12.0 - 0.3 * plane[0], 3, 4 };
  EXPECT_NE(cuts->IsAcross(12, 3, 4, front), cuts->IsAcross(12, 3, 4, back));
}

TEST(RefractaGridCuts, GlassCutsNothing)
{
  vtkNew<vtkMatrix4x4> identity;
  vtkNew<vtkRefractaGridCuts> cuts;
  cuts->Update(Set(Wall(0.53), true), Dims, Spacing, identity);
  EXPECT_FALSE(cuts->HasCuts());
  EXPECT_TRUE(cuts->GetVoxelPlanes().empty());
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
  EXPECT_EQ(cuts->GetLinks()[Voxel(6, 0, 0)], 1); // 0.3 * 23 = 6.9
  EXPECT_EQ(cuts->GetLinks()[Voxel(12, 0, 0)], 0);
  const int finer[3] = { 2 * N - 1, 2 * N - 1, 2 * N - 1 };
  const double half[3] = { Spacing[0] / 2, Spacing[1] / 2, Spacing[2] / 2 };
  EXPECT_TRUE(cuts->Update(set, finer, half, placement));
  EXPECT_EQ(cuts->GetLinks()[13], 1); // 0.3 * 46 = 13.8
  placement->SetElement(0, 3, 0.25);  // the grid moves by +0.25 in x: the wall at local 0.05
  EXPECT_TRUE(cuts->Update(set, finer, half, placement));
  EXPECT_EQ(cuts->GetLinks()[2], 1); // 0.05 * 46 = 2.3
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
