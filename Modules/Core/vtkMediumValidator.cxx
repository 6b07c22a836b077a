#include "vtkMediumValidator.h"

#include "vtkArrayDispatch.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDataArrayRange.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkMatrix3x3.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkRefractaMedium.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <mutex>
#include <sstream>

vtkStandardNewMacro(vtkMediumValidator);

namespace
{
// Counts the invalid values of one medium array and remembers the first one.
struct InvalidValueScan
{
  int ArrayId = 0;
  vtkIdType NumberInvalid = 0;
  vtkIdType FirstInvalidIndex = -1;
  double FirstInvalidValue = 0.0;

  template <typename ArrayT>
  void operator()(ArrayT* array)
  {
    vtkIdType index = 0;
    for (const auto value : vtk::DataArrayValueRange(array))
    {
      const double v = static_cast<double>(value);
      if (!vtkRefractaMedium::IsValueValid(this->ArrayId, v))
      {
        if (this->FirstInvalidIndex < 0)
        {
          this->FirstInvalidIndex = index;
          this->FirstInvalidValue = v;
        }
        ++this->NumberInvalid;
      }
      ++index;
    }
  }
};

// The arrays whose value scan passed, by address, modification time and medium role: a
// render validates its medium in every pass, and rescanning 10^7 values each time costs more than
// a light move on a GPU. A few entries cover every live medium; the oldest is dropped first.
class PassedScans
{
public:
  bool Contains(vtkDataArray* array, int id)
  {
    std::lock_guard<std::mutex> lock(this->Mutex);
    const Entry wanted{ array, array->GetMTime(), id };
    return std::find(this->Entries.begin(), this->Entries.end(), wanted) != this->Entries.end();
  }

  void Add(vtkDataArray* array, int id)
  {
    std::lock_guard<std::mutex> lock(this->Mutex);
    this->Entries.push_back({ array, array->GetMTime(), id });
    if (this->Entries.size() > 64)
    {
      this->Entries.pop_front();
    }
  }

private:
  struct Entry
  {
    const vtkDataArray* Array;
    vtkMTimeType Time;
    int Id;
    bool operator==(const Entry& o) const
    {
      return this->Array == o.Array && this->Time == o.Time && this->Id == o.Id;
    }
  };
  std::mutex Mutex;
  std::deque<Entry> Entries;
};

PassedScans& ScanCache()
{
  static PassedScans cache;
  return cache;
}
}

//------------------------------------------------------------------------------
const char* vtkMediumValidator::GetError(int i) const
{
  return (i >= 0 && i < this->GetNumberOfErrors()) ? this->Errors[i].c_str() : nullptr;
}

//------------------------------------------------------------------------------
void vtkMediumValidator::AddError(const std::string& message)
{
  this->Errors.push_back(message);
  if (!this->ErrorMessage.empty())
  {
    this->ErrorMessage += "\n";
  }
  this->ErrorMessage += message;
}

//------------------------------------------------------------------------------
bool vtkMediumValidator::Validate(vtkImageData* medium)
{
  this->Errors.clear();
  this->ErrorMessage.clear();
  if (!medium)
  {
    this->AddError("The medium is null; a vtkImageData with Refracta point arrays is required.");
    return false;
  }
  this->CheckGeometry(medium);
  if (!this->Errors.empty())
  {
    return false; // array checks are meaningless on a broken grid
  }

  int numberPresent = 0;
  for (int id = 0; id < vtkRefractaMedium::NUMBER_OF_ARRAYS; ++id)
  {
    if (this->CheckArrayLayout(medium, id))
    {
      ++numberPresent;
      this->CheckArrayValues(
        medium, medium->GetPointData()->GetArray(vtkRefractaMedium::GetArrayName(id)), id);
    }
  }
  if (numberPresent == 0 && this->RequireMediumArray && this->Errors.empty())
  {
    std::ostringstream msg;
    msg << "The image carries none of the medium point arrays (RefractiveIndex, "
           "RefractiveIndexGradient, Extinction, Albedo, Anisotropy, Emission, Occupancy); map a "
           "scalar field to a medium first (e.g. through transfer functions).";
    this->AddError(msg.str());
  }
  return this->Errors.empty();
}

