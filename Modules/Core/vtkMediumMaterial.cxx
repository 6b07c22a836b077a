#include "vtkMediumMaterial.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkImplicitFunction.h"
#include "vtkMatrix3x3.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkRefractaMedium.h"
#include "vtkRefractaSettings.h"

#include <algorithm>
#include <cmath>
#include <limits>

vtkStandardNewMacro(vtkMediumMaterial);
vtkCxxSetObjectMacro(vtkMediumMaterial, DensityFunction, vtkImplicitFunction);
vtkCxxSetObjectMacro(vtkMediumMaterial, DensityImage, vtkImageData);

//------------------------------------------------------------------------------
vtkMediumMaterial::~vtkMediumMaterial()
{
  this->SetDensityFunction(nullptr);
  this->SetDensityImage(nullptr);
  this->SetDensityArrayName(nullptr);
}

//------------------------------------------------------------------------------
vtkMTimeType vtkMediumMaterial::GetMTime()
{
  vtkMTimeType t = this->Superclass::GetMTime();
  if (this->DensityFunction)
  {
    t = std::max(t, this->DensityFunction->GetMTime());
  }
  if (this->DensityImage)
  {
    t = std::max(t, this->DensityImage->GetMTime());
  }
  return t;
}

//------------------------------------------------------------------------------
bool vtkMediumMaterial::IsHeterogeneous() const
{
  return this->DensityFunction != nullptr || this->DensityImage != nullptr;
}

//------------------------------------------------------------------------------
bool vtkMediumMaterial::CheckDensity(std::string& why) const
{
  why.clear();
  if (this->DensityFunction || !this->DensityImage)
  {
    return true;
  }
  vtkImageData* image = this->DensityImage;
  if (!this->DensityArrayName || !*this->DensityArrayName)
  {
    why = "the material has a DensityImage but no DensityArrayName; set the name of a point-data "
          "array of the image";
    return false;
  }
  vtkDataArray* array = image->GetPointData()->GetArray(this->DensityArrayName);
  if (!array)
  {
    why = std::string("the DensityImage has no numeric point-data array named '") +
      this->DensityArrayName + "'";
    return false;
  }
  if (image->GetNumberOfPoints() < 1 || array->GetNumberOfTuples() != image->GetNumberOfPoints())
  {
    why = "the DensityImage is empty or its density array has the wrong number of tuples";
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
double vtkMediumMaterial::EvaluateDensity(const double x[3]) const
{
  double d = 1.0;
  if (this->DensityFunction)
  {
    double p[3] = { x[0], x[1], x[2] };
    d = this->DensityFunction->FunctionValue(p);
  }
  else if (this->DensityImage)
  {
    std::string why;
    if (!this->CheckDensity(why))
    {
      return 0.0;
    }
    vtkImageData* image = this->DensityImage;
    vtkDataArray* array = image->GetPointData()->GetArray(this->DensityArrayName);
    int ext[6];
    image->GetExtent(ext);
    // Continuous structured (extent-including) index: VTK's own physical-to-index map (origin,
    // spacing and direction matrix), the map vtkRefractaGridFrame agrees with.
    double ijk[3];
    image->TransformPhysicalPointToContinuousIndex(x, ijk);
    int i0[3];
    double t[3];
    for (int a = 0; a < 3; ++a)
    {
      const int lo = ext[2 * a], hi = ext[2 * a + 1];
      const double u = ijk[a];
      if (!(u >= lo - 1e-9 && u <= hi + 1e-9))
      {
        return 0.0; // outside the image (or NaN)
      }
      if (hi == lo)
      {
        i0[a] = lo;
        t[a] = 0.0;
        continue;
      }
      const double uc = std::min(std::max(u, static_cast<double>(lo)), static_cast<double>(hi));
      i0[a] = std::min(static_cast<int>(std::floor(uc)), hi - 1);
      t[a] = uc - i0[a];
    }
    const vtkIdType nx = ext[1] - ext[0] + 1, ny = ext[3] - ext[2] + 1;
    d = 0.0;
    for (int c = 0; c < 8; ++c)
    {
      const int di = c & 1, dj = (c >> 1) & 1, dk = (c >> 2) & 1;
      const double w =
        (di ? t[0] : 1.0 - t[0]) * (dj ? t[1] : 1.0 - t[1]) * (dk ? t[2] : 1.0 - t[2]);
      if (w == 0.0)
      {
        continue;
      }
      const vtkIdType id =
        (i0[0] + di - ext[0]) + nx * ((i0[1] + dj - ext[2]) + ny * (i0[2] + dk - ext[4]));
      d += w * array->GetComponent(id, 0);
    }
  }
  return (std::isfinite(d) && d > 0.0) ? d : 0.0;
}

//------------------------------------------------------------------------------
void vtkMediumMaterial::GetPropertiesAtDensity(
  double d, double& n, double extinction[3], double albedo[3], double& g, double emission[3]) const
{
  n = this->DensityScalesRefractiveIndex ? 1.0 + d * (this->RefractiveIndex - 1.0)
                                         : this->RefractiveIndex;
  for (int c = 0; c < 3; ++c)
  {
    extinction[c] = d * this->Extinction[c];
    albedo[c] = this->Albedo[c];
    emission[c] = d * this->Emission[c];
  }
  g = this->Anisotropy;
}

vtkRefractaCxxSetClampMacro(
  vtkMediumMaterial, RefractiveIndex, 1.0, vtkRefractaMedium::MaximumRefractiveIndex);
vtkRefractaCxxSetClampMacro(vtkMediumMaterial, Anisotropy, -0.9999, 0.9999);

//------------------------------------------------------------------------------
void vtkMediumMaterial::SetRGB(
  const char* property, double target[3], double r, double g, double b, double hi)
{
  const double value[3] = { r, g, b };
  if (vtkRefractaSettings::SetClamped3(this, property, target, value, 0.0, hi))
  {
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkMediumMaterial::SetExtinction(double r, double g, double b)
{
  this->SetRGB("Extinction", this->Extinction, r, g, b, MaximumCoefficient);
}

//------------------------------------------------------------------------------
void vtkMediumMaterial::SetAlbedo(double r, double g, double b)
{
  this->SetRGB("Albedo", this->Albedo, r, g, b, 1.0);
}

//------------------------------------------------------------------------------
void vtkMediumMaterial::SetEmission(double r, double g, double b)
{
  this->SetRGB("Emission", this->Emission, r, g, b, MaximumCoefficient);
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
  this->SetDensityFunction(other->DensityFunction);
  this->SetDensityImage(other->DensityImage);
  this->SetDensityArrayName(other->DensityArrayName);
  this->SetDensityScalesRefractiveIndex(other->DensityScalesRefractiveIndex);
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
  os << indent << "DensityFunction: " << this->DensityFunction << "\n";
  os << indent << "DensityImage: " << this->DensityImage << "\n";
  os << indent
     << "DensityArrayName: " << (this->DensityArrayName ? this->DensityArrayName : "(none)")
     << "\n";
  os << indent << "DensityScalesRefractiveIndex: " << this->DensityScalesRefractiveIndex << "\n";
}
