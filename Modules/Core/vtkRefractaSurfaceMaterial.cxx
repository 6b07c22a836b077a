#include "vtkRefractaSurfaceMaterial.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkMediumMaterial.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkRefractaMedium.h"
#include "vtkRefractaSettings.h"

#include <algorithm>
#include <cmath>

vtkStandardNewMacro(vtkRefractaSurfaceMaterial);
vtkRefractaCxxSetClampMacro(
  vtkRefractaSurfaceMaterial, IndexInside, 1.0, vtkRefractaMedium::MaximumRefractiveIndex);
vtkRefractaCxxSetClampMacro(
  vtkRefractaSurfaceMaterial, IndexOutside, 1.0, vtkRefractaMedium::MaximumRefractiveIndex);
vtkRefractaCxxSetClampMacro(vtkRefractaSurfaceMaterial, InsideAnisotropy, -0.9999, 0.9999);

//------------------------------------------------------------------------------
// Colours clamp to [0, 1], coefficients to [0, vtkMediumMaterial::MaximumCoefficient]; a NaN or
// infinite component is an error naming the setter that keeps the value (vtkRefractaSettings).
void vtkRefractaSurfaceMaterial::SetColor(
  const char* name, double target[3], double r, double g, double b)
{
  const double value[3] = { r, g, b };
  if (vtkRefractaSettings::SetClamped3(this, name, target, value, 0.0, 1.0))
  {
    this->Modified();
  }
}

void vtkRefractaSurfaceMaterial::SetNonNegative(
  const char* name, double target[3], double r, double g, double b)
{
  const double value[3] = { r, g, b };
  if (vtkRefractaSettings::SetClamped3(
        this, name, target, value, 0.0, vtkMediumMaterial::MaximumCoefficient))
  {
    this->Modified();
  }
}

void vtkRefractaSurfaceMaterial::SetInsideExtinction(double r, double g, double b)
{
  this->SetNonNegative("InsideExtinction", this->InsideExtinction, r, g, b);
}

void vtkRefractaSurfaceMaterial::SetInsideAlbedo(double r, double g, double b)
{
  this->SetColor("InsideAlbedo", this->InsideAlbedo, r, g, b);
}

void vtkRefractaSurfaceMaterial::SetInsideEmission(double r, double g, double b)
{
  this->SetNonNegative("InsideEmission", this->InsideEmission, r, g, b);
}

//------------------------------------------------------------------------------
void vtkRefractaSurfaceMaterial::SetAlbedo(double r, double g, double b)
{
  this->SetColor("Albedo", this->Albedo, r, g, b);
}

//------------------------------------------------------------------------------
void vtkRefractaSurfaceMaterial::SetCheckerColor1(double r, double g, double b)
{
  this->SetColor("CheckerColor1", this->CheckerColor1, r, g, b);
}

//------------------------------------------------------------------------------
void vtkRefractaSurfaceMaterial::SetCheckerColor2(double r, double g, double b)
{
  this->SetColor("CheckerColor2", this->CheckerColor2, r, g, b);
}

