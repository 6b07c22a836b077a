#include "vtkTransferFunctionMedium.h"

#include "vtkColorTransferFunction.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkRefractaMedium.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkVersionMacros.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <cmath>

vtkStandardNewMacro(vtkTransferFunctionMedium);

//------------------------------------------------------------------------------
vtkTransferFunctionMedium::vtkTransferFunctionMedium()
{
  this->SetNumberOfInputPorts(1);
  this->SetNumberOfOutputPorts(1);
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::SCALARS);
}

vtkTransferFunctionMedium::~vtkTransferFunctionMedium() = default;

void vtkTransferFunctionMedium::SetVolumeProperty(vtkVolumeProperty* property)
{
  if (this->VolumeProperty != property)
  {
    this->VolumeProperty = property;
    this->Modified();
  }
}

vtkVolumeProperty* vtkTransferFunctionMedium::GetVolumeProperty()
{
  return this->VolumeProperty;
}

void vtkTransferFunctionMedium::SetRefractiveIndexFunction(vtkPiecewiseFunction* function)
{
  if (this->RefractiveIndexFunction != function)
  {
    this->RefractiveIndexFunction = function;
    this->Modified();
  }
}

vtkPiecewiseFunction* vtkTransferFunctionMedium::GetRefractiveIndexFunction()
{
  return this->RefractiveIndexFunction;
}

vtkMTimeType vtkTransferFunctionMedium::GetMTime()
{
  vtkMTimeType t = this->Superclass::GetMTime();
  if (this->VolumeProperty)
  {
    // vtkVolumeProperty::GetMTime includes its transfer functions.
    t = std::max(t, this->VolumeProperty->GetMTime());
  }
  if (this->RefractiveIndexFunction)
  {
    t = std::max(t, this->RefractiveIndexFunction->GetMTime());
  }
  return t;
}

int vtkTransferFunctionMedium::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(),
    inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()), 6);
  return 1;
}

//------------------------------------------------------------------------------
int vtkTransferFunctionMedium::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0], 0);
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  output->Initialize();
  if (!this->VolumeProperty)
  {
    vtkErrorMacro("No volume property: call SetVolumeProperty() with the vtkVolumeProperty whose "
                  "transfer functions map the scalars.");
    return 0;
  }
  vtkDataArray* scalars = this->GetInputArrayToProcess(0, inputVector);
  if (!input || !scalars)
  {
    vtkErrorMacro("The input image has no point scalars to map (a vtkImageData with one "
                  "scalar point array is needed).");
    return 0;
  }
  if (scalars->GetNumberOfComponents() != 1)
  {
    vtkErrorMacro("The input scalars '" << (scalars->GetName() ? scalars->GetName() : "(unnamed)")
                                        << "' have " << scalars->GetNumberOfComponents()
                                        << " components; the transfer-function mapping needs 1.");
    return 0;
  }
  vtkVolumeProperty* property = this->VolumeProperty;
  vtkPiecewiseFunction* opacity = property->GetScalarOpacity(0);
  const bool grey = property->GetColorChannels(0) == 1;
  vtkColorTransferFunction* colour = grey ? nullptr : property->GetRGBTransferFunction(0);
  vtkPiecewiseFunction* greyFunction = grey ? property->GetGrayTransferFunction(0) : nullptr;
  const double unit = property->GetScalarOpacityUnitDistance(0);
  double g = this->Anisotropy;
#if VTK_VERSION_NUMBER >= VTK_VERSION_CHECK(9, 2, 0)
  if (g == 0.0)
  {
    g = std::max(-0.9999, std::min(0.9999, static_cast<double>(property->GetScatteringAnisotropy())));
  }
#endif

  const vtkIdType n = scalars->GetNumberOfTuples();
  output->CopyStructure(input);
  auto make = [&](const char* name, int comps)
  {
    vtkNew<vtkFloatArray> a;
    a->SetName(name);
    a->SetNumberOfComponents(comps);
    a->SetNumberOfTuples(n);
    output->GetPointData()->AddArray(a);
    return a.GetPointer();
  };
  vtkFloatArray* extinction = make(vtkRefractaMedium::ExtinctionName(), 3);
  vtkFloatArray* albedo = make(vtkRefractaMedium::AlbedoName(), 3);
  vtkFloatArray* anisotropy = make(vtkRefractaMedium::AnisotropyName(), 1);
  vtkFloatArray* index =
    this->RefractiveIndexFunction ? make(vtkRefractaMedium::RefractiveIndexName(), 1) : nullptr;
  vtkFloatArray* emission =
    this->EmissionScale > 0 ? make(vtkRefractaMedium::EmissionName(), 3) : nullptr;
  anisotropy->FillValue(static_cast<float>(g));
  for (vtkIdType i = 0; i < n; ++i)
  {
    if (i % 65536 == 0)
    {
      this->UpdateProgress(static_cast<double>(i) / n);
    }
    const double s = scalars->GetComponent(i, 0);
    if (!std::isfinite(s))
    {
      vtkErrorMacro("The input scalars have the non-finite value "
        << s << " at point " << i << "; every scalar must be finite.");
      output->Initialize();
      return 0;
    }
    const double a = std::min(std::max(opacity->GetValue(s), 0.0), 1.0 - 1e-6);
    const double sigma = -std::log1p(-a) / unit;
    double c[3];
    if (grey)
    {
      c[0] = c[1] = c[2] = greyFunction->GetValue(s);
    }
    else
    {
      colour->GetColor(s, c);
    }
    float* e = extinction->GetPointer(3 * i);
    float* al = albedo->GetPointer(3 * i);
    for (int k = 0; k < 3; ++k)
    {
      c[k] = std::min(std::max(c[k], 0.0), 1.0);
      e[k] = static_cast<float>(sigma);
      al[k] = static_cast<float>(c[k]);
      if (emission)
      {
        emission->SetComponent(i, k, this->EmissionScale * c[k] * sigma);
      }
    }
    if (index)
    {
      index->SetValue(
        i, static_cast<float>(std::max(1.0, this->RefractiveIndexFunction->GetValue(s))));
    }
  }
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
void vtkTransferFunctionMedium::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "VolumeProperty: " << this->VolumeProperty.Get() << "\n";
  os << indent << "RefractiveIndexFunction: " << this->RefractiveIndexFunction.Get() << "\n";
  os << indent << "Anisotropy: " << this->Anisotropy << "\n";
  os << indent << "EmissionScale: " << this->EmissionScale << "\n";
}
