// The default scene of refracta-render in preview quality (rendered by the RefractaRender.Default
// test with --preview, which this test depends on): the image matches its baseline
// (Testing/Baselines/DefaultScene.png), the HDR image is finite and non-negative, and the scene
// shows its caustic: the glass sphere focuses the spot light onto the floor, so the in-scattered
// radiance S1 on the floor's top under the sphere exceeds that at a floor point inside the spot's
// cone but away from the focus by more than 10x (measured 40x in preview quality, 150x at full
// quality; without refraction the sphere would only attenuate, ratio < 1).
#include "RenderingTestUtilities.h"

#include "vtkCamera.h"
#include "vtkRefractaImageRenderer.h"
#include "vtkRefractaLightingVolume.h"
#include "vtkUnsignedCharArray.h"
#include "vtkXMLImageDataReader.h"

#include <gtest/gtest.h>

#include <cmath>

namespace
{
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

  auto volume = Read("refracta_radiance.vti");
  vtkDataArray* radiance =
    volume->GetPointData()->GetArray(vtkRefractaLightingVolume::RadianceName());
  ASSERT_NE(radiance, nullptr);
  double focus[3] = { 0.0, -0.78, 0.0 }, aside[3] = { 0.6, -0.78, 0.0 };
  const double r0 = radiance->GetComponent(volume->FindPoint(focus), 0);
  const double r1 = radiance->GetComponent(volume->FindPoint(aside), 0);
  std::cout << "floor S1 under the sphere " << r0 << ", beside it " << r1 << "\n";
  EXPECT_GT(r0, 10 * r1);
  EXPECT_GT(r1, 0.0);
}
