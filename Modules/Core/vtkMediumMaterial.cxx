#include "vtkMediumMaterial.h"

#include "vtkObjectFactory.h"

#include <algorithm>
#include <cmath>
#include <limits>

vtkStandardNewMacro(vtkMediumMaterial);

//------------------------------------------------------------------------------
void vtkMediumMaterial::SetClampedVector(
  double target[3], double r, double g, double b, double lo, double hi)
{
  const double in[3] = { r, g, b };
  double out[3];
  for (int c = 0; c < 3; ++c)
  {
    // NaN is not orderable; map it to the lower bound rather than letting it through.
    out[c] = std::isnan(in[c]) ? lo : std::min(std::max(in[c], lo), hi);
  }
  if (out[0] != target[0] || out[1] != target[1] || out[2] != target[2])
  {
    std::copy(out, out + 3, target);
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkMediumMaterial::SetExtinction(double r, double g, double b)
{
  this->SetClampedVector(this->Extinction, r, g, b, 0.0, std::numeric_limits<double>::max());
}

//------------------------------------------------------------------------------
void vtkMediumMaterial::SetAlbedo(double r, double g, double b)
{
  this->SetClampedVector(this->Albedo, r, g, b, 0.0, 1.0);
}

//------------------------------------------------------------------------------
void vtkMediumMaterial::SetEmission(double r, double g, double b)
{
  this->SetClampedVector(this->Emission, r, g, b, 0.0, std::numeric_limits<double>::max());
}

//------------------------------------------------------------------------------
void vtkMediumMaterial::GetScattering(double rgb[3]) const
{
  for (int c = 0; c < 3; ++c)
  {
    rgb[c] = this->Albedo[c] * this->Extinction[c];
  }
}

//------------------------------------------------------------------------------
void vtkMediumMaterial::DeepCopy(vtkMediumMaterial* other)
{
  if (!other || other == this)
  {
    return;
  }
  this->SetRefractiveIndex(other->RefractiveIndex);
  this->SetExtinction(other->Extinction);
  this->SetAlbedo(other->Albedo);
  this->SetAnisotropy(other->Anisotropy);
  this->SetEmission(other->Emission);
}

//------------------------------------------------------------------------------
void vtkMediumMaterial::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "RefractiveIndex: " << this->RefractiveIndex << "\n";
  os << indent << "Extinction: (" << this->Extinction[0] << ", " << this->Extinction[1] << ", "
     << this->Extinction[2] << ")\n";
  os << indent << "Albedo: (" << this->Albedo[0] << ", " << this->Albedo[1] << ", "
     << this->Albedo[2] << ")\n";
  os << indent << "Anisotropy: " << this->Anisotropy << "\n";
  os << indent << "Emission: (" << this->Emission[0] << ", " << this->Emission[1] << ", "
     << this->Emission[2] << ")\n";
}
