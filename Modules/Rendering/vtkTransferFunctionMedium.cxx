#include "vtkTransferFunctionMedium.h"
#include "vtkTransferFunctionMediumMapping.h"

#include "vtkCellData.h"
#include "vtkColorTransferFunction.h"
#include "vtkDataArray.h"
#include "vtkDiscretizableColorTransferFunction.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMatrix3x3.h"
#include "vtkObjectFactory.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkRefractaHostThreads.h"
#include "vtkRefractaMedium.h"
#include "vtkRefractaSettings.h"
#include "vtkSMPTools.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkVersionMacros.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <atomic>
#include <cfloat>
#include <cmath>
#include <limits>
#include <mutex>
#include <sstream>
#include <string>

vtkStandardNewMacro(vtkTransferFunctionMedium);
vtkRefractaCxxSetClampMacro(vtkTransferFunctionMedium, Anisotropy, -0.9999, 0.9999);
vtkRefractaCxxSetClampMacro(vtkTransferFunctionMedium, EmissionScale, 0.0, 1e30);

//------------------------------------------------------------------------------
vtkTransferFunctionMedium::vtkTransferFunctionMedium()
{
  this->SetNumberOfInputPorts(1);
  this->SetNumberOfOutputPorts(1);
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::SCALARS);
  vtkRefractaHostThreads::UseThreadedBackend(); // the mapping runs on every core
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

using vtkTransferFunctionMediumDetail::TupleMapping;

namespace
{
constexpr double NaN = std::numeric_limits<double>::quiet_NaN();

// "point 'a', cell 'b'": the arrays of an image, for messages.
std::string ArrayList(vtkImageData* image)
{
  std::ostringstream out;
  auto add = [&out](vtkDataSetAttributes* data, const char* kind)
  {
    for (int a = 0; data && a < data->GetNumberOfArrays(); ++a)
    {
      const char* name = data->GetArrayName(a);
      out << (out.tellp() > 0 ? ", " : "") << kind << " '" << (name ? name : "(unnamed)") << "'";
    }
  };
  if (image)
  {
    add(image->GetPointData(), "point");
    add(image->GetCellData(), "cell");
  }
  return out.tellp() > 0 ? out.str() : std::string("none");
}
}

//------------------------------------------------------------------------------
void vtkTransferFunctionMedium::ComputeCellCentreGrid(
  int extent[6], double origin[3], const double spacing[3], const double direction[9])
{
  double shift[3] = { 0, 0, 0 };
  for (int a = 0; a < 3; ++a)
  {
    if (extent[2 * a + 1] > extent[2 * a])
    {
      extent[2 * a + 1] -= 1;
      shift[a] = 0.5 * spacing[a];
    }
  }
  for (int r = 0; r < 3; ++r)
  {
    origin[r] += direction[3 * r] * shift[0] + direction[3 * r + 1] * shift[1] +
      direction[3 * r + 2] * shift[2];
  }
}

//------------------------------------------------------------------------------
void vtkTransferFunctionMedium::AnnounceCellCentreGrid(
  vtkInformation* inInfo, vtkInformation* outInfo)
{
  if (!inInfo || !outInfo || !inInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    return;
  }
  // Read from the input's information: an image algorithm's output information may lack the
  // direction matrix.
  int extent[6];
  double origin[3] = { 0, 0, 0 }, spacing[3] = { 1, 1, 1 };
  double direction[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent);
  if (inInfo->Has(vtkDataObject::ORIGIN()))
  {
    inInfo->Get(vtkDataObject::ORIGIN(), origin);
  }
  if (inInfo->Has(vtkDataObject::SPACING()))
  {
    inInfo->Get(vtkDataObject::SPACING(), spacing);
  }
  if (inInfo->Has(vtkDataObject::DIRECTION()))
  {
    inInfo->Get(vtkDataObject::DIRECTION(), direction);
  }
  ComputeCellCentreGrid(extent, origin, spacing, direction);
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  outInfo->Set(vtkDataObject::ORIGIN(), origin, 3);
  outInfo->Set(vtkDataObject::SPACING(), spacing, 3);
  outInfo->Set(vtkDataObject::DIRECTION(), direction, 9);
}

//------------------------------------------------------------------------------
bool vtkTransferFunctionMedium::MapsCellScalars()
{
  vtkInformation* info = this->GetInputArrayInformation(0);
  return info && info->Has(vtkDataObject::FIELD_ASSOCIATION()) &&
    info->Get(vtkDataObject::FIELD_ASSOCIATION()) == vtkDataObject::FIELD_ASSOCIATION_CELLS;
}

//------------------------------------------------------------------------------
int vtkTransferFunctionMedium::RequestInformation(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  if (!this->Superclass::RequestInformation(request, inputVector, outputVector))
  {
    return 0;
  }
  if (this->MapsCellScalars())
  {
    AnnounceCellCentreGrid(
      inputVector[0]->GetInformationObject(0), outputVector->GetInformationObject(0));
  }
  return 1;
}

