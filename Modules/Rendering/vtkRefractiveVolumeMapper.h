/**
 * @class   vtkRefractiveVolumeMapper
 * @brief   A vtkVolumeMapper that renders refraction, scattering, absorption and emission with
 *          Refracta's passes into an ordinary vtkRenderWindow.
 *
 * Set it on a vtkVolume in a vtkRenderer like any volume mapper. Its input is either a Refracta
 * medium (a vtkImageData carrying any of the vtkRefractaMedium arrays) or any scientific
 * vtkImageData with one scalar: then the vtkVolume's vtkVolumeProperty is mapped by
 * vtkTransferFunctionMedium (scalar opacity -> extinction, colour -> albedo, Anisotropy -> g,
 * RefractiveIndexFunction -> n, EmissionScale -> emission), so a user of
 * vtkGPUVolumeRayCastMapper switches by changing the mapper line.
 *
 * Stages and the cache rule:
 * 1. **Medium**: the input itself, or the transfer-function mapping. Re-run when the input, the
 *    volume property (including its transfer functions) or a medium setting of this mapper
 *    (RefractiveIndexFunction, Anisotropy, EmissionScale) changes.
 * 2. **Light passes**: the lighting volume for the renderer's lights (vtkLight, switched on;
 *    converted into the medium's frame through the vtkVolume's matrix): vtkPhotonTracer, then
 *    vtkLatticeBoltzmannLighting when MultipleScattering is on (default); skipped when nothing in
 *    the medium scatters. Re-run when the medium
 *    is rebuilt or any light changes (type, position, focal point, colour, intensity, cone angle,
 *    exponent, transform). A headlight or camera light moves with the camera, so for them a
 *    camera change is a light change. SetLightingData() supplies a precomputed lighting volume
 *    instead (then this stage never runs); without a light-pass implementation in the build and
 *    without lighting data, the image holds emission and absorption only.
 * 3. **View pass**: re-run when the camera, the viewport size, the depth buffer of the geometry
 *    drawn before the volume, a view setting, or an earlier stage changes; otherwise the previous
 *    image is drawn again.
 * GetNumberOfMediumBuilds(), GetNumberOfLightPassRuns() and GetNumberOfViewPassRuns() count the
 * executions, for tests and for users tuning interactivity.
 *
 * Compositing rule: VTK draws opaque geometry before volumes. The mapper reads the depth buffer
 * of that geometry, converts each pixel's depth to a path length along the pixel's view ray, and
 * stops the ray there; it then composites per RGB channel over the frame (two blended draws):
 *   pixel = Exposure * L_medium + T * pixel_before,  T = the path's RGB transmittance,
 * so geometry and background behind the medium are dimmed by the medium's transmittance, and
 * geometry in front of or inside the medium hides what is behind it.
 * What is behind the medium is not seen through refraction (the frame underneath is not bent),
 * and along curved rays the stopping length is the path length, exact for straight rays only.
 * Translucent geometry is ignored. The mapper writes no depth. Values are clamped to [0, 1] as
 * VTK's own shading is (no tone curve).
 */
#ifndef vtkRefractiveVolumeMapper_h
#define vtkRefractiveVolumeMapper_h

#include "RefractaRenderingModule.h" // for export macro
#include "vtkSmartPointer.h"         // for members
#include "vtkVolumeMapper.h"

#include <memory> // for std::unique_ptr

class vtkEffectPlan;
class vtkImageData;
class vtkOpenCLContext;
class vtkPiecewiseFunction;
class vtkRefractaViewPass;
class vtkSceneAnalysis;

