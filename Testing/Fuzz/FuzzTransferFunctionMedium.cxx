// Fuzz target: vtkTransferFunctionMedium (a CPU filter) on a scalar image and transfer functions
// decoded from the bytes.
//
// Layout of the bytes (FuzzBytes; reads past the end give zeros):
//   grid dimensions (3 x 0-5), spacing and origin (lattice values); the scalars: type (float,
//   double, int, unsigned char), components (1-3, mostly 1), tuples (the point count, sometimes
//   a few more or fewer), values (FuzzBytes::Double for floating types: NaN, Inf, 1e300, ...);
//   a volume property (or none): opacity points, grey or RGB colour points, unit distance;
//   a refractive index function (or none); Anisotropy and EmissionScale (doubles).
//   Transfer-function points have finite scalars (vtkPiecewiseFunction sorts them; NaN cannot be
//   sorted) but any values: NaN, Inf, negative, huge.
//
// Contract checked: the filter either produces a medium on the input's grid that passes
// vtkMediumValidator, or reports an error through VTK and produces an empty image.
#include "FuzzSupport.h"

#include "vtkColorTransferFunction.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkTransferFunctionMedium.h"
#include "vtkUnsignedCharArray.h"
#include "vtkVolumeProperty.h"

#include <cfloat>
#include <cmath>
#include <limits>

namespace
{
using refracta_fuzz::FuzzBytes;

float ToFloat(double d)
{
  if (d > FLT_MAX)
  {
    return std::numeric_limits<float>::infinity();
  }
  if (d < -FLT_MAX)
  {
    return -std::numeric_limits<float>::infinity();
  }
  return static_cast<float>(d);
}

// A finite scalar position for a transfer-function point.
double FiniteScalar(FuzzBytes& in)
{
  const double x = in.Double();
  return std::isfinite(x) ? x : in.Lattice();
}

vtkSmartPointer<vtkDataArray> DecodeScalars(FuzzBytes& in, vtkIdType points)
{
  vtkSmartPointer<vtkDataArray> scalars;
  const int type = in.Byte() % 4;
  switch (type)
  {
    case 0:
      scalars = vtkSmartPointer<vtkDoubleArray>::New();
      break;
    case 1:
      scalars = vtkSmartPointer<vtkIntArray>::New();
      break;
    case 2:
      scalars = vtkSmartPointer<vtkUnsignedCharArray>::New();
      break;
    default:
      scalars = vtkSmartPointer<vtkFloatArray>::New();
  }
  scalars->SetName("density");
  const uint8_t shape = in.Byte();
  scalars->SetNumberOfComponents(shape < 232 ? 1 : 1 + shape % 5); // 2 to 4: VTK's layouts
  const uint8_t count = in.Byte();
  scalars->SetNumberOfTuples(count < 232 ? points : std::max<vtkIdType>(0, points + count % 5 - 2));
  for (vtkIdType v = 0; v < scalars->GetNumberOfValues(); ++v)
  {
    const int c = scalars->GetNumberOfComponents();
    if (type == 0)
    {
      vtkDoubleArray::SafeDownCast(scalars)->SetValue(v, in.Double());
    }
    else if (type == 3)
    {
      vtkFloatArray::SafeDownCast(scalars)->SetValue(v, ToFloat(in.Double()));
    }
    else
    {
      scalars->SetComponent(v / c, static_cast<int>(v % c), in.Byte());
    }
  }
  return scalars;
}

vtkSmartPointer<vtkPiecewiseFunction> DecodeFunction(FuzzBytes& in, int maxPoints)
{
  auto function = vtkSmartPointer<vtkPiecewiseFunction>::New();
  const int n = in.Int(0, maxPoints);
  for (int p = 0; p < n; ++p)
  {
    const double x = FiniteScalar(in);
    function->AddPoint(x, in.Double());
  }
  return function;
}

vtkSmartPointer<vtkVolumeProperty> DecodeProperty(FuzzBytes& in)
{
  auto property = vtkSmartPointer<vtkVolumeProperty>::New();
  property->SetScalarOpacity(DecodeFunction(in, 5));
  if (in.Bool())
  {
    property->SetColor(DecodeFunction(in, 4)); // grey
  }
  else
  {
    vtkNew<vtkColorTransferFunction> colour;
    const int n = in.Int(0, 4);
    for (int p = 0; p < n; ++p)
    {
      const double x = FiniteScalar(in);
      const double r = in.Double(), g = in.Double(), b = in.Double();
      colour->AddRGBPoint(x, r, g, b);
    }
    property->SetColor(colour);
  }
  if (in.Bool())
  {
    property->SetScalarOpacityUnitDistance(in.Double());
  }
  return property;
}
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  refracta_fuzz::InstallQuietOutput();
  FuzzBytes in(data, size);
  vtkNew<vtkImageData> image;
  int dims[3];
  for (int& d : dims)
  {
    d = in.Int(0, 5);
  }
  image->SetDimensions(dims);
  image->SetSpacing(1.0 + in.Int(0, 3), 1.0 + in.Int(0, 3), 0.25 + in.Int(0, 3));
  image->SetOrigin(in.Lattice(), in.Lattice(), in.Lattice());
  image->GetPointData()->SetScalars(DecodeScalars(in, image->GetNumberOfPoints()));

  vtkNew<vtkTransferFunctionMedium> mapping;
  mapping->SetInputData(image);
  if (in.Byte() < 248)
  {
    mapping->SetVolumeProperty(DecodeProperty(in));
  }
  if (in.Bool())
  {
    mapping->SetRefractiveIndexFunction(DecodeFunction(in, 4));
  }
  const double g = in.Double(), emission = in.Double();
  mapping->SetAnisotropy(g);
  mapping->SetEmissionScale(emission);
  // Read last, so that older corpus files decode as before: dependent components (2 or 4 are
  // colour and opacity, or RGB and opacity).
  if (in.Bool() && mapping->GetVolumeProperty())
  {
    mapping->GetVolumeProperty()->IndependentComponentsOff();
  }

  refracta_fuzz::ResetErrorCount();
  mapping->Update();
  vtkImageData* out = mapping->GetOutput();
  if (out->GetNumberOfPoints() == 0 || out->GetPointData()->GetNumberOfArrays() == 0)
  {
    refracta_fuzz::Require(refracta_fuzz::GetErrorCount() > 0,
      "an input the transfer-function mapping rejects gets an error message");
    return 0;
  }
  int outDims[3];
  out->GetDimensions(outDims);
  refracta_fuzz::Require(outDims[0] == dims[0] && outDims[1] == dims[1] && outDims[2] == dims[2],
    "the mapped medium has the input's dimensions");
  refracta_fuzz::Require(refracta_fuzz::IsValidMedium(out), "the mapped medium is valid");
  return 0;
}
