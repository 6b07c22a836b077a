// vtkMeshVoxelizer::EXACT_INTERFACES (issue 20): n is not smoothed and grad n never holds the jump
// at a surface; the meshes reach vtkRefractaSurfaceSet as dielectric interfaces with the right
// indices inside and outside (nested meshes included); index-matched meshes are no interfaces; a
// density-scaled index falls back to SMOOTHED_INDEX with a warning.
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkMediumMaterial.h"
#include "vtkMeshVoxelizer.h"
#include "vtkPointData.h"
#include "vtkRefractaMedium.h"
#include "vtkRefractaSurfaceMaterial.h"
#include "vtkRefractaSurfaceSet.h"
#include "vtkSphere.h"
#include "vtkSphereSource.h"
#include "vtkTestErrorObserver.h"

#include <gtest/gtest.h>

#include <cmath>

namespace
{
vtkSmartPointer<vtkPolyData> Ball(double radius)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(radius);
  sphere->SetThetaResolution(48);
  sphere->SetPhiResolution(24);
  sphere->Update();
  return sphere->GetOutput();
}

vtkSmartPointer<vtkMediumMaterial> Index(double n)
{
  auto m = vtkSmartPointer<vtkMediumMaterial>::New();
  m->SetRefractiveIndex(n);
  return m;
}
}

TEST(MeshVoxelizerInterfaces, UnsmoothedIndexAndNoJumpInTheGradient)
{
  vtkNew<vtkMeshVoxelizer> voxelizer;
  voxelizer->AddInputData(Ball(1.0));
  voxelizer->AddInputData(Ball(0.5));
  voxelizer->SetMaterial(0, Index(1.5));
  voxelizer->SetMaterial(1, Index(2.0));
  voxelizer->SetSurroundingMaterial(Index(1.2));
  voxelizer->SetDimensions(32, 32, 32);
  voxelizer->SetPadding(0.3);
  voxelizer->SetInterfaceModeToExactInterfaces();
  voxelizer->Update();
  ASSERT_TRUE(voxelizer->GetWroteInterfaces());
  vtkImageData* out = voxelizer->GetOutput();
  vtkDataArray* n = out->GetPointData()->GetArray(vtkRefractaMedium::RefractiveIndexName());
  vtkDataArray* grad =
    out->GetPointData()->GetArray(vtkRefractaMedium::RefractiveIndexGradientName());
  ASSERT_NE(n, nullptr);
  ASSERT_NE(grad, nullptr);
  double maxGrad = 0;
  int pure[3] = { 0, 0, 0 };
  for (vtkIdType v = 0; v < out->GetNumberOfPoints(); ++v)
  {
    const double* g = grad->GetTuple3(v);
    maxGrad = std::max({ maxGrad, std::fabs(g[0]), std::fabs(g[1]), std::fabs(g[2]) });
    const double value = n->GetTuple1(v);
    pure[0] += value == 1.2f ? 1 : 0;
    pure[1] += value == 1.5f ? 1 : 0;
    pure[2] += value == 2.0f ? 1 : 0;
  }
  // Homogeneous materials: grad n is 0 everywhere (the jumps are the interfaces'), and n is not
  // smoothed (voxels away from the surfaces hold their material's index exactly).
  EXPECT_EQ(maxGrad, 0.0);
  EXPECT_GT(pure[0], 1000);
  EXPECT_GT(pure[1], 500);
  EXPECT_GT(pure[2], 50);

  vtkNew<vtkRefractaSurfaceSet> set;
  ASSERT_EQ(set->AddMediumInterfaces(out), 2);
  ASSERT_TRUE(set->Build());
  EXPECT_EQ(set->GetNumberOfDielectricTriangles(), 2 * Ball(1.0)->GetNumberOfCells());
  // The outer ball: 1.5 inside, the surroundings' 1.2 outside; the inner: 2.0 in 1.5.
  bool outer = false, inner = false;
  for (int s = 0; s < set->GetNumberOfSurfaces(); ++s)
  {
    vtkRefractaSurfaceMaterial* m = set->GetMaterial(s);
    EXPECT_EQ(m->GetKind(), vtkRefractaSurfaceMaterial::DIELECTRIC);
    outer = outer || (m->GetIndexInside() == 1.5 && m->GetIndexOutside() == 1.2);
    inner = inner || (m->GetIndexInside() == 2.0 && m->GetIndexOutside() == 1.5);
  }
  EXPECT_TRUE(outer);
  EXPECT_TRUE(inner);

  // The default mode smooths and writes no interfaces: nothing to add.
  voxelizer->SetInterfaceModeToSmoothedIndex();
  voxelizer->Update();
  EXPECT_FALSE(voxelizer->GetWroteInterfaces());
  vtkNew<vtkRefractaSurfaceSet> none;
  EXPECT_EQ(none->AddMediumInterfaces(voxelizer->GetOutput()), 0);
  EXPECT_EQ(none->AddMediumInterfaces(nullptr), 0);
}

