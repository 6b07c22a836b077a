/**
 * @class   vtkRefractaParticleMedium
 * @brief   The conventions of a Refracta particle medium: array names, units, defaults, checks.
 *
 * A particle medium is a vtkPointSet (usually vtkPolyData) whose points are the particle centres
 * of Szirmay-Kalos et al.'s illumination networks (papers/002): each particle stands for a
 * sphere of the medium. Its point data carries:
 *
 * | array       | comps | unit / range                                   | default    |
 * |-------------|-------|------------------------------------------------|------------|
 * | Radius      | 1     | sphere radius r > 0, world units (required)    | -          |
 * | Extinction  | 3     | sigma_t >= 0 per world unit inside the sphere  | - (required)|
 * | Albedo      | 3     | sigma_s / sigma_t in [0, 1]                    | 0 (RGB)    |
 * | Anisotropy  | 1     | Henyey-Greenstein g, abs(g) < 1                | 0          |
 * | Emission    | 3     | emitted radiance per world unit, >= 0          | 0 (RGB)    |
 *
 * Extinction is a coefficient per world unit (the medium's unit, as in vtkRefractaMedium), not a
 * per-particle optical depth: the particle's optical depth along a line is sigma_t times its
 * mean chord 4 r / 3 (the mean chord of a sphere, 4 V / S), so that a cloud of spheres of volume
 * V each, n per unit volume, attenuates on average like a continuous medium of extinction
 * n V sigma_t (see Documentation/Physics.md, "Illumination networks").
 *
 * The illumination network (vtkIlluminationNetwork) writes its results as point data on a copy of
 * the particles: DirectFluenceName() (fluence of the attenuated light sources at the particle,
 * RGB, power per unit area), DirectDirectionName() (the unit direction that light travels at the
 * particle) and MultipleFluenceName() (fluence of the light scattered by other
 * particles and of the sky, (4 pi / D) sum_d I[p, d], RGB).
 *
 * Only static methods are used; New() exists so that it can be wrapped and printed.
 */
#ifndef vtkRefractaParticleMedium_h
#define vtkRefractaParticleMedium_h

#include "RefractaCoreModule.h" // for export macro
#include "vtkObject.h"

#include <cmath>  // for std::expm1
#include <string> // for std::string

class vtkPointSet;

class REFRACTACORE_EXPORT vtkRefractaParticleMedium : public vtkObject
{
public:
  static vtkRefractaParticleMedium* New();
  vtkTypeMacro(vtkRefractaParticleMedium, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Names of the input arrays (point data of the particles).
   */
  static const char* RadiusName() { return "Radius"; }
  static const char* ExtinctionName() { return "Extinction"; }
  static const char* AlbedoName() { return "Albedo"; }
  static const char* AnisotropyName() { return "Anisotropy"; }
  static const char* EmissionName() { return "Emission"; }
  ///@}

  ///@{
  /**
   * Names of the arrays the illumination network adds (see the class description).
   */
  static const char* DirectFluenceName() { return "DirectFluence"; }
  static const char* MultipleFluenceName() { return "MultipleFluence"; }
  static const char* DirectDirectionName() { return "DirectDirection"; }
  ///@}

  /**
   * Name of the field-data array (one value: the number of particles) that vtkParticleMediumDeposit
   * puts on the grid medium it makes, so that the scene analysis and the effect plan know the
   * medium holds particles (refraction does not apply to them).
   */
  static const char* DepositedParticlesName() { return "DepositedParticles"; }

  /**
   * Mean chord of a sphere of radius r, 4 r / 3: the length over which a particle's extinction
   * acts on a line that crosses it.
   */
  static double MeanChord(double radius) { return 4.0 * radius / 3.0; }

  /**
   * Power a particle scatters per unit of its volume and per unit fluence: a alpha pi r^2 / V,
   * with alpha = 1 - exp(-sigma_t MeanChord(r)) its opacity and V = 4 pi r^3 / 3 (one channel).
   * vtkParticleMediumDeposit spreads the network's light over the sphere with it.
   */
  static double ScatteringPerVolume(double extinction, double albedo, double radius)
  {
    const double alpha = -std::expm1(-extinction * MeanChord(radius));
    return albedo * alpha * 3.0 / (4.0 * radius); // pi r^2 / (4 pi r^3 / 3)
  }

  /**
   * Checks a particle set: at least one point, Radius (1 component, finite, > 0) and Extinction
   * (3 components, finite, >= 0) present, optional Albedo (3, in [0, 1]), Anisotropy (1,
   * abs(g) < 1) and Emission (3, finite, >= 0) with the right component counts and values, finite
   * point coordinates. Returns true when valid; otherwise false and `message` names the first
   * bad array or point and what would be valid.
   */
  static bool Validate(vtkPointSet* particles, std::string& message);

protected:
  vtkRefractaParticleMedium() = default;
  ~vtkRefractaParticleMedium() override = default;

private:
  vtkRefractaParticleMedium(const vtkRefractaParticleMedium&) = delete;
  void operator=(const vtkRefractaParticleMedium&) = delete;
};

#endif
