#include "vtkRefractaEnvironmentMap.h"

#include "vtkMath.h"
#include "vtkObjectFactory.h"

#include <algorithm>
#include <cmath>

vtkStandardNewMacro(vtkRefractaEnvironmentMap);

//------------------------------------------------------------------------------
bool vtkRefractaEnvironmentMap::ComputeBasis(
  const double up[3], const double rightHint[3], double right[3], double upOut[3], double front[3])
{
  double u[3] = { up[0], up[1], up[2] };
  double r[3] = { rightHint[0], rightHint[1], rightHint[2] };
  bool ok = vtkMath::Normalize(u) > 0.0;
  if (ok)
  {
    const double along = vtkMath::Dot(r, u);
    for (int a = 0; a < 3; ++a)
    {
      r[a] -= along * u[a];
    }
    ok = vtkMath::Normalize(r) > 1e-12;
  }
  if (!ok)
  {
    u[0] = 0, u[1] = 1, u[2] = 0;
    r[0] = 1, r[1] = 0, r[2] = 0;
  }
  std::copy(u, u + 3, upOut);
  std::copy(r, r + 3, right);
  vtkMath::Cross(u, r, front);
  return ok;
}

//------------------------------------------------------------------------------
void vtkRefractaEnvironmentMap::DirectionToTexture(
  const double d[3], const double up[3], const double rightHint[3], double uv[2])
{
  double right[3], u[3], front[3];
  ComputeBasis(up, rightHint, right, u, front);
  const double x = vtkMath::Dot(d, right), y = vtkMath::Dot(d, u), z = vtkMath::Dot(d, front);
  double s = std::atan2(x, z) / (2.0 * vtkMath::Pi()) + 0.5;
  if (s >= 1.0)
  {
    s -= 1.0;
  }
  uv[0] = s;
  uv[1] = std::atan2(y, std::sqrt(x * x + z * z)) / vtkMath::Pi() + 0.5;
}

//------------------------------------------------------------------------------
void vtkRefractaEnvironmentMap::DirectionToTexture(const double d[3], double uv[2])
{
  const double up[3] = { 0, 1, 0 }, right[3] = { 1, 0, 0 };
  DirectionToTexture(d, up, right, uv);
}

//------------------------------------------------------------------------------
void vtkRefractaEnvironmentMap::TextureToDirection(
  const double uv[2], const double up[3], const double rightHint[3], double d[3])
{
  double right[3], u[3], front[3];
  ComputeBasis(up, rightHint, right, u, front);
  const double lon = (uv[0] - 0.5) * 2.0 * vtkMath::Pi();
  const double lat = (uv[1] - 0.5) * vtkMath::Pi();
  const double x = std::cos(lat) * std::sin(lon), y = std::sin(lat);
  const double z = std::cos(lat) * std::cos(lon);
  for (int a = 0; a < 3; ++a)
  {
    d[a] = x * right[a] + y * u[a] + z * front[a];
  }
}

//------------------------------------------------------------------------------
void vtkRefractaEnvironmentMap::Sample(
  const double* rgb, int width, int height, double u, double v, double out[3])
{
  const double fx = u * width - 0.5;
  const double fy = std::min(std::max(v * height - 0.5, 0.0), height - 1.0);
  const double x0f = std::floor(fx), y0f = std::floor(fy);
  const double tx = fx - x0f, ty = fy - y0f;
  auto wrap = [width](long long i) { return static_cast<int>(((i % width) + width) % width); };
  const int x0 = wrap(static_cast<long long>(x0f)), x1 = wrap(static_cast<long long>(x0f) + 1);
  const int y0 = static_cast<int>(y0f), y1 = std::min(y0 + 1, height - 1);
  for (int c = 0; c < 3; ++c)
  {
    const double a = rgb[3 * (y0 * width + x0) + c], b = rgb[3 * (y0 * width + x1) + c];
    const double e = rgb[3 * (y1 * width + x0) + c], f = rgb[3 * (y1 * width + x1) + c];
    out[c] = (1 - ty) * ((1 - tx) * a + tx * b) + ty * ((1 - tx) * e + tx * f);
  }
}

//------------------------------------------------------------------------------
int vtkRefractaEnvironmentMap::NearestTexel(int width, int height, double u, double v)
{
  long long i = static_cast<long long>(std::floor(u * width));
  i = ((i % width) + width) % width;
  const int j = std::min(std::max(static_cast<int>(std::floor(v * height)), 0), height - 1);
  return static_cast<int>(i) + width * j;
}

//------------------------------------------------------------------------------
void vtkRefractaEnvironmentMap::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Convention: VTK skybox equirectangular, front = up x right, "
     << "u = atan2(x, z) / 2pi + 1/2, v = atan2(y, |(x, z)|) / pi + 1/2\n";
}
