/**
 * @class   vtkRefractaPluginRenderImage
 * @brief   vtkRefractaImageRenderer with its camera, lights and quality given as numbers
 *          (ParaView properties), for pvbatch scripts and comparison images.
 *
 * This is vtkRefractaImageRenderer itself (a subclass: the same render pipeline, inputs, output
 * arrays `HDR` and `RGB`, and field data: the effect plan with `PlanSummary`, and the stage
 * times `PlanSeconds`, `LightingSeconds`, `ViewSeconds`, `ViewPassSeconds`); it adds:
 * - a camera of its own set by CameraPosition, CameraFocalPoint, CameraViewUp (world units;
 *   defaults (0, 0, 1), (0, 0, 0), (0, 1, 0)) and CameraViewAngle (degrees, default 30);
 * - lights as rows (SetLight / RemoveAllLights; see vtkRefractaPluginLightList), used when no
 *   lighting volume is connected to input 1;
 * - Quality (vtkEffectPlan presets, default INTERACTIVE), NumberOfPhotons (0, the default, keeps
 *   the preset's), Seed (default 1) and MultipleScattering (default on) of its pipeline;
 * - VolumeCausticSubdivision (default 4) and GlassSupersampling (default 3) for glass.
 */
#ifndef vtkRefractaPluginRenderImage_h
#define vtkRefractaPluginRenderImage_h

#include "RefractaParaViewAdaptersModule.h" // for export macro
#include "vtkRefractaImageRenderer.h"
#include "vtkRefractaPluginQuality.h" // for PipelineQuality
#include "vtkSmartPointer.h"          // for members

class vtkRefractaPluginLightList;

class REFRACTAPARAVIEWADAPTERS_EXPORT vtkRefractaPluginRenderImage : public vtkRefractaImageRenderer
{
public:
  static vtkRefractaPluginRenderImage* New();
  vtkTypeMacro(vtkRefractaPluginRenderImage, vtkRefractaImageRenderer);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The camera (world units; the view angle in degrees, clamped to [0.01, 179]).
   */
  void SetCameraPosition(double x, double y, double z);
  void SetCameraFocalPoint(double x, double y, double z);
  void SetCameraViewUp(double x, double y, double z);
  void SetCameraViewAngle(double degrees);
  ///@}

  ///@{
  /**
   * Lights as rows of numbers; see vtkRefractaPluginLightList.
   */
  void SetLight(int index, double type, double px, double py, double pz, double fx, double fy,
    double fz, double r, double g, double b, double intensity, double coneAngle);
  void RemoveAllPluginLights();
  ///@}

  ///@{
  /**
   * Quality preset (vtkEffectPlan::Quality); default INTERACTIVE.
   */
  void SetQuality(int quality);
  int GetQuality() const { return this->QualitySettings.Quality; }
  ///@}

  ///@{
  /**
   * Photons of the photon pass, >= 0; 0 (default) keeps the preset's count.
   */
  void SetNumberOfPhotons(int photons);
  int GetNumberOfPhotons() const { return this->QualitySettings.NumberOfPhotons; }
  ///@}

  ///@{
  /**
   * Seed of the photon pass (default 1) and multiple scattering on/off (default on).
   */
  void SetSeed(int seed);
  void SetMultipleScattering(bool on);
  ///@}

  ///@{
  /**
   * Glass: the photon pass's volume caustic subdivision (vtkPhotonTracer::
   * VolumeCausticSubdivision, 1..8, default 4; 1 off) and the view pass's supersampling of pixels
   * over edges of glass (vtkRefractaViewPass::DielectricSupersampling, 1..8, default 3; 1 off).
   */
  void SetVolumeCausticSubdivision(int subdivision);
  void SetGlassSupersampling(int samples);
  ///@}

protected:
  vtkRefractaPluginRenderImage();
  ~vtkRefractaPluginRenderImage() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  vtkSmartPointer<vtkRefractaPluginLightList> Lights;
  refracta_plugin::PipelineQuality QualitySettings;

private:
  vtkRefractaPluginRenderImage(const vtkRefractaPluginRenderImage&) = delete;
  void operator=(const vtkRefractaPluginRenderImage&) = delete;
};

#endif
