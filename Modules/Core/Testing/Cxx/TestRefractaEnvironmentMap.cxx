// vtkRefractaEnvironmentMap: VTK's skybox convention (front = up x right, u = 0.5 at front).
#include "vtkMath.h"
#include "vtkRefractaEnvironmentMap.h"

#include <gtest/gtest.h>

#include <cmath>
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
