/**
 * @class   vtkRefractaMedium
 * @brief   The conventions of a Refracta medium: array names, component counts, units, defaults.
 *
 * A Refracta medium is a vtkImageData whose point data carries the arrays below. Values live at
 * the grid points (voxel centres); the passes interpolate them trilinearly. Lengths are the
 * image's world units (origin, spacing and direction matrix honoured) and coefficients are per
 * world unit. Every array is optional; a missing one takes the default listed here, but a medium
 * must carry at least one of them (otherwise it is some other image, e.g. an unmapped CT scan).
 *
 * | array                     | comps | unit / range                  | default            |
 * |---------------------------|-------|-------------------------------|--------------------|
 * | RefractiveIndex           | 1     | n >= 1                        | 1                  |
 * | RefractiveIndexGradient   | 3     | 1 / world unit                | central differences of n |
 * | Extinction                | 3     | sigma_t >= 0, 1 / world unit  | 0 (RGB)            |
 * | Albedo                    | 3     | sigma_s / sigma_t in [0, 1]   | 0 (RGB)            |
 * | Anisotropy                | 1     | Henyey-Greenstein g, abs(g)<1 | 0                  |
 * | Emission                  | 3     | radiance / world unit, >= 0   | 0 (RGB)            |
 * | Occupancy                 | 1     | fraction of voxel, [0, 1]     | 1                  |
 *
 * This class only holds the conventions (static methods); it is never instantiated by the
 * passes, but New() exists so that it can be wrapped and printed.
 */
#ifndef vtkRefractaMedium_h
#define vtkRefractaMedium_h

#include "RefractaCoreModule.h" // for export macro
#include "vtkObject.h"
#include "vtkSmartPointer.h" // for NewArrayOrNull

#include <vector> // for std::vector

class vtkDataArray;
class vtkFloatArray;
class vtkImageData;