// An index-matched mesh (the same n inside and outside: a fog blob with n = 1 in air) neither
// refracts nor reflects: it is no interface, its medium is the grid's occupancy mix, and a scene of
// such meshes alone writes none (so the plan sees no surfaces and no refraction). A glass ball
// inside such a blob is still an interface, against the blob's index.
TEST(MeshVoxelizerInterfaces, IndexMatchedMeshesAreNoInterfaces)
{
  auto fog = Index(1.0);
  fog->SetExtinction(4.0, 4.0, 4.0);
  fog->SetAlbedo(0.9, 0.9, 0.9);
  vtkNew<vtkMeshVoxelizer> voxelizer;
  voxelizer->AddInputData(Ball(1.0));
  voxelizer->SetMaterial(0, fog);
  voxelizer->SetDimensions(24, 24, 24);
  voxelizer->SetPadding(0.3);
  voxelizer->SetInterfaceModeToExactInterfaces();
  voxelizer->Update();
  EXPECT_FALSE(voxelizer->GetWroteInterfaces());
  vtkImageData* out = voxelizer->GetOutput();
  EXPECT_EQ(out->GetFieldData()->GetArray(vtkRefractaMedium::InterfaceTrianglesName()), nullptr);
  vtkNew<vtkRefractaSurfaceSet> none;
  EXPECT_EQ(none->AddMediumInterfaces(out), 0);
  // The blob's medium is in the grid: the centre voxel holds its extinction.
  vtkDataArray* extinction = out->GetPointData()->GetArray(vtkRefractaMedium::ExtinctionName());
  ASSERT_NE(extinction, nullptr);
  const vtkIdType centre = out->FindPoint(0.0, 0.0, 0.0);
  EXPECT_FLOAT_EQ(extinction->GetComponent(centre, 0), 4.0f);

  // A glass ball in the blob: one interface, 1.5 inside, the blob's 1.0 outside.
  voxelizer->AddInputData(Ball(0.5));
  voxelizer->SetMaterial(1, Index(1.5));
  voxelizer->Update();
  EXPECT_TRUE(voxelizer->GetWroteInterfaces());
  vtkNew<vtkRefractaSurfaceSet> set;
  ASSERT_EQ(set->AddMediumInterfaces(voxelizer->GetOutput()), 1);
  ASSERT_TRUE(set->Build());
  EXPECT_EQ(set->GetNumberOfDielectricTriangles(), Ball(0.5)->GetNumberOfCells());
  EXPECT_EQ(set->GetMaterial(0)->GetIndexInside(), 1.5);
  EXPECT_EQ(set->GetMaterial(0)->GetIndexOutside(), 1.0);
}

TEST(MeshVoxelizerInterfaces, DensityIndexFallsBackAndBadArraysAreReported)
{
  vtkNew<vtkMeshVoxelizer> voxelizer;
  voxelizer->AddInputData(Ball(1.0));
  auto gas = Index(1.5);
  vtkNew<vtkSphere> density;
  density->SetRadius(2.0);
  gas->SetDensityFunction(density);
  gas->SetDensityScalesRefractiveIndex(true);
  voxelizer->SetMaterial(0, gas);
  voxelizer->SetDimensions(16, 16, 16);
  voxelizer->SetInterfaceModeToExactInterfaces();
  vtkNew<vtkTest::ErrorObserver> observer;
  voxelizer->AddObserver(vtkCommand::WarningEvent, observer);
  voxelizer->Update();
  EXPECT_FALSE(voxelizer->GetWroteInterfaces());
  EXPECT_TRUE(observer->GetWarning());
  vtkImageData* out = voxelizer->GetOutput();
  EXPECT_EQ(out->GetFieldData()->GetArray(vtkRefractaMedium::InterfaceTrianglesName()), nullptr);

  // Inconsistent arrays: an error naming them, nothing added.
  vtkNew<vtkImageData> bad;
  vtkNew<vtkDoubleArray> points;
  points->SetName(vtkRefractaMedium::InterfacePointsName());
  points->SetNumberOfComponents(3);
  points->InsertNextTuple3(0, 0, 0);
  bad->GetFieldData()->AddArray(points);
  vtkNew<vtkRefractaSurfaceSet> set;
  vtkNew<vtkTest::ErrorObserver> errors;
  set->AddObserver(vtkCommand::ErrorEvent, errors);
  EXPECT_EQ(set->AddMediumInterfaces(bad), -1);
  EXPECT_TRUE(errors->GetError());
  EXPECT_EQ(set->GetNumberOfSurfaces(), 0);
}
