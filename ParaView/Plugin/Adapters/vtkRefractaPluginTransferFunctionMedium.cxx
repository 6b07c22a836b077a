#include "vtkRefractaPluginTransferFunctionMedium.h"

#include "vtkCellData.h"
#include "vtkColorTransferFunction.h"
#include "vtkDataObject.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkRefractaPluginInputCheck.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkTransferFunctionMedium.h"
#include "vtkVolumeProperty.h"

#include <algorithm>

vtkStandardNewMacro(vtkRefractaPluginTransferFunctionMedium);

//------------------------------------------------------------------------------
vtkRefractaPluginTransferFunctionMedium::vtkRefractaPluginTransferFunctionMedium()
  : Medium(vtkSmartPointer<vtkTransferFunctionMedium>::New())
  , Property(vtkSmartPointer<vtkVolumeProperty>::New())
{
  this->Property->SetScalarOpacityUnitDistance(1.0);
  this->Medium->SetVolumeProperty(this->Property);
  // Default: the active point scalars.
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::SCALARS);
}

//------------------------------------------------------------------------------
vtkRefractaPluginTransferFunctionMedium::~vtkRefractaPluginTransferFunctionMedium() = default;

//------------------------------------------------------------------------------
vtkTransferFunctionMedium* vtkRefractaPluginTransferFunctionMedium::GetMediumFilter()
{
  return this->Medium;
}

//------------------------------------------------------------------------------
void vtkRefractaPluginTransferFunctionMedium::SetColorTransferFunction(
  vtkColorTransferFunction* function)
{
  if (function != this->Property->GetRGBTransferFunction(0) || !function)
  {
    if (function)
    {
      this->Property->SetColor(function);
    }
    else
    {
      this->Property->SetColor(vtkSmartPointer<vtkColorTransferFunction>::New());
    }
    this->Modified();
  }
}

//------------------------------------------------------------------------------
vtkColorTransferFunction* vtkRefractaPluginTransferFunctionMedium::GetColorTransferFunction()
{
  return this->Property->GetRGBTransferFunction(0);
}

//------------------------------------------------------------------------------
void vtkRefractaPluginTransferFunctionMedium::SetScalarOpacityFunction(
  vtkPiecewiseFunction* function)
{
  this->ScalarOpacity = function;
  this->Property->SetScalarOpacity(function);
  this->Modified();
}

//------------------------------------------------------------------------------
vtkPiecewiseFunction* vtkRefractaPluginTransferFunctionMedium::GetScalarOpacityFunction()
{
  return this->ScalarOpacity;
}

//------------------------------------------------------------------------------
void vtkRefractaPluginTransferFunctionMedium::SetRefractiveIndexFunction(
  vtkPiecewiseFunction* function)
{
  this->Medium->SetRefractiveIndexFunction(function);
  this->Modified();
}

//------------------------------------------------------------------------------
vtkPiecewiseFunction* vtkRefractaPluginTransferFunctionMedium::GetRefractiveIndexFunction()
{
  return this->Medium->GetRefractiveIndexFunction();
}

//------------------------------------------------------------------------------
void vtkRefractaPluginTransferFunctionMedium::SetScalarOpacityUnitDistance(double distance)
{
  this->Property->SetScalarOpacityUnitDistance(std::max(distance, 1e-12));
  this->Modified();
}

//------------------------------------------------------------------------------
double vtkRefractaPluginTransferFunctionMedium::GetScalarOpacityUnitDistance()
{
  return this->Property->GetScalarOpacityUnitDistance();
}

//------------------------------------------------------------------------------
void vtkRefractaPluginTransferFunctionMedium::SetAnisotropy(double g)
{
  this->Medium->SetAnisotropy(g);
  this->Modified();
}

//------------------------------------------------------------------------------
double vtkRefractaPluginTransferFunctionMedium::GetAnisotropy()
{
  return this->Medium->GetAnisotropy();
}

//------------------------------------------------------------------------------
void vtkRefractaPluginTransferFunctionMedium::SetEmissionScale(double scale)
{
  this->Medium->SetEmissionScale(scale);
  this->Modified();
}

//------------------------------------------------------------------------------
double vtkRefractaPluginTransferFunctionMedium::GetEmissionScale()
{
  return this->Medium->GetEmissionScale();
}

//------------------------------------------------------------------------------
vtkMTimeType vtkRefractaPluginTransferFunctionMedium::GetMTime()
{
  // The transfer functions are edited in place by ParaView's colour map editor.
  return std::max(this->Superclass::GetMTime(), this->Medium->GetMTime());
}

