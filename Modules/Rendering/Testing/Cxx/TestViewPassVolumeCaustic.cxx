// The volume caustic in the view pass (vtkRefractaLightingVolume::VolumeCaustic*Name(),
// Kernels/view_pass.cl refracta_view_volume_caustic, Documentation/Physics.md "Volume caustics").
//
// - Sub-voxel resolution, exact: one brick (c = 2) whose fine column (0, 0) holds S1 = H and whose
//   other fine voxels hold 0, seen along z by a parallel camera whose 4 x 4 pixels tile the
//   brick's voxel. The brick is trilinear over its fine voxels, clamped at its faces, so pixel
//   (i, j) sees H w_i w_j with w = (1, 3/4, 1/4, 0) laterally; every ray has the same path along
//   z, so pixel (i, j) / pixel (0, 0) = w_i w_j exactly (to float rounding), and pixel (0, 0) is
//   H / (4 pi) times the path through the voxel (0.25) within 10% (attenuation and the step's
//   midpoint rule). The same light in Radiance instead (the voxel holding the brick's mean) is
//   spread over the pixels.
// - Bad volume-caustic arrays are errors naming the array and what is valid; the lighting volume
//   without them renders as before (the variant without the caustic is compiled).
#include "RenderingTestUtilities.h"

#include "vtkCamera.h"
#include "vtkFieldData.h"
#include "vtkIntArray.h"
#include "vtkMath.h"
#include "vtkRefractaImageRenderer.h"
#include "vtkRefractaLightingVolume.h"
#include "vtkRefractaViewPass.h"
#include "vtkTestErrorObserver.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>

namespace
{
const int C = 2;         // the bricks' subdivision in these tests
const double H = 3.0;    // S1 of the hot fine column
const double Sigma = 0.01; // a thin medium: nearly the plain path length
const int Hot = 1 + 4 * (1 + 4 * 1); // voxel (1, 1, 1) of the 4^3 grid

// A 4^3 grid of spacing 0.25 with sigma_t = Sigma, g = 0, and a lighting volume whose S1 is zero
// except in voxel (1, 1, 1): either its brick's fine column (0, 0) at H (`brick`) or, in
// Radiance, that brick's mean H / 4.
struct Scene
{
  vtkSmartPointer<vtkImageData> Medium = refracta_test::MakeGrid(4, 4, 4, 0.25);
  vtkSmartPointer<vtkImageData> Lighting = vtkSmartPointer<vtkImageData>::New();

  explicit Scene(bool brick)
  {
    refracta_test::AddConstant(this->Medium, "Extinction", 3, Sigma, Sigma, Sigma);
    this->Lighting->CopyStructure(this->Medium);
    vtkFloatArray* s1 =
      refracta_test::AddConstant(this->Lighting, vtkRefractaLightingVolume::RadianceName(), 3, 0);
    refracta_test::AddConstant(
      this->Lighting, vtkRefractaLightingVolume::RadianceDirectionName(), 3, 0, 0, 1);
    if (!brick)
    {
      const double mean = H / 4; // 2 of the brick's 8 fine voxels hold H
      s1->SetTuple3(Hot, mean, mean, mean);
      return;
    }
    vtkNew<vtkIntArray> bricks;
    bricks->SetName(vtkRefractaLightingVolume::VolumeCausticBricksName());
    bricks->SetNumberOfTuples(64);
    bricks->Fill(-1);
    bricks->SetValue(Hot, 0);
    vtkNew<vtkFloatArray> fine, direction;
    fine->SetName(vtkRefractaLightingVolume::VolumeCausticRadianceName());
    direction->SetName(vtkRefractaLightingVolume::VolumeCausticRadianceDirectionName());
    for (vtkFloatArray* a : { fine.Get(), direction.Get() })
    {
      a->SetNumberOfComponents(3);
      a->SetNumberOfTuples(C * C * C);
    }
    for (int k = 0; k < C; ++k)
    {
      const int column = k * C * C; // fine voxel (0, 0, k)
      for (int f = 0; f < C * C; ++f)
      {
        const double value = f == 0 ? H : 0.0;
        fine->SetTuple3(column + f, value, value, value);
        direction->SetTuple3(column + f, 0, 0, 1);
      }
    }
    this->Lighting->GetFieldData()->AddArray(bricks);
    this->Lighting->GetFieldData()->AddArray(fine);
    this->Lighting->GetFieldData()->AddArray(direction);
  }

