// The default scene of refracta-render in preview quality (rendered by the RefractaRender.Default
// test with --preview, which this test depends on): the image matches its baseline
// (Testing/Baselines/DefaultScene.png), the HDR image is finite and non-negative, and the image
// shows the caustic on the floor (an opaque plane surface at y = -0.8): the glass sphere focuses
// the spot light onto it, so the radiance of the pixels where the camera sees the floor under the
// sphere exceeds that where it sees the floor inside the spot's cone but away from the focus
// (x = 0.6) by more than CausticRatio (see below; without refraction the sphere would only cast a
// shadow there, ratio < 1).
#include "RenderingTestUtilities.h"

#include "vtkCamera.h"
#include "vtkMatrix4x4.h"
#include "vtkXMLImageDataReader.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace
{
// Measured 49x in preview quality with exact interfaces (123x with the smoothed index, whose
// graded blob focused nearer the floor; the brightest pixel of 3 x 3 at each point).
const double CausticRatio = 10.0;

vtkSmartPointer<vtkImageData> Read(const std::string& name)
{
  vtkNew<vtkXMLImageDataReader> reader;
  const std::string file = refracta_test::EnvOr("REFRACTA_TEST_OUTPUT_DIR", ".") + "/" + name;
  reader->SetFileName(file.c_str());
  reader->Update();
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->ShallowCopy(reader->GetOutput());
  return image;
}
}

TEST(DefaultScene, ImageAndCaustic)
{
  auto hdrImage = Read("refracta_hdr.vti");
  ASSERT_EQ(hdrImage->GetNumberOfPoints(), 128 * 128); // --preview: half of 256 x 256
  hdrImage->GetPointData()->SetActiveScalars("RGB");
  EXPECT_TRUE(refracta_test::MatchesBaseline(hdrImage, "DefaultScene", 15));
  vtkDataArray* hdr = hdrImage->GetPointData()->GetArray("HDR");
  ASSERT_NE(hdr, nullptr);
  for (vtkIdType i = 0; i < hdr->GetNumberOfValues(); ++i)
  {
    const double v = hdr->GetVariantValue(i).ToDouble();
    ASSERT_TRUE(std::isfinite(v) && v >= 0) << "HDR value " << i << " is " << v;
  }

  // The floor points under the sphere and beside it, projected with the default scene's camera
  // (128 x 128 preview), each the brightest HDR luminance within 1 pixel.
  vtkNew<vtkCamera> camera;
  camera->SetPosition(0.0, 0.55, 3.2);
  camera->SetFocalPoint(0.0, -0.1, 0.0);
  camera->SetViewUp(0, 1, 0);
  camera->SetViewAngle(34);
  vtkMatrix4x4* projection = camera->GetCompositeProjectionTransformMatrix(1.0, -1, 1);
  auto floorLuminance = [&](double x, double z)
  {
    double p[4] = { x, -0.8, z, 1.0 }, ndc[4];
    projection->MultiplyPoint(p, ndc);
    const int i0 = static_cast<int>((ndc[0] / ndc[3] + 1) * 64),
              j0 = static_cast<int>((ndc[1] / ndc[3] + 1) * 64);
    double best = 0;
    for (int j = j0 - 1; j <= j0 + 1; ++j)
    {
      for (int i = i0 - 1; i <= i0 + 1; ++i)
      {
        double rgba[4];
        hdr->GetTuple(i + 128 * j, rgba);
        best = std::max(best, 0.2126 * rgba[0] + 0.7152 * rgba[1] + 0.0722 * rgba[2]);
      }
    }
    return best;
  };
  const double caustic = floorLuminance(0.0, 0.0), beside = floorLuminance(0.6, 0.0);
  std::cout << "floor radiance under the sphere " << caustic << ", beside it " << beside << "\n";
  EXPECT_GT(caustic, CausticRatio * beside);
  EXPECT_GT(beside, 0.0);
}