//------------------------------------------------------------------------------
int vtkTransferFunctionMedium::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(),
    inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()), 6);
  return 1;
}

//------------------------------------------------------------------------------
bool vtkTransferFunctionMedium::CheckInputs(vtkImageData* input, vtkDataArray* scalars, bool cells)
{
  if (!this->VolumeProperty)
  {
    vtkErrorMacro("No volume property: call SetVolumeProperty() with the vtkVolumeProperty whose "
                  "transfer functions map the scalars.");
    return false;
  }
  if (!input || !scalars)
  {
    // Name what was asked for and what there is.
    vtkInformation* info = this->GetInputArrayInformation(0);
    const char* wanted = info && info->Has(vtkDataObject::FIELD_NAME())
      ? info->Get(vtkDataObject::FIELD_NAME())
      : nullptr;
    vtkErrorMacro("The input image has no "
      << (cells ? "cell" : "point") << " array "
      << (wanted && *wanted ? std::string("'") + wanted + "'" : std::string("(active scalars)"))
      << " to map; its arrays: " << ArrayList(input)
      << ". Select one with SetInputArrayToProcess (FIELD_ASSOCIATION_POINTS or _CELLS).");
    return false;
  }
  if (cells != this->MapsCellScalars())
  {
    // FIELD_ASSOCIATION_POINTS_THEN_CELLS found a cell array: the grid announced before the data
    // (RequestInformation) was the points'.
    vtkErrorMacro("The scalars '" << (scalars->GetName() ? scalars->GetName() : "(unnamed)")
                                  << "' were found in the cell data, but the array was not "
                                     "selected as cell data; select it with "
                                     "FIELD_ASSOCIATION_CELLS (a cell array's medium lies on the "
                                     "cells' centres, a grid that must be known before the data).");
    return false;
  }
  const char* name = scalars->GetName() ? scalars->GetName() : "(unnamed)";
  const vtkIdType expected = cells ? input->GetNumberOfCells() : input->GetNumberOfPoints();
  const char* element = cells ? "cell" : "point";
  if (expected == 0 || scalars->GetNumberOfTuples() != expected)
  {
    vtkErrorMacro("The input scalars '"
      << name << "' have " << scalars->GetNumberOfTuples() << " values but the image has "
      << expected << " " << element << "s; a non-empty image with one scalar per " << element
      << " is needed.");
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
int vtkTransferFunctionMedium::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0], 0);
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  output->Initialize();
  int association = vtkDataObject::FIELD_ASSOCIATION_POINTS;
  vtkDataArray* scalars = this->GetInputArrayToProcess(0, inputVector, association);
  const bool cells = association == vtkDataObject::FIELD_ASSOCIATION_CELLS;
  if (!this->CheckInputs(input, scalars, cells))
  {
    return 0;
  }
  vtkVolumeProperty* property = this->VolumeProperty;
  TupleMapping mapping;
  std::string why;
  if (!mapping.Configure(
        property, scalars, this->RefractiveIndexFunction, this->EmissionScale, why))
  {
    vtkErrorMacro("The input scalars '" << (scalars->GetName() ? scalars->GetName() : "(unnamed)")
                                        << "' " << why << ".");
    return 0;
  }
  if (!mapping.CheckUnitDistances(why))
  {
    vtkErrorMacro(<< why);
    return 0;
  }
  double g = this->Anisotropy;
#if VTK_VERSION_NUMBER >= VTK_VERSION_CHECK(9, 2, 0)
  if (g == 0.0)
  {
    g =
      std::max(-0.9999, std::min(0.9999, static_cast<double>(property->GetScatteringAnisotropy())));
  }