  // The 4 x 4 image of the voxel (1, 1, 1) seen along -z (parallel rays), red channel.
  std::vector<double> Render()
  {
    vtkNew<vtkCamera> camera;
    camera->ParallelProjectionOn();
    camera->SetFocalPoint(0.25, 0.25, 0.25);
    camera->SetPosition(0.25, 0.25, 5.0);
    camera->SetViewUp(0, 1, 0);
    camera->SetParallelScale(0.125);
    vtkNew<vtkRefractaImageRenderer> renderer;
    renderer->SetInputData(this->Medium);
    renderer->SetLightingData(this->Lighting);
    renderer->SetCamera(camera);
    renderer->SetImageSize(4, 4);
    renderer->SetStepSize(0.1);
    renderer->SetTransmittanceCutoff(0.0);
    renderer->Update();
    auto* hdr = vtkFloatArray::SafeDownCast(renderer->GetOutput()->GetPointData()->GetArray("HDR"));
    std::vector<double> red;
    for (vtkIdType p = 0; hdr && p < 16; ++p)
    {
      red.push_back(hdr->GetValue(4 * p));
    }
    return red;
  }
};
}

TEST(ViewPassVolumeCaustic, BrickResolvesItsVoxel)
{
  Scene scene(true);
  const std::vector<double> image = scene.Render();
  ASSERT_EQ(image.size(), 16u);
  const double w[4] = { 1.0, 0.75, 0.25, 0.0 };
  const double corner = image[0];
  EXPECT_NEAR(corner, H / (4 * vtkMath::Pi()) * 0.25, 0.1 * H / (4 * vtkMath::Pi()) * 0.25);
  for (int j = 0; j < 4; ++j)
  {
    for (int i = 0; i < 4; ++i)
    {
      EXPECT_NEAR(image[i + 4 * j] / corner, w[i] * w[j], 1e-5) << "pixel " << i << ", " << j;
    }
  }
  // The same light in Radiance: the voxel's mean, spread over all 16 pixels (each sees some of
  // it) instead of concentrated in the corner.
  Scene coarse(false);
  const std::vector<double> spread = coarse.Render();
  ASSERT_EQ(spread.size(), 16u);
  for (double value : spread)
  {
    EXPECT_GT(value, 0.0);
    EXPECT_LT(value, 0.5 * corner);
  }
}

TEST(ViewPassVolumeCaustic, RejectsBadArrays)
{
  using Edit = std::function<void(vtkFieldData*)>;
  const std::pair<const char*, Edit> cases[] = {
    { vtkRefractaLightingVolume::VolumeCausticRadianceDirectionName(),
      [](vtkFieldData* fd)
      { fd->RemoveArray(vtkRefractaLightingVolume::VolumeCausticRadianceDirectionName()); } },
    { vtkRefractaLightingVolume::VolumeCausticBricksName(),
      [](vtkFieldData* fd)
      {
        fd->GetArray(vtkRefractaLightingVolume::VolumeCausticBricksName())->SetTuple1(3, -2);
      } },
    { vtkRefractaLightingVolume::VolumeCausticBricksName(),
      [](vtkFieldData* fd)
      { fd->GetArray(vtkRefractaLightingVolume::VolumeCausticBricksName())->SetNumberOfTuples(63); } },
    { vtkRefractaLightingVolume::VolumeCausticRadianceName(),
      [](vtkFieldData* fd)
      {
        fd->GetArray(vtkRefractaLightingVolume::VolumeCausticRadianceName())->SetNumberOfTuples(7);
      } },
    { vtkRefractaLightingVolume::VolumeCausticRadianceName(),
      [](vtkFieldData* fd)
      {
        fd->GetArray(vtkRefractaLightingVolume::VolumeCausticRadianceName())
          ->SetTuple3(2, -1.0, 0.0, 0.0);
      } },
    { vtkRefractaLightingVolume::VolumeCausticRadianceDirectionName(),
      [](vtkFieldData* fd)
      {
        fd->GetArray(vtkRefractaLightingVolume::VolumeCausticRadianceDirectionName())
          ->SetTuple3(1, std::nan(""), 0.0, 0.0);
      } },
  };
  for (const auto& bad : cases)
  {
    Scene scene(true);
    bad.second(scene.Lighting->GetFieldData());
    vtkNew<vtkRefractaViewPass> view;
    vtkNew<vtkTest::ErrorObserver> errors;
    view->AddObserver(vtkCommand::ErrorEvent, errors);
    ASSERT_TRUE(view->SetMedium(scene.Medium));
    EXPECT_FALSE(view->SetLighting(scene.Lighting)) << bad.first;
    EXPECT_NE(errors->GetErrorMessage().find(bad.first), std::string::npos)
      << errors->GetErrorMessage();
    EXPECT_EQ(view->GetLightingVolumeCausticSubdivision(), 1);
  }
  // Without the arrays: no volume caustic, no error.
  Scene plain(false);
  vtkNew<vtkRefractaViewPass> view;
  ASSERT_TRUE(view->SetMedium(plain.Medium));
  EXPECT_TRUE(view->SetLighting(plain.Lighting));
  EXPECT_EQ(view->GetLightingVolumeCausticSubdivision(), 1);
  Scene brick(true);
  EXPECT_TRUE(view->SetLighting(brick.Lighting));
  EXPECT_EQ(view->GetLightingVolumeCausticSubdivision(), C);
}
