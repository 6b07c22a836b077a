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
 * Values outside the valid ranges are clamped by the setters (vtkSetClampMacro semantics), so a
 * material is always valid.
 */
#ifndef vtkMediumMaterial_h
#define vtkMediumMaterial_h

#include "RefractaCoreModule.h" // for export macro
#include "vtkObject.h"

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
  vtkSetClampMacro(RefractiveIndex, double, 1.0, 100.0);
  vtkGetMacro(RefractiveIndex, double);
  ///@}

  ///@{
  /**
   * Extinction coefficient sigma_t per RGB channel (1 / world unit), each clamped to >= 0.
   * Default (0, 0, 0).
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
  vtkSetClampMacro(Anisotropy, double, -0.9999, 0.9999);
  vtkGetMacro(Anisotropy, double);
  ///@}

  ///@{
  /**
   * Emitted radiance per world unit of path length per RGB channel, each clamped to >= 0.
   * Default (0, 0, 0).
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
   * Copy every property from another material.
   */
  void DeepCopy(vtkMediumMaterial* other);

protected:
  vtkMediumMaterial() = default;
  ~vtkMediumMaterial() override = default;

  double RefractiveIndex = 1.0;
  double Extinction[3] = { 0.0, 0.0, 0.0 };
  double Albedo[3] = { 0.0, 0.0, 0.0 };
  double Anisotropy = 0.0;
  double Emission[3] = { 0.0, 0.0, 0.0 };

private:
  vtkMediumMaterial(const vtkMediumMaterial&) = delete;
  void operator=(const vtkMediumMaterial&) = delete;

  void SetClampedVector(double target[3], double r, double g, double b, double lo, double hi);
};

#endif