//------------------------------------------------------------------------------
int vtkRefractaPluginTransferFunctionMedium::FillInputPortInformation(
  int port, vtkInformation* info)
{
  // Any data object: a wrong type is reported once by RequestInformation (see
  // vtkRefractaPluginInputCheck.h) instead of by every pipeline pass.
  this->Superclass::FillInputPortInformation(port, info);
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataObject");
  return 1;
}

//------------------------------------------------------------------------------
int vtkRefractaPluginTransferFunctionMedium::RequestInformation(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  const std::string wrong0 =
    refracta_plugin::CheckImageInput(inputVector, 0, "Refracta Transfer Function Medium",
      "a scalar volume (vtkImageData with a point array); resample other data to an image first "
      "(Resample To Image)");
  if (!wrong0.empty())
  {
    vtkErrorMacro(<< wrong0);
    return refracta_plugin::EmptyInformation(outputVector);
  }
  if (!this->Superclass::RequestInformation(request, inputVector, outputVector))
  {
    return 0;
  }
  // A cell array: the medium lies on the cells' centres (vtkTransferFunctionMedium).
  vtkInformation* array = this->GetInputArrayInformation(0);
  if (array && array->Has(vtkDataObject::FIELD_ASSOCIATION()) &&
    array->Get(vtkDataObject::FIELD_ASSOCIATION()) == vtkDataObject::FIELD_ASSOCIATION_CELLS)
  {
    vtkTransferFunctionMedium::AnnounceCellCentreGrid(
      inputVector[0]->GetInformationObject(0), outputVector->GetInformationObject(0));
  }
  return 1;
}

//------------------------------------------------------------------------------
int vtkRefractaPluginTransferFunctionMedium::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  return refracta_plugin::RequestWholeExtent(inputVector, 0); // the whole grid
}

//------------------------------------------------------------------------------
int vtkRefractaPluginTransferFunctionMedium::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0], 0);
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  output->Initialize();
  if (!input)
  {
    return 1; // a wrong input type, reported by RequestInformation
  }
  int association = vtkDataObject::FIELD_ASSOCIATION_POINTS;
  vtkDataArray* scalars = this->GetInputArrayToProcess(0, inputVector, association);
  vtkInformation* info = this->GetInputArrayInformation(0);
  const char* name =
    info && info->Has(vtkDataObject::FIELD_NAME()) ? info->Get(vtkDataObject::FIELD_NAME()) : "";
  if (!scalars && (!name || !*name))
  {
    // No array chosen (a proxy made from Python before its input's arrays were known leaves the
    // name empty): the input's active point scalars, as documented.
    scalars = input->GetPointData()->GetScalars();
    association = vtkDataObject::FIELD_ASSOCIATION_POINTS;
  }
  const bool cells = association == vtkDataObject::FIELD_ASSOCIATION_CELLS;
  if (!scalars || (!cells && association != vtkDataObject::FIELD_ASSOCIATION_POINTS))
  {
    vtkErrorMacro("The input has no point or cell array '"
      << (name ? name : "") << "' to map (" << (scalars ? "it is field data" : "not found")
      << "); select a point-data scalar array (values at the grid points) or a cell-data one "
         "(values at the cells' centres).");
    return 1; // empty output until something changes (ParaView would re-run a failure)
  }
  if (!this->ScalarOpacity)
  {
    vtkErrorMacro("No scalar opacity function: set ScalarOpacityFunction.");
    return 1;
  }
  vtkNew<vtkImageData> scalarImage;
  scalarImage->ShallowCopy(input);
  (cells ? static_cast<vtkDataSetAttributes*>(scalarImage->GetCellData())
         : scalarImage->GetPointData())
    ->SetScalars(scalars);
  this->Medium->SetInputArrayToProcess(0, 0, 0,
    cells ? vtkDataObject::FIELD_ASSOCIATION_CELLS : vtkDataObject::FIELD_ASSOCIATION_POINTS,
    vtkDataSetAttributes::SCALARS);
  this->Medium->SetInputData(scalarImage);
  this->Medium->Update();
  this->Medium->SetInputData(nullptr);
  vtkImageData* medium = this->Medium->GetOutput();
  if (medium->GetNumberOfPoints() == 0)
  {
    return 1; // vtkTransferFunctionMedium said why; empty output until something changes
  }
  output->ShallowCopy(medium);
  return 1;
}

//------------------------------------------------------------------------------
void vtkRefractaPluginTransferFunctionMedium::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ScalarOpacityUnitDistance: " << this->GetScalarOpacityUnitDistance() << "\n";
  os << indent << "Medium:\n";
  this->Medium->PrintSelf(os, indent.GetNextIndent());
}
