/**
 * @class   vtkMediumMaterial
 * @brief   Optical properties of one homogeneous material of a Refracta medium.
 *
 * A material is what a closed mesh is filled with when it is voxelized (vtkMeshVoxelizer), and
 * what the space around the meshes is filled with. Coefficients are per world unit of the medium
 * the material ends up in; colours are linear RGB.
 *
 * - RefractiveIndex: n, in [1, 100]; default 1 (vacuum).
 * - Extinction: sigma_t per RGB channel, >= 0, 1 / world unit; default (0, 0, 0).
 * - Albedo: single-scattering albedo sigma_s / sigma_t per channel, in [0, 1]; default (0, 0, 0).
 * - Anisotropy: Henyey-Greenstein g in [-0.9999, 0.9999]; default 0 (isotropic).
 * - Emission: emitted radiance per world unit of path length, per channel, >= 0; default 0.
 *
 * Finite values outside the valid ranges are clamped by the setters (vtkSetClampMacro semantics;
 * coefficients at most MaximumCoefficient, 1e30 per world unit, beyond which everything is opaque
 * within a float's precision); a NaN (or an infinite colour channel) is an error (vtkErrorMacro
 * naming the property) and leaves the property unchanged (vtkRefractaSettings.h). So a material
 * is always valid.
 *
 * **Heterogeneous materials.** A material may carry a dimensionless density field d(x) >= 0 (for
 * example a particle density), given either as a vtkImplicitFunction (DensityFunction, evaluated
 * at the point) or as a point-data array of a vtkImageData (DensityImage + DensityArrayName,
 * trilinear between the image's points, 0 outside its bounds). Without either, d = 1 everywhere.
 * Negative or NaN values of d count as 0. The density scales the extinction and the emission at a
 * point: sigma_t(x) = d(x) Extinction, eps(x) = d(x) Emission; albedo and anisotropy are
 * unchanged. When DensityScalesRefractiveIndex is on (default off), the refractive index follows
 * the Gladstone-Dale relation n(x) = 1 + d(x) (RefractiveIndex - 1). EvaluateDensity() and
 * EvaluateProperties() give the values at a point; they are safe to call from several threads at
 * once provided the implicit function is (VTK's analytic ones are).
 */
#ifndef vtkMediumMaterial_h
#define vtkMediumMaterial_h

#include "RefractaCoreModule.h" // for export macro
#include "vtkObject.h"

#include <string> // for std::string

class vtkDataArray;
class vtkImageData;
class vtkImplicitFunction;