#endif

  const vtkIdType n = scalars->GetNumberOfTuples();
  output->CopyStructure(input);
  if (cells)
  {
    // The cells' centres: VTK's volume mappers place cell values there.
    int extent[6];
    double origin[3];
    input->GetExtent(extent);
    input->GetOrigin(origin);
    ComputeCellCentreGrid(
      extent, origin, input->GetSpacing(), input->GetDirectionMatrix()->GetData());
    output->SetExtent(extent);
    output->SetOrigin(origin);
  }
  bool allocated = true;
  auto make = [&](int id) -> vtkFloatArray*
  {
    vtkSmartPointer<vtkFloatArray> a = vtkRefractaMedium::NewArrayOrNull(id, n);
    allocated = allocated && a;
    if (a)
    {
      output->GetPointData()->AddArray(a);
    }
    return a;
  };
  vtkFloatArray* extinction = make(vtkRefractaMedium::EXTINCTION);
  vtkFloatArray* albedo = make(vtkRefractaMedium::ALBEDO);
  vtkFloatArray* anisotropy = make(vtkRefractaMedium::ANISOTROPY);
  vtkFloatArray* index =
    this->RefractiveIndexFunction ? make(vtkRefractaMedium::REFRACTIVE_INDEX) : nullptr;
  vtkFloatArray* emission = this->EmissionScale > 0 ? make(vtkRefractaMedium::EMISSION) : nullptr;
  if (!allocated)
  {
    const int* dims = output->GetDimensions();
    const int components =
      7 + (this->RefractiveIndexFunction ? 1 : 0) + (this->EmissionScale > 0 ? 3 : 0);
    vtkErrorMacro("Cannot allocate the medium of the grid "
      << dims[0] << " x " << dims[1] << " x " << dims[2] << " ("
      << static_cast<double>(n) * 4 * components / (1 << 30) << " GiB at " << 4 * components
      << " bytes per point): not enough memory. Resample the volume to fewer points first "
         "(vtkImageResample, vtkImageShrink3D).");
    output->Initialize(); // an empty output, not an image with some of the arrays
    return 0;
  }
  anisotropy->FillValue(static_cast<float>(g));
  // Blocks of voxels in parallel (vtkSMPTools; VTK evaluates its transfer functions without
  // changing them), each block with its own mapping; the first voxel that cannot be mapped (in
  // index order, as a serial loop would find it) is mapped again below to report why.
  // A vtkDiscretizableColorTransferFunction rebuilds itself in GetColor() (ParaView's subclass
  // changes its annotations there): built here once, then evaluated under a lock; two threads
  // inside it crashed pvserver (RefractaParaView.ClientServer, session 18).
  std::mutex colourLock;
  mapping.PrepareColourFunctions(&colourLock);
  const int components = mapping.GetNumberOfComponents();
  std::atomic<vtkIdType> missing(0); // NaN scalars: no data, mapped to empty space
  auto mapRange = [&](vtkIdType begin, vtkIdType end, std::atomic<vtkIdType>& firstBad)
  {
    vtkIdType localMissing = 0;
    TupleMapping point = mapping;
    // Neighbouring voxels often share a tuple (a background, a segmented label): the last
    // mapping is reused (the functions are evaluated once per run of equal tuples).
    double mapped[4] = { NaN, NaN, NaN, NaN }, t[4] = { 0, 0, 0, 0 };
    std::string message;
    for (vtkIdType i = begin; i < end; ++i)
    {
      if (components == 1)
      {
        t[0] = scalars->GetComponent(i, 0); // one virtual call, not a tuple copy
      }
      else
      {
        scalars->GetTuple(i, t);
      }
      if (point.IsMissing(t))
      {
        // Missing data (NaN, as NetCDF fill values often become): empty space, n = 1.
        std::fill_n(extinction->GetPointer(3 * i), 3, 0.0f);
        std::fill_n(albedo->GetPointer(3 * i), 3, 0.0f);
        if (emission)
        {
          std::fill_n(emission->GetPointer(3 * i), 3, 0.0f);
        }
        if (index)
        {
          index->SetValue(i, 1.0f);
        }
        ++localMissing;
        continue;
      }
      if (!std::equal(t, t + components, mapped) &&
        (point.HasInfinite(t) || !point.Map(t, message)))
      {
        vtkIdType known = firstBad.load();
        while (i < known && !firstBad.compare_exchange_weak(known, i))
        {
        }
        return;
      }
      std::copy_n(t, components, mapped);
      float* e = extinction->GetPointer(3 * i);
      float* al = albedo->GetPointer(3 * i);
      float* em = emission ? emission->GetPointer(3 * i) : nullptr;
      for (int k = 0; k < 3; ++k)
      {
        e[k] = static_cast<float>(point.Sigma);
        al[k] = static_cast<float>(point.Albedo[k]);
        if (em)
        {
          em[k] = static_cast<float>(point.Emission[k]);
        }
      }
      if (index)
      {
        index->SetValue(i, static_cast<float>(point.RefractiveIndex));
      }
    }
    missing += localMissing;
  };
  std::atomic<vtkIdType> firstBad(n);
  const vtkIdType progressStep = 1 << 18; // voxels between progress reports
  for (vtkIdType first = 0; first < n && firstBad.load() == n; first += progressStep)
  {
    this->UpdateProgress(static_cast<double>(first) / n);
    vtkSMPTools::For(first, std::min(n, first + progressStep),
      [&](vtkIdType begin, vtkIdType end) { mapRange(begin, end, firstBad); });
  }
  if (firstBad.load() < n)
  {
    const vtkIdType i = firstBad.load();
    double t[4] = { 0, 0, 0, 0 };
    scalars->GetTuple(i, t);
    why = "every scalar must be finite (or NaN: missing data, empty space)";
    if (!mapping.HasInfinite(t))
    {
      mapping.Map(t, why);
    }
    std::ostringstream value;
    value << (components > 1 ? "(" : "");
    for (int c = 0; c < components; ++c)
    {
      value << (c ? ", " : "") << t[c];
    }
    value << (components > 1 ? ")" : "");
    vtkErrorMacro("Cannot map the input scalar "
      << value.str() << " at " << (cells ? "cell " : "point ") << i << ": " << why << ".");
    output->Initialize();
    return 0;
  }
  if (missing.load() > 0)
  {
    vtkWarningMacro(<< missing.load() << " of " << n
                    << " input scalars are NaN (missing data): those voxels are empty space (no "
                       "extinction, no emission, refractive index 1).");
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
