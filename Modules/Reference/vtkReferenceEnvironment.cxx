#include "vtkReferenceEnvironment.h"

#include "vtkRefractaEnvironmentMap.h"

#include <algorithm>
#include <cmath>

namespace refracta
{
namespace reference
{
namespace
{
double Luminance(const double* rgb)
{
  return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
}

// Index k of the interval [cdf[k], cdf[k + 1]) holding x, for cdf of n + 1 increasing values
// with a positive last one; intervals of zero width are never returned.
int FindInterval(const double* cdf, int n, double x)
{
  const int k = static_cast<int>(std::upper_bound(cdf, cdf + n + 1, x) - cdf) - 1;
  int c = std::min(std::max(k, 0), n - 1);
  while (c > 0 && !(cdf[c + 1] > cdf[c]))
  {
    --c;
  }
  while (c < n - 1 && !(cdf[c + 1] > cdf[c]))
  {
    ++c;
  }
  return c;
}
} // namespace

Vec3 Environment::Radiance(const Vec3& dWorld) const
{
  if (W == 0)
  {
    return Colour;
  }
  const double d[3] = { dWorld.x, dWorld.y, dWorld.z };
  double uv[2], rgb[3];
  vtkRefractaEnvironmentMap::DirectionToTexture(d, Up, Right, uv);
  if (CheckerSquares[0] > 0)
  {
    vtkRefractaEnvironmentMap::EvaluateChecker(
      uv[0], uv[1], CheckerSquares, Checker1, Checker2, rgb);
  }
  else
  {
    vtkRefractaEnvironmentMap::Sample(Rgb.data(), W, H, uv[0], uv[1], rgb);
  }
  return ToVec3(rgb);
}

bool Environment::BuildSampling()
{
  if (W == 0)
  {
    return Colour.x > 0 || Colour.y > 0 || Colour.z > 0;
  }
  vtkRefractaEnvironmentMap::ComputeBasis(Up, Right, Basis, Basis + 3, Basis + 6);
  SinLat.resize(H + 1);
  for (int j = 0; j <= H; ++j)
  {
    SinLat[j] = std::sin((static_cast<double>(j) / H - 0.5) * Pi);
  }
  Weight.assign(static_cast<size_t>(W) * H, 0.0);
  for (int j = 0; j < H; ++j)
  {
    const double omega = 2 * Pi / W * (SinLat[j + 1] - SinLat[j]);
    for (int i = 0; i < W; ++i)
    {
      double y = 0;
      for (int dj = -1; dj <= 1; ++dj)
      {
        const int jj = std::min(std::max(j + dj, 0), H - 1);
        for (int di = -1; di <= 1; ++di)
        {
          const int ii = ((i + di) % W + W) % W;
          y = std::max(y, Luminance(&Rgb[3 * (static_cast<size_t>(jj) * W + ii)]));
        }
      }
      Weight[static_cast<size_t>(j) * W + i] = omega * y;
    }
  }
  RowCdf.assign(H + 1, 0.0);
  CellCdf.assign(static_cast<size_t>(H) * (W + 1), 0.0);
  for (int j = 0; j < H; ++j)
  {
    double* row = &CellCdf[static_cast<size_t>(j) * (W + 1)];
    for (int i = 0; i < W; ++i)
    {
      row[i + 1] = row[i] + Weight[static_cast<size_t>(j) * W + i];
    }
    RowCdf[j + 1] = RowCdf[j] + row[W];
  }
  return RowCdf[H] > 0;
}

Vec3 Environment::Sample(double u1, double u2, double u3, double u4) const
{
  if (W == 0)
  {
    const double z = 1 - 2 * u1, r = std::sqrt(std::max(0.0, 1 - z * z)), phi = 2 * Pi * u2;
    return Vec3(r * std::cos(phi), r * std::sin(phi), z);
  }
  const int j = FindInterval(RowCdf.data(), H, u1 * RowCdf[H]);
  const double* row = &CellCdf[static_cast<size_t>(j) * (W + 1)];
  const int i = FindInterval(row, W, u2 * row[W]);
  const double lon = ((i + u3) / W - 0.5) * 2 * Pi;
  const double y = SinLat[j] + u4 * (SinLat[j + 1] - SinLat[j]);
  const double c = std::sqrt(std::max(0.0, 1 - y * y));
  const double x = c * std::sin(lon), z = c * std::cos(lon);
  return Vec3(x * Basis[0] + y * Basis[3] + z * Basis[6],
    x * Basis[1] + y * Basis[4] + z * Basis[7], x * Basis[2] + y * Basis[5] + z * Basis[8]);
}

double Environment::Pdf(const Vec3& dWorld) const
{
  if (W == 0)
  {
    return 1 / (4 * Pi);
  }
  const double d[3] = { dWorld.x, dWorld.y, dWorld.z };
  double uv[2];
  vtkRefractaEnvironmentMap::DirectionToTexture(d, Up, Right, uv);
  const int i = std::min(std::max(static_cast<int>(uv[0] * W), 0), W - 1);
  const int j = std::min(std::max(static_cast<int>(uv[1] * H), 0), H - 1);
  const double omega = 2 * Pi / W * (SinLat[j + 1] - SinLat[j]);
  return Weight[static_cast<size_t>(j) * W + i] / (RowCdf[H] * omega);
}
} // namespace reference
} // namespace refracta
