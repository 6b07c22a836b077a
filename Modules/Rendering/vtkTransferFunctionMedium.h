/**
 * @class   vtkTransferFunctionMedium
 * @brief   Maps a scalar vtkImageData (CT scan, simulation field) through a vtkVolumeProperty's
 *          transfer functions to a Refracta medium.
 *
 * The mapping (per grid point, s the input's scalar; multi-component scalars below):
 * - **Extinction** (RGB, equal channels) from the scalar opacity function a(s), read as VTK reads
 *   it: the opacity of a slab ScalarOpacityUnitDistance d thick. So
 *   sigma_t = -ln(1 - a) / d, with a clamped to 1 - 1e-6 (sigma_t <= 13.8 / d). An image made with
 *   vtkGPUVolumeRayCastMapper and the same property therefore has the same transmittance per
 *   unit length; Refracta's box reaches half a voxel beyond the outer grid points (its voxels
 *   are centred on them, Documentation/Physics.md "Geometry"), so a ray across N points runs N
 *   spacings, not VTK's N - 1: exp(-sigma N h) against exp(-sigma (N - 1) h), a difference that
 *   shows on small grids (measured 0.475 against 0.490 across 21 points).
 * - **Albedo** (RGB) = the colour transfer function (or the grey function) at s, clamped to
 *   [0, 1]: what fraction of the extinguished light is scattered, per channel.
 * - **Anisotropy** (Henyey-Greenstein g) = the Anisotropy knob, default 0. (VTK 9.1's
 *   vtkVolumeProperty has no scattering anisotropy; with VTK >= 9.2 the property's
 *   GetScatteringAnisotropy() is used when this knob is left at 0.)
 * - **RefractiveIndex** = RefractiveIndexFunction(s) (a vtkPiecewiseFunction added by Refracta),
 *   clamped to >= 1. Without it the index is 1 everywhere (straight rays).
 * - **Emission** (RGB) = EmissionScale * colour(s) * sigma_t. With EmissionScale = 1 and no
 *   lights this is the emission-absorption model of VTK's compositing ray casters
 *   (C = sum T a c), so an existing volume rendering looks the same. Default 0 (no emission).
 *
 * Multi-component scalars follow VTK's volume mappers (vtkVolumeProperty::IndependentComponents):
 * - independent components (2 to 4; on, VTK's default): component c through the property's
 *   functions of index c and its ComponentWeight w_c, as a mixture of species: sigma_t =
 *   sum w_c sigma_c, albedo = sum w_c sigma_c colour_c / sigma_t (the weighted mean colour where
 *   sigma_t = 0), emission = EmissionScale sum w_c sigma_c colour_c; the index function reads
 *   component 0;
 * - two dependent components: colour of component 0, opacity (and index) of component 1;
 * - four dependent components: RGB given by components 0..2 (integer types divided by their
 *   type's maximum, so 0..255 for unsigned char; floating point taken as it is, clamped to
 *   [0, 1]), opacity (and index) of component 3.
 * Other counts are errors naming the layouts that are valid. A NaN is missing data: in a
 * dependent layout the voxel is empty space; an independent species with a NaN (or of weight 0)
 * is left out of the mix, and the voxel is empty only when every species is.
 *
 * Output: a medium on the input's grid (origin, spacing and direction matrix copied) with the
 * arrays above. Cell scalars (SetInputArrayToProcess with FIELD_ASSOCIATION_CELLS, as a volume
 * mapper's SetScalarModeToUseCellData selects them) are values at the cells' centres, as VTK's
 * volume mappers read them: the medium's grid is then those centres, one point fewer along every
 * axis that has cells and half a spacing further in (the direction matrix applied), its box half a
 * cell smaller on every side than the input's cells. Errors (no property, no scalars, a
 * component layout VTK does not define, a scalar count other than the point (cell) count or an
 * empty image, infinite scalars, a unit distance that is not
 * finite and > 0, NaN Anisotropy or EmissionScale, transfer functions that give NaN, values
 * beyond the float range, or an image whose medium (28 to 44 bytes per point) does not fit in
 * memory): vtkErrorMacro naming the problem and what would be valid,
 * RequestData returns 0, the output is empty. A NaN scalar is missing data: its voxel is empty
 * space (no extinction or emission, n = 1), and one warning says how many there were.
 */
#ifndef vtkTransferFunctionMedium_h
#define vtkTransferFunctionMedium_h

#include "RefractaRenderingModule.h" // for export macro
#include "vtkImageAlgorithm.h"
#include "vtkSmartPointer.h" // for members

class vtkDataArray;
class vtkInformation;
class vtkImageData;
class vtkPiecewiseFunction;
class vtkVolumeProperty;

class REFRACTARENDERING_EXPORT vtkTransferFunctionMedium : public vtkImageAlgorithm
{
public:
  static vtkTransferFunctionMedium* New();
  vtkTypeMacro(vtkTransferFunctionMedium, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The volume property whose scalar opacity and colour functions are used. Required.
   */
  void SetVolumeProperty(vtkVolumeProperty* property);
  vtkVolumeProperty* GetVolumeProperty();
  ///@}

  ///@{
  /**
   * Scalar -> refractive index. nullptr (default): n = 1.
   */
  void SetRefractiveIndexFunction(vtkPiecewiseFunction* function);
  vtkPiecewiseFunction* GetRefractiveIndexFunction();
  ///@}

  ///@{
  /**
   * Henyey-Greenstein g, clamped to [-0.9999, 0.9999]. Default 0.
   */
  void SetAnisotropy(double value);
  vtkGetMacro(Anisotropy, double);
  ///@}

  ///@{
  /**
   * Emission = EmissionScale * colour * sigma_t; >= 0. Default 0.
   */
  void SetEmissionScale(double value);
  vtkGetMacro(EmissionScale, double);
  ///@}

  vtkMTimeType GetMTime() override;

  /**
   * The grid of the cell centres of an image (its extent, origin, spacing and direction matrix,
   * row-major), where the medium of cell scalars lies: along every axis with cells one point
   * fewer, the origin half a spacing further in through the direction matrix. `extent` and
   * `origin` are changed in place.
   */
  static void ComputeCellCentreGrid(
    int extent[6], double origin[3], const double spacing[3], const double direction[9]);

  /**
   * Sets the image information of a pipeline output (WHOLE_EXTENT, ORIGIN, SPACING, DIRECTION)
   * to the grid of the cell centres of the input's (read from `inInfo`), as RequestInformation
   * announces it for cell scalars (for filters that wrap this one).
   */
  static void AnnounceCellCentreGrid(vtkInformation* inInfo, vtkInformation* outInfo);

protected:
  vtkTransferFunctionMedium();
  ~vtkTransferFunctionMedium() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  /**
   * The checks that do not depend on the scalars' values; false (with an error) when the
   * mapping cannot run. `cells`: the scalars are cell data.
   */
  bool CheckInputs(vtkImageData* input, vtkDataArray* scalars, bool cells);

  /// Whether the array to process is cell data (FIELD_ASSOCIATION_CELLS).
  bool MapsCellScalars();

  vtkSmartPointer<vtkVolumeProperty> VolumeProperty;
  vtkSmartPointer<vtkPiecewiseFunction> RefractiveIndexFunction;
  double Anisotropy = 0.0;
  double EmissionScale = 0.0;

private:
  vtkTransferFunctionMedium(const vtkTransferFunctionMedium&) = delete;
  void operator=(const vtkTransferFunctionMedium&) = delete;
};

#endif