//------------------------------------------------------------------------------
void vtkMediumValidator::CheckGeometry(vtkImageData* medium)
{
  int dims[3];
  medium->GetDimensions(dims);
  if (medium->GetNumberOfPoints() <= 0 || dims[0] < 1 || dims[1] < 1 || dims[2] < 1)
  {
    std::ostringstream msg;
    msg << "The medium grid is empty (dimensions " << dims[0] << " x " << dims[1] << " x "
        << dims[2] << "); every dimension must be at least 1.";
    this->AddError(msg.str());
    return;
  }
  const double* spacing = medium->GetSpacing();
  for (int a = 0; a < 3; ++a)
  {
    if (!std::isfinite(spacing[a]) || spacing[a] <= 0.0)
    {
      std::ostringstream msg;
      msg << "The medium spacing (" << spacing[0] << ", " << spacing[1] << ", " << spacing[2]
          << ") is invalid along axis " << a << "; each spacing must be finite and > 0.";
      this->AddError(msg.str());
      break;
    }
    if (spacing[a] < MinimumSpacing || spacing[a] > MaximumSpacing)
    {
      // The kernels work in float: voxel volumes and per-volume deposits under- or overflow
      // beyond these (the photon pass deposits nothing at a spacing of 1e-16).
      std::ostringstream msg;
      msg << "The medium spacing (" << spacing[0] << ", " << spacing[1] << ", " << spacing[2]
          << ") is outside [" << MinimumSpacing << ", " << MaximumSpacing << "] along axis " << a
          << ", where the passes' float arithmetic stays exact; express the grid in other units "
             "(micrometres instead of metres, say; coefficients scale inversely).";
      this->AddError(msg.str());
      break;
    }
  }
  const double* origin = medium->GetOrigin();
  if (!std::isfinite(origin[0]) || !std::isfinite(origin[1]) || !std::isfinite(origin[2]))
  {
    std::ostringstream msg;
    msg << "The medium origin (" << origin[0] << ", " << origin[1] << ", " << origin[2]
        << ") is not finite.";
    this->AddError(msg.str());
  }
  vtkMatrix3x3* direction = medium->GetDirectionMatrix();
  const double det = direction->Determinant();
  if (!std::isfinite(det) || std::abs(det) < 1e-12)
  {
    this->AddError("The medium direction matrix is singular or not finite; it must be a "
                   "rotation (orthonormal).");
  }
  else
  {
    // The grid-local frame (vtkRefractaGridFrame) keeps world units only for an orthonormal D.
    double worst = 0.0;
    for (int r = 0; r < 3; ++r)
    {
      for (int c = 0; c < 3; ++c)
      {
        double dot = 0.0;
        for (int k = 0; k < 3; ++k)
        {
          dot += direction->GetElement(k, r) * direction->GetElement(k, c);
        }
        worst = std::max(worst, std::abs(dot - (r == c ? 1.0 : 0.0)));
      }
    }
    if (worst > 1e-6)
    {
      std::ostringstream msg;
      msg << "The medium direction matrix is not orthonormal (D^T D differs from the identity by "
          << worst << "); it must be a rotation (or reflection): put scale in the spacing.";
      this->AddError(msg.str());
    }
  }
}