class REFRACTARENDERING_EXPORT vtkRefractiveVolumeMapper : public vtkVolumeMapper
{
public:
  static vtkRefractiveVolumeMapper* New();
  vtkTypeMacro(vtkRefractiveVolumeMapper, vtkVolumeMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Run the stages that changed and draw the result. Called by the vtkVolume.
   */
  void Render(vtkRenderer* renderer, vtkVolume* volume) override;

  void ReleaseGraphicsResources(vtkWindow*) override;

  ///@{
  /**
   * Medium settings for scalar inputs (see vtkTransferFunctionMedium). RefractiveIndexFunction:
   * scalar -> n (default none: n = 1). Anisotropy: HG g (default 0). EmissionScale (default 0).
   */
  void SetRefractiveIndexFunction(vtkPiecewiseFunction* function);
  vtkPiecewiseFunction* GetRefractiveIndexFunction();
  vtkSetClampMacro(Anisotropy, double, -0.9999, 0.9999);
  vtkGetMacro(Anisotropy, double);
  vtkSetClampMacro(EmissionScale, double, 0.0, 1e30);
  vtkGetMacro(EmissionScale, double);
  ///@}

  ///@{
  /**
   * A precomputed lighting volume on the medium's grid (see vtkRefractaImageRenderer); replaces
   * the light passes. Default none.
   */
  void SetLightingData(vtkImageData* lighting);
  vtkImageData* GetLightingData();
  ///@}

  ///@{
  /**
   * Light-pass quality: photons traced per light (default 2^18) and the seed (default 1), used
   * when the build has the photon tracer.
   */
  vtkSetClampMacro(NumberOfPhotons, int, 1, 1 << 28);
  vtkGetMacro(NumberOfPhotons, int);
  vtkSetMacro(Seed, int);
  vtkGetMacro(Seed, int);
  ///@}

  ///@{
  /**
   * Run vtkLatticeBoltzmannLighting after the photon pass to add multiple scattering
   * (`MultipleScattering`, S_ms). Default on.
   */
  vtkSetMacro(MultipleScattering, bool);
  vtkGetMacro(MultipleScattering, bool);
  vtkBooleanMacro(MultipleScattering, bool);

  ///@{
  /**
   * The effect plan every render goes through (see vtkEffectPlan): set its tolerance or force an
   * effect on or off here. Refraction, absorption and emission prune the medium all passes see;
   * single and multiple scattering decide whether the photon and Lattice-Boltzmann passes run.
   * MultipleScattering off forces multiple scattering off on top of the plan.
   */
  vtkEffectPlan* GetEffectPlan();
  vtkSceneAnalysis* GetSceneAnalysis();
  ///@}

  /**
   * Apply a quality preset (vtkEffectPlan::DRAFT, INTERACTIVE or PRODUCTION): the plan's
   * tolerance, NumberOfPhotons and StepSize, and for the light passes the photon tracer's
   * minimum step and octree tolerance and the Lattice-Boltzmann tolerance and block size, all
   * as measured by BenchmarkAccuracyTime (README, "Accuracy and time"). Until it is called the
   * light passes use their classes' defaults. Setting NumberOfPhotons or StepSize afterwards
   * overrides those two.
   */
  void SetQuality(int quality);
  ///@}

  ///@{
  /**
   * View-pass settings (see vtkRefractaViewPass): StepSize in voxels (default 1), RayMode
   * (default AUTO), TransmittanceCutoff (default 1e-4), EmptySpaceSkipping (default on; the
   * occupancy grid is rebuilt only with the medium or the light passes, and the image is the
   * same up to float rounding either way).
   */
  void SetStepSize(double voxels);
  double GetStepSize();
  void SetRayMode(int mode);
  int GetRayMode();
  void SetTransmittanceCutoff(double cutoff);
  double GetTransmittanceCutoff();
  void SetEmptySpaceSkipping(bool on);
  bool GetEmptySpaceSkipping();
  void EmptySpaceSkippingOn() { this->SetEmptySpaceSkipping(true); }
  void EmptySpaceSkippingOff() { this->SetEmptySpaceSkipping(false); }
  ///@}

  ///@{
  /**
   * Multiplier on the medium's radiance before it is drawn, >= 0. Default 1.
   */
  vtkSetClampMacro(Exposure, double, 0.0, 1e30);
  vtkGetMacro(Exposure, double);
  ///@}

  ///@{
  /**
   * OpenCL context. Default vtkOpenCLContext::GetDefault().
   */
  void SetContext(vtkOpenCLContext* context);
  vtkOpenCLContext* GetContext();
  ///@}

  ///@{
  /**
   * Execution counters (see the class description).
   */
  vtkGetMacro(NumberOfMediumBuilds, int);
  vtkGetMacro(NumberOfLightPassRuns, int);
  vtkGetMacro(NumberOfViewPassRuns, int);
  ///@}

  /**
   * The medium used by the last render (the input or its mapping), or nullptr.
   */
  vtkImageData* GetMedium();

  /**
   * The lighting volume used by the last render, or nullptr.
   */
  vtkImageData* GetLighting();

  /**
   * The view pass (its statistics: GetLastSeconds(), GetLastTotalSteps()).
   */
  vtkRefractaViewPass* GetViewPass();

  /**
   * Whether this build has a light-pass implementation (the photon tracer).
   */
  static bool HasLightPasses();

protected:
  vtkRefractiveVolumeMapper();
  ~vtkRefractiveVolumeMapper() override;

  bool UpdateMedium(vtkVolume* volume);
  bool DecidePlan();
  bool UpdateLighting(vtkRenderer* renderer, vtkVolume* volume);

  double Anisotropy = 0.0;
  double EmissionScale = 0.0;
  double Exposure = 1.0;
  int NumberOfPhotons = 1 << 18;
  int Seed = 1;
  bool MultipleScattering = true;
  bool QualityPresetApplied = false; // light passes take the plan's recommended settings
  int NumberOfMediumBuilds = 0;
  int NumberOfLightPassRuns = 0;
  int NumberOfViewPassRuns = 0;

private:
  vtkRefractiveVolumeMapper(const vtkRefractiveVolumeMapper&) = delete;
  void operator=(const vtkRefractiveVolumeMapper&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
