/**
 * @class   vtkRefractaImageRenderer
 * @brief   Headless view pass: renders a medium and its lighting volume for a vtkCamera into a
 *          2D image (no OpenGL needed).
 *
 * Input port 0: the medium (vtkImageData, validated with vtkMediumValidator). Input port 1
 * (optional): the lighting volume on the same grid with point arrays `Radiance` (S1, RGB) and
 * `RadianceDirection` (unit mean travel direction, grid-local frame) and/or `MultipleScattering`
 * (S_ms, RGB), as written by vtkPhotonTracer and vtkLatticeBoltzmannLighting. Without it the
 * image holds emission, absorption and the background only.
 *
 * Output: a W x H x 1 vtkImageData (origin 0, spacing 1; row 0 at the bottom, VTK's convention)
 * with point arrays
 * - `HDR`: float RGBA, linear radiance; A = 1 - mean over RGB of the transmittance along the
 *   pixel's path (the medium's opacity);
 * - `RGB`: unsigned char, tone-mapped, the active scalars:
 *   v = Exposure * L per channel, then the ToneMapping operator
 *   CLAMP (default): min(v, 1); REINHARD: v / (1 + v); EXPONENTIAL: 1 - exp(-v);
 *   then the sRGB transfer curve (1.055 c^(1/2.4) - 0.055, 12.92 c below 0.0031308) and
 *   rounding to 0..255.
 * Field data records `ViewPassSeconds`, `TotalSteps`, `CurvedRays` (0/1), `EmptySpaceSkipping`
 * (0/1: whether the skipping kernel ran), `ActiveCellFraction` (macro cells rays had to march
 * through; 1 without skipping) and `LaneMarching` (0/1: whether the eight-lane
 * kernel ran, vtkRefractaViewPass::LaneMarching) of the run.
 *
 * Knobs (units, defaults): Camera (required), ImageSize (pixels, default 256 x 256),
 * BackgroundColor (linear RGB radiance, default black), EnvironmentMap / EnvironmentTexture
 * (equirectangular, looked up in the ray's bent exit direction; see vtkRefractaViewPass for the
 * orientation, EnvironmentUp and EnvironmentRight), StepSize (voxels, default 1), RayMode (AUTO,
 * STRAIGHT, CURVED; default AUTO: curved only where grad n is non-zero somewhere),
 * TransmittanceCutoff (default 1e-4), MaxSteps (0 = automatic), Exposure (default 1), ToneMapping
 * (default CLAMP), Context (default vtkOpenCLContext::GetDefault()).
 *
 * Lights (AddLight, world coordinates): when lights are given and no lighting volume is
 * connected, the light passes run too (photon pass, and multiple scattering where the effect plan
 * calls for it), so this filter renders a whole scene from a medium. It runs through
 * vtkRefractaRenderPipeline (GetPipeline()), which keeps its device state between updates: a
 * camera change re-runs only the view pass. Its effect plan forces refraction, absorption and
 * emission on, so the medium is rendered as given and the plan only decides which light passes
 * run; set those modes to AUTOMATIC through GetPipeline()->GetEffectPlan() to let it skip
 * effects below its tolerance. Field data also
 * records the effect plan (vtkEffectPlan::RecordInFieldData) and `PlanSeconds`, `LightingSeconds`,
 * `ViewSeconds` (0 for a stage that was reused). Progress is reported through UpdateProgress;
 * AbortExecuteOn() stops the running pass and leaves the output empty.
 *
 * Bad input (invalid medium, lighting volume on another grid, no camera, a degenerate camera, a
 * bad environment image): vtkErrorMacro naming it, RequestData returns 0, the output is empty.
 *
 * Progress and abort: the view pass renders in tiles of rows (vtkRefractaViewPass::TilePixels,
 * default 65536 pixels; the image is identical to an untiled render) and its per-tile progress is
 * forwarded: ProgressEvent rises monotonically from 0.02 (uploads done) to 0.98 (all tiles) and
 * 1. AbortExecute is handed to the pass, which stops after the current tile: the output is then
 * empty, no error is reported (RequestData returns 1), GetLastRunAborted() is set, and after
 * AbortExecuteOff() the next Update() renders from the start.
 */
#ifndef vtkRefractaImageRenderer_h
#define vtkRefractaImageRenderer_h

#include "RefractaRenderingModule.h" // for export macro
#include "vtkImageAlgorithm.h"
#include "vtkSmartPointer.h" // for members

#include <vector> // for std::vector

class vtkCamera;
class vtkImageData;
class vtkOpenCLContext;
class vtkLight;
class vtkRefractaRenderPipeline;
class vtkRefractaSurfaceSet;
class vtkRefractaViewPass;
class vtkTexture;
class vtkUnsignedCharArray;