class REFRACTACORE_EXPORT vtkMediumMaterial : public vtkObject
{
public:
  static vtkMediumMaterial* New();
  vtkTypeMacro(vtkMediumMaterial, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Refractive index n (dimensionless), clamped to [1, 100]. Default 1.
   */
  void SetRefractiveIndex(double n);
  vtkGetMacro(RefractiveIndex, double);
  ///@}

  ///@{
  /**
   * Extinction coefficient sigma_t per RGB channel (1 / world unit), each clamped to
   * [0, MaximumCoefficient]. Default (0, 0, 0).
   */
  void SetExtinction(double r, double g, double b);
  void SetExtinction(const double rgb[3]) { this->SetExtinction(rgb[0], rgb[1], rgb[2]); }
  vtkGetVector3Macro(Extinction, double);
  ///@}

  ///@{
  /**
   * Single-scattering albedo sigma_s / sigma_t per RGB channel, each clamped to [0, 1].
   * Default (0, 0, 0): a pure absorber.
   */
  void SetAlbedo(double r, double g, double b);
  void SetAlbedo(const double rgb[3]) { this->SetAlbedo(rgb[0], rgb[1], rgb[2]); }
  vtkGetVector3Macro(Albedo, double);
  ///@}

  ///@{
  /**
   * Henyey-Greenstein anisotropy g, clamped to [-0.9999, 0.9999] (the phase function is a delta
   * at +-1). Positive values scatter forward. Default 0.
   */
  void SetAnisotropy(double g);
  vtkGetMacro(Anisotropy, double);
  ///@}

  ///@{
  /**
   * Emitted radiance per world unit of path length per RGB channel, each clamped to
   * [0, MaximumCoefficient]. Default (0, 0, 0).
   */
  void SetEmission(double r, double g, double b);
  void SetEmission(const double rgb[3]) { this->SetEmission(rgb[0], rgb[1], rgb[2]); }
  vtkGetVector3Macro(Emission, double);
  ///@}

  /**
   * Scattering coefficient sigma_s = albedo * sigma_t per channel (1 / world unit).
   */
  void GetScattering(double rgb[3]) const;

  /**
   * The largest extinction or emission coefficient a setter keeps (1e30 per world unit): a float
   * holds it with room for a density field up to 1e8 (vtkMeshVoxelizer rejects a medium whose
   * coefficient times density overflows a float).
   */
  static constexpr double MaximumCoefficient = 1e30;

  ///@{
  /**
   * Density field given by an implicit function (dimensionless, values < 0 count as 0). Takes
   * precedence over DensityImage when both are set. Default nullptr (d = 1).
   */
  void SetDensityFunction(vtkImplicitFunction* function);
  vtkGetObjectMacro(DensityFunction, vtkImplicitFunction);
  ///@}

  ///@{
  /**
   * Density field given by the point-data array DensityArrayName (first component) of an image,
   * interpolated trilinearly at a point (the image's origin, spacing, extent and direction matrix
   * honoured, as vtkImageData::TransformPhysicalPointToContinuousIndex); 0 outside the image.
   * Default nullptr (d = 1).
   */
  void SetDensityImage(vtkImageData* image);
  vtkGetObjectMacro(DensityImage, vtkImageData);
  vtkSetStringMacro(DensityArrayName);
  vtkGetStringMacro(DensityArrayName);
  ///@}

  ///@{
  /**
   * When on, the density also scales n - 1 (Gladstone-Dale). Default off.
   */
  vtkSetMacro(DensityScalesRefractiveIndex, bool);
  vtkGetMacro(DensityScalesRefractiveIndex, bool);
  vtkBooleanMacro(DensityScalesRefractiveIndex, bool);
  ///@}

  /**
   * True when the material has a density field (a function, or an image with its array).
   */
  bool IsHeterogeneous() const;

  /**
   * Check that the density field can be evaluated: an image density needs a non-empty
   * DensityArrayName naming a numeric point-data array of the image. Returns false and fills `why`
   * otherwise. A homogeneous material is always usable.
   */
  bool CheckDensity(std::string& why) const;

  /**
   * Density d(x) at a world point x (1 for a homogeneous material; >= 0 and finite otherwise).
   */
  double EvaluateDensity(const double x[3]) const;

  /**
   * The material's properties with a given density d applied (see the class documentation):
   * n, sigma_t (RGB), albedo (RGB), g, emission (RGB).
   */
  void GetPropertiesAtDensity(double d, double& n, double extinction[3], double albedo[3],
    double& g, double emission[3]) const;

  /**
   * Copy every property from another material (the density field objects are shared, not
   * copied).
   */
  void DeepCopy(vtkMediumMaterial* other);

  /**
   * Modification time including the density function's and image's.
   */
  vtkMTimeType GetMTime() override;

protected:
  vtkMediumMaterial() = default;
  ~vtkMediumMaterial() override;

  double RefractiveIndex = 1.0;
  double Extinction[3] = { 0.0, 0.0, 0.0 };
  double Albedo[3] = { 0.0, 0.0, 0.0 };
  double Anisotropy = 0.0;
  double Emission[3] = { 0.0, 0.0, 0.0 };
  vtkImplicitFunction* DensityFunction = nullptr;
  vtkImageData* DensityImage = nullptr;
  char* DensityArrayName = nullptr;
  bool DensityScalesRefractiveIndex = false;

private:
  vtkMediumMaterial(const vtkMediumMaterial&) = delete;
  void operator=(const vtkMediumMaterial&) = delete;

  void SetRGB(const char* property, double target[3], double r, double g, double b, double hi);
};

#endif
