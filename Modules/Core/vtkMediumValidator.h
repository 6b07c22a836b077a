/**
 * @class   vtkMediumValidator
 * @brief   Checks that a vtkImageData is a valid Refracta medium, and says exactly why not.
 *
 * Any filter that consumes a medium calls Validate() on its input before doing work. The
 * validator rejects, with one message per problem:
 * - a null or empty image, a spacing that is not finite and positive or lies outside
 *   [MinimumSpacing, MaximumSpacing] (1e-12 to 1e18 world units, where the passes' float
 *   arithmetic holds), an origin or direction matrix that is not finite (or a singular
 *   direction matrix);
 * - an image that carries none of the medium arrays (see vtkRefractaMedium), unless
 *   RequireMediumArray is off;
 * - a medium array stored as cell data instead of point data, one that is not numeric, one with
 *   the wrong number of components or tuples;
 * - values that are NaN or infinite, negative coefficients, a refractive index below 1, an
 *   albedo or occupancy outside [0, 1], a Henyey-Greenstein g with abs(g) >= 1.
 * A message names the array, the number of bad values, and the first bad voxel (i, j, k), its
 * component and value, and what would be valid.
 *
 * Every pass validates its input, so one render validates the same medium several times. The
 * value scan (the only part that reads every voxel) is remembered, process-wide, for arrays that
 * passed: an array whose address and modification time (vtkObject::GetMTime(), which VTK bumps on
 * every Modified() and which no other object shares) match a passed scan is not read again. This
 * follows VTK's own convention (vtkDataArray::GetRange() caches the same way): code that writes
 * into an array's memory must call Modified() on it.
 *
 * @code
 * vtkNew<vtkMediumValidator> validator;
 * if (!validator->Validate(medium))
 * {
 *   vtkErrorMacro("Input is not a valid medium: " << validator->GetErrorMessage());
 *   return 0;
 * }
 * @endcode
 */
#ifndef vtkMediumValidator_h
#define vtkMediumValidator_h

#include "RefractaCoreModule.h" // for export macro
#include "vtkObject.h"

#include <string> // for std::string
#include <vector> // for std::vector

class vtkDataArray;
class vtkImageData;
class vtkLight;

class REFRACTACORE_EXPORT vtkMediumValidator : public vtkObject
{
public:
  static vtkMediumValidator* New();
  vtkTypeMacro(vtkMediumValidator, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The range of spacings a medium may have (world units).
   */
  static constexpr double MinimumSpacing = 1e-12;
  static constexpr double MaximumSpacing = 1e18;
  ///@}

  /**
   * Check `medium`. Returns true when it is valid; otherwise GetErrorMessage() lists every
   * problem found (at most one message per array). Does not modify the medium.
   */
  bool Validate(vtkImageData* medium);

  /**
   * Whether a switched-on light can emit: a finite position, focal point, colour and intensity,
   * and no negative intensity or colour. When not, `error` says so, naming the light by `index`
   * (its place in the caller's list). Every light pass checks its lights with this.
   */
  static bool CheckLight(vtkLight* light, int index, std::string& error);

  /**
   * All problems found by the last Validate(), one per line; empty when it passed.
   */
  const char* GetErrorMessage() const { return this->ErrorMessage.c_str(); }

  /**
   * Number of problems found by the last Validate().
   */
  int GetNumberOfErrors() const { return static_cast<int>(this->Errors.size()); }

  /**
   * The i-th problem found by the last Validate(), or nullptr when out of range.
   */
  const char* GetError(int i) const;

  ///@{
  /**
   * When on (default), an image with none of the medium arrays is rejected: it is most likely a
   * scalar field that has not been mapped to a medium yet.
   */
  vtkSetMacro(RequireMediumArray, bool);
  vtkGetMacro(RequireMediumArray, bool);
  vtkBooleanMacro(RequireMediumArray, bool);
  ///@}

protected:
  vtkMediumValidator() = default;
  ~vtkMediumValidator() override = default;

  void AddError(const std::string& message);
  void CheckGeometry(vtkImageData* medium);
  bool CheckArrayLayout(vtkImageData* medium, int id);
  void CheckArrayValues(vtkImageData* medium, vtkDataArray* array, int id);

  bool RequireMediumArray = true;
  std::vector<std::string> Errors;
  std::string ErrorMessage;

private:
  vtkMediumValidator(const vtkMediumValidator&) = delete;
  void operator=(const vtkMediumValidator&) = delete;
};

#endif