//------------------------------------------------------------------------------
void vtkRefractaSurfaceMaterial::SetCheckerSquares(int u, int v)
{
  u = std::max(1, std::min(u, 4096));
  v = std::max(1, std::min(v, 4096));
  if (u != this->CheckerSquares[0] || v != this->CheckerSquares[1])
  {
    this->CheckerSquares[0] = u;
    this->CheckerSquares[1] = v;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkRefractaSurfaceMaterial::EvaluateChecker(double u, double v, double rgb[3]) const
{
  const long long i = static_cast<long long>(std::floor(u * this->CheckerSquares[0]));
  const long long j = static_cast<long long>(std::floor(v * this->CheckerSquares[1]));
  const double* color = ((i + j) % 2 == 0) ? this->CheckerColor1 : this->CheckerColor2;
  std::copy(color, color + 3, rgb);
}

vtkRefractaSurfaceMaterial::vtkRefractaSurfaceMaterial() = default;
vtkRefractaSurfaceMaterial::~vtkRefractaSurfaceMaterial() = default;

//------------------------------------------------------------------------------
void vtkRefractaSurfaceMaterial::SetTexture(vtkImageData* image)
{
  if (this->Texture != image)
  {
    this->Texture = image;
    this->Modified();
  }
}

vtkImageData* vtkRefractaSurfaceMaterial::GetTexture() const
{
  return this->Texture;
}

vtkMTimeType vtkRefractaSurfaceMaterial::GetMTime()
{
  const vtkMTimeType own = this->Superclass::GetMTime();
  return this->Texture ? std::max(own, this->Texture->GetMTime()) : own;
}

namespace
{
// Texture coordinate t (in pixels, pixel centres at i + 0.5) -> pixel index in [0, n), wrapped
// (repeat) or clamped.
int TexturePixel(long long i, int n, bool repeat)
{
  if (repeat)
  {
    const long long m = i % n;
    return static_cast<int>(m < 0 ? m + n : m);
  }
  return static_cast<int>(std::min<long long>(std::max<long long>(i, 0), n - 1));
}

// The colour of pixel (i, j) of `scalars` (an image `width` wide), in [0, 1].
void TexturePixelColour(vtkDataArray* scalars, int width, int i, int j, double rgb[3])
{
  const vtkIdType p = i + static_cast<vtkIdType>(width) * j;
  const int nc = scalars->GetNumberOfComponents();
  const double scale = scalars->GetDataType() == VTK_UNSIGNED_CHAR ? 1.0 / 255.0 : 1.0;
  for (int c = 0; c < 3; ++c)
  {
    const double v = scalars->GetComponent(p, nc >= 3 ? c : 0) * scale;
    rgb[c] = v >= 0.0 ? std::min(v, 1.0) : 0.0;
  }
}
}

bool vtkRefractaSurfaceMaterial::HasUsableTexture() const
{
  vtkImageData* image = this->Texture;
  vtkDataArray* scalars = image ? image->GetPointData()->GetScalars() : nullptr;
  int dims[3] = { 0, 0, 0 };
  if (image)
  {
    image->GetDimensions(dims);
  }
  return scalars && dims[0] >= 1 && dims[1] >= 1 && dims[2] == 1 &&
    scalars->GetNumberOfTuples() == static_cast<vtkIdType>(dims[0]) * dims[1] &&
    scalars->GetNumberOfComponents() <= 4;
}

bool vtkRefractaSurfaceMaterial::EvaluateTexture(double u, double v, double rgb[3]) const
{
  if (!this->HasUsableTexture() || !std::isfinite(u) || !std::isfinite(v))
  {
    return false;
  }
  vtkDataArray* scalars = this->Texture->GetPointData()->GetScalars();
  int dims[3];
  this->Texture->GetDimensions(dims);
  const double x = u * dims[0], y = v * dims[1]; // in pixels
  if (!this->TextureInterpolate)
  {
    TexturePixelColour(scalars, dims[0],
      TexturePixel(static_cast<long long>(std::floor(x)), dims[0], this->TextureRepeat),
      TexturePixel(static_cast<long long>(std::floor(y)), dims[1], this->TextureRepeat), rgb);
    return true;
  }
  // Bilinear between the four pixel centres around (x, y).
  const double fx = x - 0.5, fy = y - 0.5;
  const long long i0 = static_cast<long long>(std::floor(fx)),
                  j0 = static_cast<long long>(std::floor(fy));
  const double wx = fx - i0, wy = fy - j0;
  rgb[0] = rgb[1] = rgb[2] = 0.0;
  for (int dj = 0; dj < 2; ++dj)
  {
    for (int di = 0; di < 2; ++di)
    {
      double c[3];
      TexturePixelColour(scalars, dims[0], TexturePixel(i0 + di, dims[0], this->TextureRepeat),
        TexturePixel(j0 + dj, dims[1], this->TextureRepeat), c);
      const double w = (di ? wx : 1.0 - wx) * (dj ? wy : 1.0 - wy);
      for (int k = 0; k < 3; ++k)
      {
        rgb[k] += w * c[k];
      }
    }
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkRefractaSurfaceMaterial::DeepCopy(vtkRefractaSurfaceMaterial* other)
{
  if (!other)
  {
    return;
  }
  this->SetAlbedo(other->Albedo);
  this->SetUseChecker(other->UseChecker);
  this->SetCheckerSquares(other->CheckerSquares);
  this->SetCheckerColor1(other->CheckerColor1);
  this->SetCheckerColor2(other->CheckerColor2);
  this->SetUseScalarColors(other->UseScalarColors);
  this->SetKind(other->Kind);
  this->SetIndexInside(other->IndexInside);
  this->SetIndexOutside(other->IndexOutside);
  this->SetSmoothNormals(other->SmoothNormals);
  this->SetUseInsideMedium(other->UseInsideMedium);
  this->SetInsideExtinction(other->InsideExtinction);
  this->SetInsideAlbedo(other->InsideAlbedo);
  this->SetInsideAnisotropy(other->InsideAnisotropy);
  this->SetInsideEmission(other->InsideEmission);
  this->SetTexture(other->Texture);
  this->SetTextureRepeat(other->TextureRepeat);
  this->SetTextureInterpolate(other->TextureInterpolate);
}

//------------------------------------------------------------------------------
void vtkRefractaSurfaceMaterial::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Albedo: (" << this->Albedo[0] << ", " << this->Albedo[1] << ", "
     << this->Albedo[2] << ")\n";
  os << indent << "UseChecker: " << this->UseChecker << "\n";
  os << indent << "CheckerSquares: (" << this->CheckerSquares[0] << ", " << this->CheckerSquares[1]
     << ")\n";
  os << indent << "CheckerColor1: (" << this->CheckerColor1[0] << ", " << this->CheckerColor1[1]
     << ", " << this->CheckerColor1[2] << ")\n";
  os << indent << "CheckerColor2: (" << this->CheckerColor2[0] << ", " << this->CheckerColor2[1]
     << ", " << this->CheckerColor2[2] << ")\n";
  os << indent << "UseScalarColors: " << this->UseScalarColors << "\n";
  os << indent << "Texture: " << static_cast<void*>(this->Texture.Get()) << "\n";
  os << indent << "TextureRepeat: " << this->TextureRepeat << "\n";
  os << indent << "TextureInterpolate: " << this->TextureInterpolate << "\n";
  os << indent << "Kind: " << (this->Kind == DIELECTRIC ? "DIELECTRIC" : "LAMBERTIAN") << "\n";
  os << indent << "IndexInside: " << this->IndexInside << "\n";
  os << indent << "IndexOutside: " << this->IndexOutside << "\n";
  os << indent << "SmoothNormals: " << this->SmoothNormals << "\n";
  os << indent << "UseInsideMedium: " << this->UseInsideMedium << "\n";
  os << indent << "InsideExtinction: (" << this->InsideExtinction[0] << ", "
     << this->InsideExtinction[1] << ", " << this->InsideExtinction[2] << ")\n";
  os << indent << "InsideAlbedo: (" << this->InsideAlbedo[0] << ", " << this->InsideAlbedo[1]
     << ", " << this->InsideAlbedo[2] << ")\n";
  os << indent << "InsideAnisotropy: " << this->InsideAnisotropy << "\n";
  os << indent << "InsideEmission: (" << this->InsideEmission[0] << ", " << this->InsideEmission[1]
     << ", " << this->InsideEmission[2] << ")\n";
}
