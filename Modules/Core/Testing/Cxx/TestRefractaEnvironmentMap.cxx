// vtkRefractaEnvironmentMap: VTK's skybox convention (front = up x right, u = 0.5 at front).
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkMath.h"
#include "vtkPointData.h"
#include "vtkRefractaEnvironmentMap.h"
#include "vtkSmartPointer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

TEST(RefractaEnvironmentMap, DefaultConvention)
{
  struct Case
  {
    double D[3];
    double U, V;
  };
  // Defaults: up +y, right +x, front = up x right = -z.
  const Case cases[] = { { { 0, 0, -1 }, 0.5, 0.5 }, { { 1, 0, 0 }, 0.75, 0.5 },
    { { -1, 0, 0 }, 0.25, 0.5 }, { { 0, 0, 1 }, 0.0, 0.5 }, { { 1, 1, 0 }, 0.75, 0.75 },
    { { 0, -1, 0 }, 0.5, 0.0 } };
  for (const Case& c : cases)
  {
    double uv[2];
    vtkRefractaEnvironmentMap::DirectionToTexture(c.D, uv);
    EXPECT_NEAR(uv[0], c.U, 1e-12) << c.D[0] << "," << c.D[1] << "," << c.D[2];
    EXPECT_NEAR(uv[1], c.V, 1e-12) << c.D[0] << "," << c.D[1] << "," << c.D[2];
    EXPECT_GE(uv[0], 0.0);
    EXPECT_LT(uv[0], 1.0);
  }
}

TEST(RefractaEnvironmentMap, RoundTripAndCustomBasis)
{
  const double up[3] = { 0, 0, 2 }, right[3] = { 1, 1, 0.3 }; // not unit, not orthogonal
  for (double u = 0.03; u < 1; u += 0.11)
  {
    for (double v = 0.05; v < 1; v += 0.13)
    {
      const double uv[2] = { u, v };
      double d[3], back[2];
      vtkRefractaEnvironmentMap::TextureToDirection(uv, up, right, d);
      EXPECT_NEAR(vtkMath::Norm(d), 1.0, 1e-12);
      vtkRefractaEnvironmentMap::DirectionToTexture(d, up, right, back);
      EXPECT_NEAR(back[0], u, 1e-12);
      EXPECT_NEAR(back[1], v, 1e-12);
    }
  }
  // Up is +z: the +z pole is v = 1.
  const double z[3] = { 0, 0, 1 };
  double uv[2];
  vtkRefractaEnvironmentMap::DirectionToTexture(z, up, right, uv);
  EXPECT_NEAR(uv[1], 1.0, 1e-12);
}

TEST(RefractaEnvironmentMap, SampleAndNearestTexel)
{
  const int w = 8, h = 4;
  std::vector<double> rgb(3 * w * h);
  for (int i = 0; i < w * h; ++i)
  {
    rgb[3 * i] = i;
    rgb[3 * i + 1] = 2 * i;
    rgb[3 * i + 2] = 0;
  }
  double out[3];
  // Texel centre (i + 0.5) / w, (j + 0.5) / h returns the texel.
  vtkRefractaEnvironmentMap::Sample(rgb.data(), w, h, 2.5 / w, 1.5 / h, out);
  EXPECT_NEAR(out[0], 2 + w * 1, 1e-12);
  EXPECT_EQ(vtkRefractaEnvironmentMap::NearestTexel(w, h, 2.5 / w, 1.5 / h), 2 + w * 1);
  // Wraps in u: halfway between the last and the first texel.
  vtkRefractaEnvironmentMap::Sample(rgb.data(), w, h, 0.0, 0.5 / h, out);
  EXPECT_NEAR(out[0], 0.5 * (w - 1 + 0), 1e-12);
}

// ReadRadiance, the one conversion of an environment image: 8- and 16-bit integers normalised as
// VTK's textures read them (a 16-bit PNG was taken as radiance 0..65535: a white image), grey and
// grey + alpha images spread over R, G and B (they were refused, after the light passes had run),
// other types as stored; a wrong shape and a negative or non-finite texel refused with the reason.
TEST(RefractaEnvironmentMap, ReadRadianceNormalisesAndExpands)
{
  auto image = [](int type, int components, std::vector<double> values)
  {
    auto map = vtkSmartPointer<vtkImageData>::New();
    map->SetDimensions(static_cast<int>(values.size()) / components, 1, 1);
    vtkSmartPointer<vtkDataArray> scalars;
    scalars.TakeReference(vtkDataArray::CreateDataArray(type));
    scalars->SetNumberOfComponents(components);
    scalars->SetNumberOfTuples(static_cast<vtkIdType>(values.size()) / components);
    for (size_t v = 0; v < values.size(); ++v)
    {
      scalars->SetComponent(static_cast<vtkIdType>(v) / components, v % components, values[v]);
    }
    map->GetPointData()->SetScalars(scalars);
    return map;
  };
  std::vector<double> rgb;
  int size[2];
  std::string error;
  ASSERT_TRUE(vtkRefractaEnvironmentMap::ReadRadiance(
    image(VTK_UNSIGNED_SHORT, 3, { 65535, 0, 32768 }), rgb, size, error))
    << error;
  EXPECT_EQ(size[0], 1);
  EXPECT_NEAR(rgb[0], 1.0, 1e-12);
  EXPECT_NEAR(rgb[2], 32768.0 / 65535.0, 1e-12);
  ASSERT_TRUE(vtkRefractaEnvironmentMap::ReadRadiance(
    image(VTK_UNSIGNED_CHAR, 4, { 255, 51, 0, 128 }), rgb, size, error));
  EXPECT_NEAR(rgb[1], 0.2, 1e-12);
  ASSERT_TRUE(vtkRefractaEnvironmentMap::ReadRadiance(
    image(VTK_UNSIGNED_CHAR, 2, { 51, 255, 102, 0 }), rgb, size, error));
  ASSERT_EQ(size[0], 2);
  const std::vector<double> grey = { 0.2, 0.2, 0.2, 0.4, 0.4, 0.4 };
  for (size_t k = 0; k < grey.size(); ++k)
  {
    EXPECT_NEAR(rgb[k], grey[k], 1e-12) << k;
  }
  ASSERT_TRUE(
    vtkRefractaEnvironmentMap::ReadRadiance(image(VTK_FLOAT, 1, { 7.5 }), rgb, size, error));
  EXPECT_EQ(rgb[2], 7.5);

  EXPECT_FALSE(
    vtkRefractaEnvironmentMap::ReadRadiance(image(VTK_FLOAT, 3, { 1, -1, 0 }), rgb, size, error));
  EXPECT_NE(error.find("texel 0 (channel 1) is -1"), std::string::npos) << error;
  auto volume = vtkSmartPointer<vtkImageData>::New();
  volume->SetDimensions(2, 2, 2);
  volume->AllocateScalars(VTK_FLOAT, 3);
  EXPECT_FALSE(vtkRefractaEnvironmentMap::ReadRadiance(volume, rgb, size, error));
  EXPECT_NE(error.find("2 x 2 x 2"), std::string::npos) << error;
  EXPECT_FALSE(vtkRefractaEnvironmentMap::ReadRadiance(nullptr, rgb, size, error));
}
