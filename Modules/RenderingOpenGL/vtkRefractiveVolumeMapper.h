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
 * Surfaces and background (see vtkRefractaActorSurfaces and vtkRefractaRendererBackground): the
 * renderer's visible opaque polydata actors become surfaces of the pipeline (their matrices,
 * their diffuse colour or mapped scalar colours as albedo), so light and view rays in the medium
 * meet them: glass shows them bent, inverted or magnified, lit by the medium's caustics and
 * shadowed by it. The renderer's background (colour, gradient, background texture, or the
 * environment texture with UseImageBasedLighting) is what a bent view ray sees when it escapes.
 * ActorSurfaces (default on) switches the actors off as surfaces. The surface set is rebuilt
 * only when the taken actors or their mappers, inputs, properties or lookup tables change;
 * moving an actor re-runs the light passes (and the view pass), never the medium stage.
 *
 * Compositing rule: VTK draws opaque geometry and the background before volumes. The mapper
 * reads the depth buffer of that geometry and sorts the pixels (see
 * vtkRefractiveVolumeMapperCompositing.h):
 * - a pixel whose straight camera ray crosses the medium's active box (the voxels with n != 1,
 *   extinction or emission, grown by two voxels) and whose depth, if any, is one of the
 *   pipeline's surfaces is **replaced** by the view pass's radiance, which holds the medium, the
 *   surfaces and the background seen along the bent ray: pixel = Exposure * (L - B) + B, B the
 *   part of L that is the background seen through the medium (not exposed: VTK's background,
 *   whether a colour, a gradient or a texture, looks the same through clear medium as around it);
 * - a pixel whose depth is drawn by a prop that is not a surface (a translucent-free prop that
 *   vtkRefractaActorSurfaces does not take, or any actor with ActorSurfaces off) stops the view
 *   ray at that depth (converted to a path length, exact for straight rays only) and is
 *   **blended**: pixel = Exposure * (L - B) + B + T * pixel_before, T the path's RGB
 *   transmittance, so such geometry behind the medium is dimmed but not bent (a ray that leaves
 *   the medium before it sees no background), and geometry in front of it hides it;
 * - with ShadeActorsEverywhere (default off), a pixel whose depth is one of the pipeline's
 *   surfaces is **replaced** too wherever it is, so the actors are shaded by the light passes
 *   across the whole image: the medium's shadows and caustics show wherever they fall;
 * - every other pixel keeps what VTK drew (the background, and by default the actors where no
 *   medium covers them, with VTK's shading).
 * In a transparent renderer (a layer above 0) the layers below show through the medium, dimmed
 * and unbent, in place of the renderer's own background, which VTK does not draw there. The
 * camera's WindowCenter (tiled rendering: vtkRenderLargeImage) shifts the view rays as VTK's
 * frustum.
 * Translucent geometry is ignored. The mapper writes no depth, so it cannot composite with
 * another volume in the same renderer (it warns once when one is visible there): put several
 * media in one vtkImageData, or the other volume in another renderer layer. Values are clamped to
 * [0, 1] as VTK's own shading is (no tone curve).
 */
#ifndef vtkRefractiveVolumeMapper_h
#define vtkRefractiveVolumeMapper_h

#include "RefractaRenderingOpenGLModule.h" // for export macro
#include "vtkRefractaViewPass.h"           // for RayFrame
#include "vtkSmartPointer.h"               // for members
#include "vtkVolumeMapper.h"

#include <memory> // for std::unique_ptr
#include <string> // for std::string
#include <vector> // for std::vector

class vtkEffectPlan;
class vtkImageData;
class vtkOpenCLContext;
class vtkOpenGLRenderWindow;
class vtkCamera;
class vtkPiecewiseFunction;
class vtkRefractaActorSurfaces;
class vtkRefractaRenderPipeline;
class vtkRefractaRendererBackground;
class vtkRefractaSurfaceSet;
class vtkSceneAnalysis;

class REFRACTARENDERINGOPENGL_EXPORT vtkRefractiveVolumeMapper : public vtkVolumeMapper
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
  void SetAnisotropy(double value);
  vtkGetMacro(Anisotropy, double);
  void SetEmissionScale(double value);
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
   * Light-pass quality: photons traced (default 2^18, clamped to [1, 2^28] as
   * vtkPhotonTracer::SetNumberOfPhotons does) and the seed (default 1); the photon
   * tracer's other knobs through GetPipeline()->GetPhotonTracer().
   */
  void SetNumberOfPhotons(int photons);
  int GetNumberOfPhotons();
  void SetSeed(int seed);
  int GetSeed();
  ///@}

  ///@{
  /**
   * Run vtkLatticeBoltzmannLighting after the photon pass to add multiple scattering
   * (`MultipleScattering`, S_ms). Default on.
   */
  void SetMultipleScattering(bool on);
  bool GetMultipleScattering();
  void MultipleScatteringOn() { this->SetMultipleScattering(true); }
  void MultipleScatteringOff() { this->SetMultipleScattering(false); }
  ///@}

  ///@{
  /**
   * Whether the renderer's background (the one bent rays see, see vtkRefractaRendererBackground)
   * also lights the medium and the actor surfaces, as an emitter at infinity
   * (vtkRefractaRenderPipeline::BackgroundIlluminates, vtkPhotonTracer's environment light).
   * Default off: only the renderer's lights light the scene. Changing the background then re-runs
   * the light passes.
   */
  void SetBackgroundIlluminates(bool on);
  bool GetBackgroundIlluminates();
  void BackgroundIlluminatesOn() { this->SetBackgroundIlluminates(true); }
  void BackgroundIlluminatesOff() { this->SetBackgroundIlluminates(false); }

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
   * Where single scattering comes from: vtkRefractaRenderPipeline::SetSingleScatteringMethod
   * (vtkEffectPlan::AUTOMATIC_METHOD (default), PHOTONS, LIGHT_RAYS, INTERPOLATED).
   */
  void SetSingleScatteringMethod(int method);
  int GetSingleScatteringMethod();
  ///@}

  ///@{
  /**
   * How multiple scattering is computed: vtkRefractaRenderPipeline::SetMultipleScatteringMethod
   * (vtkEffectPlan::AUTOMATIC_MULTIPLE_METHOD (default), LATTICE_ONLY, FIRST_COLLISION_SPLIT,
   * PHOTONS_EVERY_ORDER) and SetScatteringOrders (the split's k; default 0: the plan's choice).
   * SetLattice chooses the Lattice-Boltzmann lattice: 0 (default, the plan's choice: D3Q18 where
   * the medium scatters strongly forward or backward, see vtkEffectPlan::SetLatticeDirections),
   * 6 or 18 directions.
   */
  void SetMultipleScatteringMethod(int method);
  int GetMultipleScatteringMethod();
  void SetScatteringOrders(int orders);
  int GetScatteringOrders();
  void SetLattice(int directions);
  int GetLattice();
  ///@}

  ///@{
  /**
   * View-pass settings (see vtkRefractaViewPass): StepSize in voxels (default 1, clamped to
   * [0.01, 16]; NaN is an error and keeps the step), RayMode
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
   * Multiplier on the medium's radiance before it is drawn, >= 0. Default 1. With
   * AutomaticExposure on it multiplies the automatic exposure. The background seen through the
   * medium (a colour, a gradient, a background texture or an environment) is not multiplied: it
   * stays VTK's background (see vtkRefractiveVolumeMapperCompositing.h).
   */
  void SetExposure(double value);
  vtkGetMacro(Exposure, double);
  ///@}

  ///@{
  /**
   * Automatic exposure (default on): the radiance is scaled so that the 99th percentile of the
   * luminance over the pixels where the medium shows (mean transmittance below 0.98; the
   * background's part left out) is drawn at 0.8, like a camera's metering. Why: VTK's volume
   * mappers draw the transfer function's colour as if it glowed (unshaded compositing is physically
   * a medium under unit ambient light), while this mapper computes the light the scene's lights
   * actually scatter, which for the same lights is several times dimmer (measured 0.25x on VTK's
   * wavelet with the default headlight, in VTK light units; 1.07x with metering); metering makes
   * the mapper a drop-in that shows a comparably exposed image. The exposure is metered again only
   * when the medium or the lighting was recomputed, never on a camera move, so brightness stays
   * comparable while the view changes. Turn it off for radiometrically calibrated output (then
   * pixel = Exposure x radiance).
   */
  vtkSetMacro(AutomaticExposure, bool);
  vtkGetMacro(AutomaticExposure, bool);
  vtkBooleanMacro(AutomaticExposure, bool);
  vtkGetMacro(LastExposure, double); ///< the multiplier used by the last draw
  ///@}

  ///@{
  /**
   * Take the renderer's visible opaque polydata actors as surfaces of the light and view passes
   * (see the class description and vtkRefractaActorSurfaces). Default on. Off: every actor is
   * composited by depth, unbent, as before surfaces existed.
   */
  vtkSetMacro(ActorSurfaces, bool);
  vtkGetMacro(ActorSurfaces, bool);
  vtkBooleanMacro(ActorSurfaces, bool);
  ///@}

  ///@{
  /**
   * Where the taken actors show the pipeline's shading (their photon-lit irradiance, with the
   * medium's shadows and caustics) instead of VTK's. Off (default, the drop-in behaviour): only
   * where the medium covers the pixel; elsewhere VTK draws them as without the mapper (its
   * shading, textures, specular highlights), so a shadow or caustic the medium casts outside its
   * own screen footprint is not shown, and the two shadings can meet in a seam at its outline.
   * On: every pixel where a taken actor is drawn: the medium's light on the actors shows
   * wherever it falls and there is no seam, at the cost of the photon estimate's noise, the
   * atlas's texel size and the loss of textures and highlights over the whole of every actor
   * (Reference.md, "Compositing rule").
   */
  vtkSetMacro(ShadeActorsEverywhere, bool);
  vtkGetMacro(ShadeActorsEverywhere, bool);
  vtkBooleanMacro(ShadeActorsEverywhere, bool);
  ///@}

  /**
   * The actors taken as surfaces by the last render and their surface set (GetSurfaces(),
   * GetNumberOfRebuilds()).
   */
  vtkRefractaActorSurfaces* GetActorSurfaceCollector();

  /**
   * The conversion of the renderer's background (GetLastSource()).
   */
  vtkRefractaRendererBackground* GetBackgroundConverter();

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
  int GetNumberOfMediumBuilds();
  int GetNumberOfLightPassRuns();
  int GetNumberOfViewPassRuns();
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
   * The render pipeline this mapper runs (effect plan, passes, stage statistics, progress events).
   */
  vtkRefractaRenderPipeline* GetPipeline();

  /**
   * Whether this build has a light-pass implementation (the photon tracer).
   */
  static bool HasLightPasses();

protected:
  vtkRefractiveVolumeMapper();
  ~vtkRefractiveVolumeMapper() override;

  bool UpdateMedium(vtkVolume* volume);
  void CutAwayClippedRegions(vtkImageData* medium, vtkVolume* volume);
  void WarnAboutUnsupportedModes(vtkRenderer* renderer, vtkVolume* volume);
  void ReportOnce(const std::string& message);
  bool UpdateActiveBox();
  void ClassifyPixels(vtkRenderer* renderer, vtkCamera* camera,
    const vtkRefractaViewPass::RayFrame& frame, vtkRefractaSurfaceSet* surfaces, int width,
    int height);
  void Composite(vtkOpenGLRenderWindow* window, int x0, int y0, int width, int height);
  static std::vector<float> DepthToPathLengths(vtkRenderer* renderer, vtkCamera* camera,
    const vtkRefractaViewPass::RayFrame& frame, int width, int height,
    const std::vector<float>& depth);

  double Anisotropy = 0.0;
  double EmissionScale = 0.0;
  double Exposure = 1.0;
  bool AutomaticExposure = true;
  double LastExposure = 1.0;
  bool ActorSurfaces = true;
  bool ShadeActorsEverywhere = false;

private:
  vtkRefractiveVolumeMapper(const vtkRefractiveVolumeMapper&) = delete;
  void operator=(const vtkRefractiveVolumeMapper&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
