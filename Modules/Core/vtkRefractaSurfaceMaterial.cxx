#include "vtkRefractaSurfaceMaterial.h"

#include "vtkMediumMaterial.h"
#include "vtkObjectFactory.h"
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