//------------------------------------------------------------------------------
bool vtkMediumValidator::CheckArrayLayout(vtkImageData* medium, int id)
{
  const char* name = vtkRefractaMedium::GetArrayName(id);
  vtkAbstractArray* abstract = medium->GetPointData()->GetAbstractArray(name);
  if (!abstract)
  {
    if (medium->GetCellData()->GetAbstractArray(name))
    {
      std::ostringstream msg;
      msg << "Medium array '" << name << "' is cell data; Refracta media store arrays as point "
          << "data (values at voxel centres). Convert it with vtkCellDataToPointData or rebuild "
          << "the image with one more point per axis.";
      this->AddError(msg.str());
    }
    return false;
  }
  std::ostringstream msg;
  msg << "Medium array '" << name << "' ";
  vtkDataArray* array = vtkDataArray::SafeDownCast(abstract);
  const int expected = vtkRefractaMedium::GetNumberOfComponents(id);
  if (!array)
  {
    msg << "is a " << abstract->GetClassName() << "; it must be a numeric vtkDataArray.";
  }
  else if (array->GetNumberOfComponents() != expected)
  {
    msg << "has " << array->GetNumberOfComponents() << " component(s); it must have " << expected
        << ".";
  }
  else if (array->GetNumberOfTuples() != medium->GetNumberOfPoints())
  {
    msg << "has " << array->GetNumberOfTuples() << " tuples but the grid has "
        << medium->GetNumberOfPoints() << " points; they must be equal.";
  }
  else
  {
    return true;
  }
  this->AddError(msg.str());
  return false;
}

//------------------------------------------------------------------------------
void vtkMediumValidator::CheckArrayValues(vtkImageData* medium, vtkDataArray* array, int id)
{
  if (ScanCache().Contains(array, id))
  {
    return;
  }
  InvalidValueScan scan;
  scan.ArrayId = id;
  if (!vtkArrayDispatch::Dispatch::Execute(array, scan))
  {
    scan(array); // uncommon array type: go through the generic vtkDataArray API
  }
  if (scan.NumberInvalid == 0)
  {
    ScanCache().Add(array, id);
    return;
  }
  const int nc = array->GetNumberOfComponents();
  const vtkIdType pointId = scan.FirstInvalidIndex / nc;
  const int component = static_cast<int>(scan.FirstInvalidIndex % nc);
  int dims[3];
  medium->GetDimensions(dims);
  const vtkIdType i = pointId % dims[0];
  const vtkIdType j = (pointId / dims[0]) % dims[1];
  const vtkIdType k = pointId / (static_cast<vtkIdType>(dims[0]) * dims[1]);

  std::ostringstream msg;
  msg << "Medium array '" << vtkRefractaMedium::GetArrayName(id) << "' has " << scan.NumberInvalid
      << " invalid value(s) of " << array->GetNumberOfValues() << "; the first is "
      << scan.FirstInvalidValue << " at voxel (" << i << ", " << j << ", " << k << ")";
  if (nc > 1)
  {
    msg << ", component " << component;
  }
  msg << ". Values must be " << vtkRefractaMedium::GetValidRangeDescription(id) << ".";
  this->AddError(msg.str());
}

//------------------------------------------------------------------------------
void vtkMediumValidator::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "RequireMediumArray: " << this->RequireMediumArray << "\n";
  os << indent << "NumberOfErrors: " << this->Errors.size() << "\n";
  for (const auto& e : this->Errors)
  {
    os << indent.GetNextIndent() << e << "\n";
  }
}

//------------------------------------------------------------------------------
bool vtkMediumValidator::CheckLight(vtkLight* light, int index, std::string& error)
{
  double pw[3], fw[3], colour[3];
  light->GetTransformedPosition(pw);
  light->GetTransformedFocalPoint(fw);
  light->GetDiffuseColor(colour);
  const double intensity = light->GetIntensity();
  bool finite = std::isfinite(intensity);
  for (int c = 0; c < 3; ++c)
  {
    finite = finite && std::isfinite(pw[c]) && std::isfinite(fw[c]) && std::isfinite(colour[c]);
  }
  if (!finite || intensity < 0 || colour[0] < 0 || colour[1] < 0 || colour[2] < 0)
  {
    std::ostringstream os;
    os << "Light " << index
       << " has a non-finite position, focal point, colour or intensity, or a negative intensity "
          "or colour; all must be finite and >= 0.";
    error = os.str();
    return false;
  }
  return true;
}
