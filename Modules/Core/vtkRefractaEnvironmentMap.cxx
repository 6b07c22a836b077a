#include "vtkRefractaEnvironmentMap.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"

#include <algorithm>
#include <cmath>
#include <sstream>

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
namespace
{
// Share of [a, b) (in units of squares along one axis) covered by odd-numbered squares.
double OddShare(double a, double b)
{
  // The odd squares' measure of [0, x): floor(x / 2) whole pairs plus the odd part of the last.
  auto odd = [](double x)
  {
    const double pairs = std::floor(x / 2.0);
    return pairs + std::min(std::max(x - 2.0 * pairs - 1.0, 0.0), 1.0);
  };
  return b > a ? (odd(b) - odd(a)) / (b - a) : 0.0;
}
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkImageData> vtkRefractaEnvironmentMap::MakeChecker(
  int squaresU, int squaresV, const double color1[3], const double color2[3])
{
  const int nu = std::min(std::max(squaresU, 1), 4096);
  const int nv = std::min(std::max(squaresV, 1), 4096);
  // 16 texels per square where that fits, so that texels rarely straddle an edge.
  const int w = std::min(std::max(nu * 16, 64), 4096);
  const int h = std::min(std::max(nv * 16, 32), 2048);
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(w, h, 1);
  vtkNew<vtkFloatArray> rgb;
  rgb->SetName("Checker");
  rgb->SetNumberOfComponents(3);
  rgb->SetNumberOfTuples(static_cast<vtkIdType>(w) * h);
  for (int j = 0; j < h; ++j)
  {
    // The parity is odd where exactly one of the two indices is odd: the texel's share of odd
    // squares is pu (1 - pv) + (1 - pu) pv, from the odd shares along each axis.
    const double pv = OddShare(double(j) * nv / h, double(j + 1) * nv / h);
    for (int i = 0; i < w; ++i)
    {
      const double pu = OddShare(double(i) * nu / w, double(i + 1) * nu / w);
      const double f1 = pu * (1.0 - pv) + (1.0 - pu) * pv;
      for (int c = 0; c < 3; ++c)
      {
        rgb->SetComponent(i + static_cast<vtkIdType>(w) * j, c,
          static_cast<float>(f1 * color1[c] + (1.0 - f1) * color2[c]));
      }
    }
  }
  image->GetPointData()->SetScalars(rgb);
  vtkNew<vtkIntArray> squares;
  squares->SetName(CheckerSquaresName());
  squares->SetNumberOfComponents(2);
  squares->InsertNextTuple2(nu, nv);
  vtkNew<vtkDoubleArray> colors;
  colors->SetName(CheckerColorsName());
  colors->SetNumberOfComponents(6);
  const double both[6] = { color1[0], color1[1], color1[2], color2[0], color2[1], color2[2] };
  colors->InsertNextTuple(both);
  image->GetFieldData()->AddArray(squares);
  image->GetFieldData()->AddArray(colors);
  return image;
}

//------------------------------------------------------------------------------
double vtkRefractaEnvironmentMap::NormalizingScale(vtkDataArray* scalars)
{
  const int type = scalars ? scalars->GetDataType() : VTK_VOID;
  return type == VTK_UNSIGNED_CHAR ? 1.0 / 255.0
                                   : (type == VTK_UNSIGNED_SHORT ? 1.0 / 65535.0 : 1.0);
}

//------------------------------------------------------------------------------
bool vtkRefractaEnvironmentMap::ReadRadiance(
  vtkImageData* image, std::vector<double>& rgb, int size[2], std::string& error)
{
  int dims[3] = { 0, 0, 0 };
  if (image)
  {
    image->GetDimensions(dims);
  }
  vtkDataArray* scalars = image ? image->GetPointData()->GetScalars() : nullptr;
  const int components = scalars ? scalars->GetNumberOfComponents() : 0;
  if (dims[0] < 1 || dims[1] < 1 || dims[2] != 1 || components < 1 || components > 4 ||
    scalars->GetNumberOfTuples() != static_cast<vtkIdType>(dims[0]) * dims[1])
  {
    std::ostringstream msg;
    msg << "The environment map must be a 2D vtkImageData (W x H x 1) with grey, grey + alpha, "
           "RGB or RGBA point scalars (1 to 4 components); got "
        << dims[0] << " x " << dims[1] << " x " << dims[2] << " with " << components
        << " scalar components.";
    error = msg.str();
    return false;
  }
  const double scale = NormalizingScale(scalars);
  const int colours = components < 3 ? 1 : 3; // grey (+ alpha): one value for R, G and B
  rgb.resize(3 * static_cast<size_t>(dims[0]) * dims[1]);
  for (vtkIdType t = 0; t < scalars->GetNumberOfTuples(); ++t)
  {
    for (int c = 0; c < 3; ++c)
    {
      const double v = scale * scalars->GetComponent(t, colours == 1 ? 0 : c);
      if (!std::isfinite(v) || v < 0)
      {
        std::ostringstream msg;
        msg << "The environment map's texel " << t << " (channel " << c << ") is " << v
            << "; its radiance must be finite and >= 0.";
        error = msg.str();
        return false;
      }
      rgb[3 * t + c] = v;
    }
  }
  size[0] = dims[0];
  size[1] = dims[1];
  return true;
}

//------------------------------------------------------------------------------
bool vtkRefractaEnvironmentMap::GetChecker(
  vtkImageData* map, int squares[2], double color1[3], double color2[3])
{
  vtkFieldData* fd = map ? map->GetFieldData() : nullptr;
  vtkDataArray* s = fd ? fd->GetArray(CheckerSquaresName()) : nullptr;
  vtkDataArray* c = fd ? fd->GetArray(CheckerColorsName()) : nullptr;
  if (!s || !c || s->GetNumberOfComponents() != 2 || s->GetNumberOfTuples() < 1 ||
    c->GetNumberOfComponents() != 6 || c->GetNumberOfTuples() < 1)
  {
    return false;
  }
  for (int a = 0; a < 2; ++a)
  {
    const double v = s->GetComponent(0, a);
    if (!(v >= 1 && v <= 4096))
    {
      return false;
    }
    squares[a] = static_cast<int>(v);
  }
  for (int k = 0; k < 6; ++k)
  {
    const double v = c->GetComponent(0, k);
    if (!std::isfinite(v))
    {
      return false;
    }
    (k < 3 ? color1 : color2)[k % 3] = std::max(v, 0.0);
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkRefractaEnvironmentMap::EvaluateChecker(double u, double v, const int squares[2],
  const double color1[3], const double color2[3], double rgb[3])
{
  const long long su = std::min<long long>(
    std::max<long long>(static_cast<long long>(std::floor(u * squares[0])), 0), squares[0] - 1);
  const long long sv = std::min<long long>(
    std::max<long long>(static_cast<long long>(std::floor(v * squares[1])), 0), squares[1] - 1);
  const double* c = ((su + sv) % 2) ? color1 : color2;
  std::copy(c, c + 3, rgb);
}

//------------------------------------------------------------------------------
void vtkRefractaEnvironmentMap::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Convention: VTK skybox equirectangular, front = up x right, "
     << "u = atan2(x, z) / 2pi + 1/2, v = atan2(y, |(x, z)|) / pi + 1/2\n";
}
