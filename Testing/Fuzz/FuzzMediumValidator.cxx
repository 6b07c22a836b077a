// Fuzz target: vtkMediumValidator on an image whose extent, spacing, origin, direction matrix and
// arrays come from the bytes.
//
// Layout of the bytes (FuzzBytes; reads past the end give zeros):
//   extent per axis (start in [-3, 3] or far away, 0-5 points, sometimes none); spacing and
//   origin (3 FuzzBytes::Double each); direction (identity, a signed axis permutation, a
//   rotation by a lattice angle, or 9 doubles); RequireMediumArray (bit); arrays (0-8): name (a
//   medium array or another), point or cell data, type (float, double, int, unsigned char,
//   short, vtkIdType, string), components (0-4), tuples (the point count, or a few more or
//   fewer), values (doubles for floating types, bytes for integer ones)
//
// Contract checked: Validate() answers, its answer agrees with its list of errors, and every
// error is a non-empty message. A crash, a hang or a sanitizer report is a bug.
#include "FuzzSupport.h"

#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkMatrix3x3.h"
#include "vtkMediumValidator.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkRefractaMedium.h"
#include "vtkShortArray.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"

#include <cfloat>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

namespace
{
using refracta_fuzz::FuzzBytes;

void DecodeGeometry(FuzzBytes& in, vtkImageData* image)
{
  int extent[6];
  for (int a = 0; a < 3; ++a)
  {
    const uint8_t mode = in.Byte();
    extent[2 * a] = mode < 240 ? in.Int(-3, 3) : (mode % 2 ? 1000000 : -1000000);
    extent[2 * a + 1] = extent[2 * a] + in.Int(-1, 4); // -1: an empty axis
  }
  image->SetExtent(extent);
  image->SetSpacing(in.Double(), in.Double(), in.Double());
  image->SetOrigin(in.Double(), in.Double(), in.Double());
  double d[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  switch (in.Byte() % 4)
  {
    case 1:
    {
      // A signed permutation of the axes (a rotation or a reflection).
      const int perms[6][3] = { { 0, 1, 2 }, { 0, 2, 1 }, { 1, 0, 2 }, { 1, 2, 0 }, { 2, 0, 1 },
        { 2, 1, 0 } };
      const int* p = perms[in.Byte() % 6];
      std::fill(d, d + 9, 0.0);
      for (int r = 0; r < 3; ++r)
      {
        d[3 * r + p[r]] = in.Bool() ? -1.0 : 1.0;
      }
      break;
    }
    case 2:
    {
      const double angle = in.Lattice();
      d[0] = d[4] = std::cos(angle);
      d[1] = -std::sin(angle);
      d[3] = std::sin(angle);
      break;
    }
    case 3:
      for (double& v : d)
      {
        v = in.Double();
      }
      break;
    default:
      break;
  }
  image->SetDirectionMatrix(d);
}

vtkSmartPointer<vtkAbstractArray> NewArray(FuzzBytes& in)
{
  switch (in.Byte() % 8)
  {
    case 0:
      return vtkSmartPointer<vtkDoubleArray>::New();
    case 1:
      return vtkSmartPointer<vtkIntArray>::New();
    case 2:
      return vtkSmartPointer<vtkUnsignedCharArray>::New();
    case 3:
      return vtkSmartPointer<vtkShortArray>::New();
    case 4:
      return vtkSmartPointer<vtkIdTypeArray>::New();
    case 5:
      return vtkSmartPointer<vtkStringArray>::New();
    default:
      return vtkSmartPointer<vtkFloatArray>::New();
  }
}

// A double as the float it becomes in a float array (out of range: infinite, as a cast would
// give where it is defined).
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

// Values from the bytes: doubles (with NaN, Inf, denormals) for floating arrays, small signed
// integers for integer arrays, short strings for string arrays.
void FillValues(FuzzBytes& in, vtkAbstractArray* array)
{
  auto* numbers = vtkDataArray::SafeDownCast(array);
  auto* strings = vtkStringArray::SafeDownCast(array);
  const int type = array->GetDataType();
  for (vtkIdType v = 0; v < array->GetNumberOfValues(); ++v)
  {
    if (strings)
    {
      strings->SetValue(v, std::string(in.Int(0, 3), 'a'));
    }
    else if (type == VTK_DOUBLE)
    {
      vtkDoubleArray::SafeDownCast(numbers)->SetValue(v, in.Double());
    }
    else if (type == VTK_FLOAT)
    {
      vtkFloatArray::SafeDownCast(numbers)->SetValue(v, ToFloat(in.Double()));
    }
    else
    {
      const int c = numbers->GetNumberOfComponents();
      numbers->SetComponent(
        v / c, static_cast<int>(v % c), in.Int(0, 255) - (type == VTK_UNSIGNED_CHAR ? 0 : 128));
    }
  }
}

void DecodeArray(FuzzBytes& in, vtkImageData* image)
{
  const int nameId = in.Int(0, vtkRefractaMedium::NUMBER_OF_ARRAYS);
  const char* name = nameId < vtkRefractaMedium::NUMBER_OF_ARRAYS
    ? vtkRefractaMedium::GetArrayName(nameId)
    : "Density";
  const bool cellData = in.Byte() >= 224;
  auto array = NewArray(in);
  array->SetName(name);
  array->SetNumberOfComponents(in.Int(0, 4));
  const vtkIdType points = cellData ? image->GetNumberOfCells() : image->GetNumberOfPoints();
  const uint8_t tupleMode = in.Byte();
  const vtkIdType tuples =
    tupleMode < 224 ? points : std::max<vtkIdType>(0, points + tupleMode % 5 - 2);
  array->SetNumberOfTuples(tuples);
  FillValues(in, array);
  if (cellData)
  {
    image->GetCellData()->AddArray(array);
  }
  else
  {
    image->GetPointData()->AddArray(array);
  }
}
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  refracta_fuzz::InstallQuietOutput();
  FuzzBytes in(data, size);
  vtkNew<vtkImageData> image;
  DecodeGeometry(in, image);
  vtkNew<vtkMediumValidator> validator;
  validator->SetRequireMediumArray(in.Byte() < 192);
  const int arrays = in.Int(0, 8);
  for (int a = 0; a < arrays; ++a)
  {
    DecodeArray(in, image);
  }
  const bool valid = validator->Validate(image);
  const int errors = validator->GetNumberOfErrors();
  refracta_fuzz::Require(valid == (errors == 0), "Validate() agrees with its list of errors");
  refracta_fuzz::Require(valid == (std::strlen(validator->GetErrorMessage()) == 0),
    "the error message is empty exactly when the medium is valid");
  for (int e = 0; e < errors; ++e)
  {
    refracta_fuzz::Require(validator->GetError(e) && std::strlen(validator->GetError(e)) > 0,
      "every error has a message");
  }
  refracta_fuzz::Require(validator->GetError(errors) == nullptr, "no error past the last");
  return 0;
}
