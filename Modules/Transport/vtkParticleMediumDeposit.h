/**
 * @class   vtkParticleMediumDeposit
 * @brief   Deposits a particle medium (and its illumination network) onto a grid for the view pass.
 *
 * Input: particles with the arrays of vtkRefractaParticleMedium, optionally with the results of
 * vtkIlluminationNetwork (DirectFluence, DirectDirection, MultipleFluence). Output 0: a Refracta
 * medium (vtkRefractaMedium arrays Extinction, Albedo, Anisotropy, Emission; no refractive index:
 * refraction does not apply to particles, and the field array
 * vtkRefractaParticleMedium::DepositedParticlesName() says so to vtkSceneAnalysis and the effect
 * plan). Output 1: a lighting volume on the same grid
 * (vtkRefractaLightingVolume arrays), present when the input carries the network's results.
 *
 * Each particle's sphere is sampled exactly on SamplesPerAxis^3 points per voxel (default 2^3 = 8):
 * a voxel receives the fraction f of its sub-samples inside the sphere. Overlapping spheres add:
 * Extinction = sum f sigma_t, Albedo = sum f sigma_s / sum f sigma_t, Anisotropy = the
 * sigma_s-weighted mean g, Emission = sum f Le. The lighting volume carries the network's scattered
 * power: a particle scatters a alpha phi pi r^2 (alpha its opacity, phi its fluence, pi r^2 its
 * cross section), spread evenly over its sphere's volume, so Radiance (single scattering, from
 * DirectFluence, with RadianceDirection the light's travel direction) and MultipleScattering
 * (from MultipleFluence) integrate over the grid to exactly the network's scattered powers.
 *
 * The grid: SampleDimensions points (default 64^3) spanning ModelBounds; when ModelBounds is
 * not valid (default: min > max), the particles' bounds grown by their radii.
 *
 * Why a deposit and not splatting: the view pass (curved rays, surfaces, background,
 * environment, the mapper's compositing) then renders particle media and grid media alike and
 * together; the price is that the multiple-scattered part is rendered isotropically (single
 * scattering keeps its phase function through RadianceDirection). Measured
 * (BenchmarkParticleRendering, Documentation/Benchmarks.md "Particle media: deposit or
 * splatting"): from 64^3 on the deposit's image is as close to the path tracer as exact splatting
 * (13.1% and 13.0% on the paper's 1024-particle cloud, both the network's own error) and within
 * 4% of the splats.
 */
#ifndef vtkParticleMediumDeposit_h
#define vtkParticleMediumDeposit_h

#include "RefractaTransportModule.h" // for export macro
#include "vtkImageAlgorithm.h"

class REFRACTATRANSPORT_EXPORT vtkParticleMediumDeposit : public vtkImageAlgorithm
{
public:
  static vtkParticleMediumDeposit* New();
  vtkTypeMacro(vtkParticleMediumDeposit, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Grid points per axis, each >= 2. Default 64 64 64.
   */
  vtkSetVector3Macro(SampleDimensions, int);
  vtkGetVector3Macro(SampleDimensions, int);
  ///@}

  ///@{
  /**
   * World bounds of the grid (xmin xmax ymin ymax zmin zmax); invalid (default): automatic.
   */
  vtkSetVector6Macro(ModelBounds, double);
  vtkGetVector6Macro(ModelBounds, double);
  ///@}

  ///@{
  /**
   * Sub-samples per voxel axis for the sphere's occupancy, in [1, 8]. Default 2.
   */
  vtkSetClampMacro(SamplesPerAxis, int, 1, 8);
  vtkGetMacro(SamplesPerAxis, int);
  ///@}

  /** The medium (output 0) and the lighting volume (output 1). */
  vtkImageData* GetMediumOutput() { return this->GetOutput(0); }
  vtkImageData* GetLightingOutput() { return this->GetOutput(1); }

protected:
  vtkParticleMediumDeposit();
  ~vtkParticleMediumDeposit() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int SampleDimensions[3] = { 64, 64, 64 };
  double ModelBounds[6] = { 1, -1, 1, -1, 1, -1 };
  int SamplesPerAxis = 2;

private:
  vtkParticleMediumDeposit(const vtkParticleMediumDeposit&) = delete;
  void operator=(const vtkParticleMediumDeposit&) = delete;
};

#endif
