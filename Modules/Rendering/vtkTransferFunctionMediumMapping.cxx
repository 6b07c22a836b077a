#include "vtkTransferFunctionMediumMapping.h"

#include "vtkColorTransferFunction.h"
#include "vtkDataArray.h"
#include "vtkDiscretizableColorTransferFunction.h"
#include "vtkPiecewiseFunction.h"
#include "vtkRefractaMedium.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>
#include <sstream>

namespace vtkTransferFunctionMediumDetail
{
namespace
{
bool Fail(const std::ostringstream& message, std::string& why)
{
  why = message.str();
  return false;
}

// 1 / the largest value of an integer array type (RGB given as integers), 1 for floating point.
double ColourScaleOf(vtkDataArray* scalars)
{
  const int type = scalars->GetDataType();
  if (type == VTK_FLOAT || type == VTK_DOUBLE)
  {
    return 1.0;
  }
  const double maximum = scalars->GetDataTypeMax();
  return maximum > 0 ? 1.0 / maximum : 1.0;
}
}

//------------------------------------------------------------------------------
bool TupleMapping::Configure(vtkVolumeProperty* property, vtkDataArray* scalars,
  vtkPiecewiseFunction* index, double emissionScale, std::string& why)
{
  const int components = scalars->GetNumberOfComponents();
  const bool independent = property->GetIndependentComponents() != 0;
  std::ostringstream message;
  if (components == 1)
  {
    this->Mode = SINGLE;
  }
  else if (independent && components <= 4)
  {
    this->Mode = INDEPENDENT;
  }
  else if (!independent && (components == 2 || components == 4))
  {
    this->Mode = components == 2 ? COLOUR_OPACITY : RGB_OPACITY;
  }
  else
  {
    message << "have " << components << " components; the transfer-function mapping takes 1, 2 to "
            << "4 independent components (vtkVolumeProperty::IndependentComponents on) or 2 or 4 "
               "dependent ones (colour and opacity, or RGB and opacity)";
    return Fail(message, why);
  }
  this->Components = components;
  // Independent components have their own functions; every other layout uses the first.
  for (int c = 0; c < (this->Mode == INDEPENDENT ? components : 1); ++c)
  {
    ComponentFunctions& f = this->Functions[c];
    f.Opacity = property->GetScalarOpacity(c);
    const bool grey = property->GetColorChannels(c) == 1;
    f.Colour = grey ? nullptr : property->GetRGBTransferFunction(c);
    f.Grey = grey ? property->GetGrayTransferFunction(c) : nullptr;
    f.Unit = property->GetScalarOpacityUnitDistance(c);
    f.Weight = this->Mode == INDEPENDENT ? property->GetComponentWeight(c) : 1.0;
  }
  this->Index = index;
  this->EmissionScale = emissionScale;
  this->ColourScale = this->Mode == RGB_OPACITY ? ColourScaleOf(scalars) : 1.0;
  return true;
}

//------------------------------------------------------------------------------
bool TupleMapping::IsMissing(const double* s) const
{
  bool anyNaN = false, anyRead = false;
  for (int c = 0; c < this->Components; ++c)
  {
    if (this->Reads(c))
    {
      anyNaN = anyNaN || std::isnan(s[c]);
      anyRead = anyRead || !std::isnan(s[c]);
    }
  }
  return this->Mode == INDEPENDENT ? !anyRead && anyNaN : anyNaN;
}

//------------------------------------------------------------------------------
bool TupleMapping::HasInfinite(const double* s) const
{
  for (int c = 0; c < this->Components; ++c)
  {
    if (this->Reads(c) && std::isinf(s[c]))
    {
      return true;
    }
  }
  return false;
}

//------------------------------------------------------------------------------
bool TupleMapping::CheckUnitDistances(std::string& why) const
{
  for (int c = 0; c < (this->Mode == INDEPENDENT ? this->Components : 1); ++c)
  {
    if (!this->Reads(c))
    {
      continue; // a species of weight 0 is never evaluated
    }
    const double unit = this->Functions[c].Unit;
    if (!std::isfinite(unit) || !(unit > 0.0))
    {
      std::ostringstream message;
      message << "The volume property's ScalarOpacityUnitDistance";
      if (this->Mode == INDEPENDENT)
      {
        message << " of component " << c;
      }
      message << " is " << unit << "; it must be finite and > 0 (world units).";
      return Fail(message, why);
    }
  }
  return true;
}

//------------------------------------------------------------------------------
void TupleMapping::PrepareColourFunctions(std::mutex* lock)
{
  this->ColourLock = nullptr;
  for (int c = 0; c < (this->Mode == INDEPENDENT ? this->Components : 1); ++c)
  {
    vtkColorTransferFunction* colour = this->Functions[c].Colour;
    if (vtkDiscretizableColorTransferFunction::SafeDownCast(colour))
    {
      colour->Build();
      this->ColourLock = lock;
    }
  }
}

//------------------------------------------------------------------------------
bool TupleMapping::MapComponent(double s, const ComponentFunctions& f, int component, double& sigma,
  double colour[3], std::string& why)
{
  auto of = [component]()
  { return component < 0 ? std::string() : " of component " + std::to_string(component); };
  // Messages are built only on a failure: a stream per voxel cost more than the mapping.
  if (f.Opacity)
  {
    const double a = f.Opacity->GetValue(s);
    if (std::isnan(a))
    {
      std::ostringstream message;
      message << "the scalar opacity function" << of() << " is NaN at scalar " << s
              << "; opacities must be numbers in [0, 1]";
      return Fail(message, why);
    }
    sigma = -std::log1p(-std::min(std::max(a, 0.0), 1.0 - 1e-6)) / f.Unit;
  }
  if (!colour)
  {
    return true;
  }
  if (f.Grey)
  {
    colour[0] = colour[1] = colour[2] = f.Grey->GetValue(s);
  }
  else if (this->ColourLock)
  {
    std::lock_guard<std::mutex> lock(*this->ColourLock);
    f.Colour->GetColor(s, colour);
  }
  else
  {
    f.Colour->GetColor(s, colour);
  }
  for (int k = 0; k < 3; ++k)
  {
    if (std::isnan(colour[k]))
    {
      std::ostringstream message;
      message << "the colour transfer function" << of() << " is NaN at scalar " << s
              << "; colours (albedos) must be numbers in [0, 1]";
      return Fail(message, why);
    }
    colour[k] = std::min(std::max(colour[k], 0.0), 1.0);
  }
  return true;
}

//------------------------------------------------------------------------------
bool TupleMapping::MapIndex(double s, std::string& why)
{
  this->RefractiveIndex = 1.0;
  if (!this->Index || std::isnan(s))
  {
    return true; // no function, or a species without data here: n = 1
  }
  const double value = this->Index->GetValue(s);
  this->RefractiveIndex = std::max(1.0, value);
  if (!(value <= vtkRefractaMedium::MaximumRefractiveIndex)) // NaN, +Inf, or beyond the range
  {
    std::ostringstream message;
    message << "the refractive index function gives " << value << " at scalar " << s
            << "; indices must be finite numbers in [1, "
            << vtkRefractaMedium::MaximumRefractiveIndex << "] (below 1 they are raised to 1)";
    return Fail(message, why);
  }
  return true;
}

//------------------------------------------------------------------------------
bool TupleMapping::Map(const double* s, std::string& why)
{
  if (this->Mode == SINGLE)
  {
    // The common case, without the mixing below.
    if (!this->MapComponent(s[0], this->Functions[0], -1, this->Sigma, this->Albedo, why))
    {
      return false;
    }
    for (int k = 0; k < 3; ++k)
    {
      this->Emission[k] = this->EmissionScale * this->Albedo[k] * this->Sigma;
    }
    return this->CheckRange(s[0], why) && this->MapIndex(s[0], why);
  }
  int indexComponent = 0;
  double colour[3] = { 0, 0, 0 };
  switch (this->Mode)
  {
    case SINGLE:
      break; // above
    case INDEPENDENT:
    {
      // Species: extinctions add; the albedo is scattering over extinction (the weighted mean
      // colour where nothing extinguishes); emissions add.
      double scattering[3] = { 0, 0, 0 }, plain[3] = { 0, 0, 0 }, weights = 0;
      this->Sigma = 0;
      for (int c = 0; c < this->Components; ++c)
      {
        const ComponentFunctions& f = this->Functions[c];
        if (!this->Reads(c) || std::isnan(s[c]))
        {
          continue; // weight 0, or no data for this species here
        }
        double sigma = 0, cc[3];
        if (!this->MapComponent(s[c], f, c, sigma, cc, why))
        {
          return false;
        }
        this->Sigma += f.Weight * sigma;
        weights += f.Weight;
        for (int k = 0; k < 3; ++k)
        {
          scattering[k] += f.Weight * sigma * cc[k];
          plain[k] += f.Weight * cc[k];
        }
      }
      for (int k = 0; k < 3; ++k)
      {
        colour[k] = this->Sigma > 0 ? std::min(1.0, scattering[k] / this->Sigma)
                                    : (weights > 0 ? plain[k] / weights : 0.0);
      }
      break;
    }
    case COLOUR_OPACITY:
      indexComponent = 1;
      if (!this->MapComponent(s[1], this->Functions[0], -1, this->Sigma, nullptr, why))
      {
        return false;
      }
      {
        ComponentFunctions colourOnly = this->Functions[0];
        colourOnly.Opacity = nullptr;
        double unused = 0;
        if (!this->MapComponent(s[0], colourOnly, -1, unused, colour, why))
        {
          return false;
        }
      }
      break;
    case RGB_OPACITY:
      indexComponent = 3;
      if (!this->MapComponent(s[3], this->Functions[0], -1, this->Sigma, nullptr, why))
      {
        return false;
      }
      for (int k = 0; k < 3; ++k)
      {
        colour[k] = std::min(std::max(s[k] * this->ColourScale, 0.0), 1.0);
      }
      break;
  }
  for (int k = 0; k < 3; ++k)
  {
    this->Albedo[k] = colour[k];
    this->Emission[k] = this->EmissionScale * colour[k] * this->Sigma;
  }
  return this->CheckRange(s[indexComponent], why) && this->MapIndex(s[indexComponent], why);
}

//------------------------------------------------------------------------------
bool TupleMapping::CheckRange(double s, std::string& why) const
{
  if (this->Sigma <= FLT_MAX && this->Emission[0] <= FLT_MAX && this->Emission[1] <= FLT_MAX &&
    this->Emission[2] <= FLT_MAX)
  {
    return true;
  }
  std::ostringstream message;
  message << "the extinction " << this->Sigma << " times the emission scale " << this->EmissionScale
          << " exceeds the float range at scalar " << s
          << "; use a larger ScalarOpacityUnitDistance or a smaller EmissionScale";
  return Fail(message, why);
}
}