class REFRACTACORE_EXPORT vtkRefractaMedium : public vtkObject
{
public:
  static vtkRefractaMedium* New();
  vtkTypeMacro(vtkRefractaMedium, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Identifiers of the medium arrays, in the order of the table above.
   */
  enum ArrayId
  {
    REFRACTIVE_INDEX = 0,
    REFRACTIVE_INDEX_GRADIENT,
    EXTINCTION,
    ALBEDO,
    ANISOTROPY,
    EMISSION,
    OCCUPANCY,
    NUMBER_OF_ARRAYS
  };

  ///@{
  /**
   * Array names as they appear in the point data.
   */
  static const char* RefractiveIndexName() { return "RefractiveIndex"; }
  static const char* RefractiveIndexGradientName() { return "RefractiveIndexGradient"; }
  static const char* ExtinctionName() { return "Extinction"; }
  static const char* AlbedoName() { return "Albedo"; }
  static const char* AnisotropyName() { return "Anisotropy"; }
  static const char* EmissionName() { return "Emission"; }
  static const char* OccupancyName() { return "Occupancy"; }

  ///@}

  ///@{
  /**
   * Field-data arrays of a medium voxelized with exact dielectric interfaces
   * (vtkMeshVoxelizer::EXACT_INTERFACES; read by vtkRefractaSurfaceSet::AddMediumInterfaces):
   * InterfacePoints (double, 3 components, the medium's data coordinates), InterfaceTriangles
   * (vtkIdType, 3 point ids per triangle, wound with the normal outwards) and InterfaceIndices
   * (double, 2 components per triangle: refractive index inside, outside). Optional,
   * InterfaceMaterials (double, InterfaceMaterialComponents = 11 components per triangle: the
   * homogeneous medium filling the mesh's inside, extinction RGB (1 / world unit, >= 0), albedo
   * RGB ([0, 1]), anisotropy g ((-1, 1)), emission RGB (>= 0), then 1 when the inside is that
   * homogeneous medium or 0 when the passes must use the grid inside (a material with a density
   * field); see vtkRefractaSurfaceMaterial::UseInsideMedium and Physics.md "Glass bodies").
   */
  static const char* InterfacePointsName() { return "InterfacePoints"; }
  static const char* InterfaceTrianglesName() { return "InterfaceTriangles"; }
  static const char* InterfaceIndicesName() { return "InterfaceIndices"; }
  static const char* InterfaceMaterialsName() { return "InterfaceMaterials"; }
  static constexpr int InterfaceMaterialComponents = 11;

  /**
   * The largest refractive index a medium, a material or a surface may have (100; every real
   * material at optical wavelengths is below 5). Beyond it the index gradient and the Fresnel
   * terms lose their float precision.
   */
  static constexpr double MaximumRefractiveIndex = 100.0;
  ///@}

  /**
   * Name of the array with the given id, or nullptr for an id out of range.
   */
  static const char* GetArrayName(int id);

  /**
   * Id of the array with the given name, or -1 if the name is not a medium array.
   */
  static int GetArrayId(const char* name);

  /**
   * Number of components the array must have (1 or 3), or 0 for an id out of range.
   */
  static int GetNumberOfComponents(int id);

  /**
   * Value every component takes when the array is missing. The gradient's default is 0 here;
   * passes that need it compute it from RefractiveIndex when that array exists.
   */
  static double GetDefaultValue(int id);

  /**
   * Smallest and largest valid value of a component (inclusive unless noted in
   * IsValueValid), used by vtkMediumValidator.
   */
  static void GetValidRange(int id, double range[2]);

  /**
   * True when `value` is a valid component value for array `id` (finite, and within the valid
   * range; Anisotropy excludes -1 and 1).
   */
  static bool IsValueValid(int id, double value);

  /**
   * Human-readable statement of the valid range, e.g. "finite and >= 1".
   */
  static const char* GetValidRangeDescription(int id);

#ifndef __VTK_WRAP__
  /**
   * The point array `name` of `image` as interleaved floats (`components` per point), or every
   * value `fallback` when the array is missing or has another shape. For passes that upload a
   * medium to a device.
   */
  static std::vector<float> ReadArray(
    vtkImageData* image, const char* name, int components, float fallback);

  /**
   * The same for medium array `id`, with its documented default as the fallback.
   */
  static std::vector<float> ReadArray(vtkImageData* image, int id);

  /**
   * `array` as `tuples` x `components` interleaved floats into `out` (resized), or every value
   * `fallback` when the array is null or has another shape. Float arrays are copied as memory,
   * others converted in parallel (vtkSMPTools).
   */
  static void ReadArray(
    vtkDataArray* array, vtkIdType tuples, int components, float fallback, std::vector<float>& out);

  /**
   * Whether interleaved RGB values (3 per point, as ReadArray gives them) are grey: the three
   * channels equal at every point. Passes then keep one value per point on the device.
   */
  static bool IsGrey(const std::vector<float>& rgb);

  /**
   * A new float array for medium array `id` (its name and number of components) with `tuples`
   * tuples, values not initialised; nullptr when the memory cannot be had. The values are
   * allocated here and handed to the array: VTK's own allocation path aborts the process when an
   * allocation fails under a process memory limit, where a filter must instead report that the
   * grid is too large (vtkMeshVoxelizer, vtkTransferFunctionMedium).
   */
  static vtkSmartPointer<vtkFloatArray> NewArrayOrNull(int id, vtkIdType tuples);
#endif

  /**
   * Gives every voxel without extinction (in a channel) the albedo of its neighbours that have
   * some: their mean over the 26-neighbourhood, weighted by their extinction. Such a voxel's
   * albedo means nothing by itself, but the passes interpolate albedo and extinction separately,
   * so between clear glass (extinction 0, albedo 0 by default) and a white fog (albedo 1) the
   * interpolated albedo fell below 1 where the interpolated extinction is not 0: the fog's rim
   * absorbed light it cannot absorb (0.3 to 0.8% of an albedo-1 scene's power). After
   * the fill the interpolated albedo there is the fog's, as sigma_s / sigma_t interpolated would
   * be. The albedo array is replaced by a filled copy (the input's array is never written);
   * nothing changes without Extinction and Albedo arrays of 3 components, or where no voxel
   * needs it. Returns the number of voxel channels filled.
   */
  static vtkIdType FillAlbedoWithoutExtinction(vtkImageData* medium);

protected:
  vtkRefractaMedium() = default;
  ~vtkRefractaMedium() override = default;

private:
  vtkRefractaMedium(const vtkRefractaMedium&) = delete;
  void operator=(const vtkRefractaMedium&) = delete;
};

#endif