class REFRACTARENDERING_EXPORT vtkRefractaImageRenderer : public vtkImageAlgorithm
{
public:
  static vtkRefractaImageRenderer* New();
  vtkTypeMacro(vtkRefractaImageRenderer, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum ToneMappingOperators
  {
    CLAMP = 0,
    REINHARD = 1,
    EXPONENTIAL = 2
  };

  ///@{
  /**
   * Opaque surfaces of the scene (world coordinates), passed to the pipeline
   * (vtkRefractaRenderPipeline::SetSurfaces). Default none.
   */
  void SetSurfaces(vtkRefractaSurfaceSet* surfaces);
  vtkRefractaSurfaceSet* GetSurfaces();
  ///@}

  ///@{
  /**
   * Convenience: the lighting volume on input port 1 (nullptr removes it).
   */
  void SetLightingData(vtkImageData* lighting);
  void SetLightingConnection(vtkAlgorithmOutput* output);
  ///@}

  ///@{
  /**
   * Lights (world coordinates) for the light passes, used when no lighting volume is connected.
   * Default none: emission, absorption and the background only.
   */
  void AddLight(vtkLight* light);
  void RemoveAllLights();
  ///@}

  ///@{
  /**
   * The camera, in world coordinates. Required. Its MTime is part of this filter's.
   */
  void SetCamera(vtkCamera* camera);
  vtkCamera* GetCamera();
  ///@}

  ///@{
  /**
   * Output size in pixels, each side 1 to MaximumImageSide (16384). Default 256 x 256. A size
   * outside that is an error that keeps the current size (clamping a mistyped 100000 to 16384
   * would start a render of 268 million rays).
   */
  static constexpr int MaximumImageSide = 16384;
  void SetImageSize(int width, int height);
  vtkGetVector2Macro(ImageSize, int);
  ///@}

  ///@{
  /**
   * Uniform background radiance (linear RGB, >= 0). Default (0, 0, 0).
   */
  void SetBackgroundColor(double r, double g, double b);
  void GetBackgroundColor(double rgb[3]);
  ///@}

  ///@{
  /**
   * Equirectangular environment image, or a texture whose input image is used. nullptr (default)
   * uses the background colour. The texture takes precedence when both are set.
   */
  void SetEnvironmentMap(vtkImageData* image);
  vtkImageData* GetEnvironmentMap();
  void SetEnvironmentTexture(vtkTexture* texture);
  vtkTexture* GetEnvironmentTexture();
  void SetEnvironmentUp(double x, double y, double z);
  void SetEnvironmentRight(double x, double y, double z);
  ///@}

  ///@{
  /**
   * View-pass settings; see vtkRefractaViewPass. StepSize in voxels (default 1, clamped to
   * [0.01, 16]; NaN is an error and keeps the step), RayMode
   * (default AUTO), TransmittanceCutoff (default 1e-4), MaxSteps (default 0 = automatic),
   * EmptySpaceSkipping (default on; same image up to float rounding, see vtkRefractaViewPass).
   */
  void SetStepSize(double voxels);
  double GetStepSize();
  void SetRayMode(int mode);
  int GetRayMode();
  void SetRayModeToStraight() { this->SetRayMode(1); }
  void SetRayModeToCurved() { this->SetRayMode(2); }
  void SetRayModeToAuto() { this->SetRayMode(0); }
  void SetTransmittanceCutoff(double cutoff);
  double GetTransmittanceCutoff();
  void SetMaxSteps(int steps);
  int GetMaxSteps();
  void SetEmptySpaceSkipping(bool on);
  bool GetEmptySpaceSkipping();
  void EmptySpaceSkippingOn() { this->SetEmptySpaceSkipping(true); }
  void EmptySpaceSkippingOff() { this->SetEmptySpaceSkipping(false); }
  ///@}

  ///@{
  /**
   * Exposure multiplier applied before tone mapping, >= 0. Default 1.
   */
  void SetExposure(double value);
  vtkGetMacro(Exposure, double);
  ///@}

  ///@{
  /**
   * Tone-mapping operator: CLAMP (default), REINHARD or EXPONENTIAL.
   */
  vtkSetClampMacro(ToneMapping, int, CLAMP, EXPONENTIAL);
  vtkGetMacro(ToneMapping, int);
  ///@}

  ///@{
  /**
   * OpenCL context. Default vtkOpenCLContext::GetDefault().
   */
  void SetContext(vtkOpenCLContext* context);
  vtkOpenCLContext* GetContext();
  ///@}

  /**
   * The view pass this filter runs (its statistics: GetLastSeconds(), GetLastTotalSteps(), ...).
   */
  vtkRefractaViewPass* GetViewPass();

  /**
   * The render pipeline this filter runs (the effect plan, the light passes, their statistics).
   */
  vtkRefractaRenderPipeline* GetPipeline();

  /**
   * Whether the last RequestData stopped because AbortExecute was set (its output is empty).
   */
  vtkGetMacro(LastRunAborted, bool);

  /**
   * Tone-map `pixels` RGBA floats into 8-bit RGB with the operator and exposure given.
   */
  static void ToneMap(
    const float* hdr, size_t pixels, int toneMapping, double exposure, vtkUnsignedCharArray* rgb);

  vtkMTimeType GetMTime() override;

protected:
  vtkRefractaImageRenderer();
  ~vtkRefractaImageRenderer() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int ImageSize[2] = { 256, 256 };
  double Exposure = 1.0;
  int ToneMapping = CLAMP;
  vtkSmartPointer<vtkCamera> Camera;
  vtkSmartPointer<vtkTexture> EnvironmentTexture;
  vtkSmartPointer<vtkRefractaRenderPipeline> Pipeline;
  vtkRefractaViewPass* ViewPass; // the pipeline's
  bool LastRunAborted = false;

private:
  vtkRefractaImageRenderer(const vtkRefractaImageRenderer&) = delete;
  void operator=(const vtkRefractaImageRenderer&) = delete;
};

#endif
