/**
 * @class   vtkRefractaPluginLighting
 * @brief   The light passes of vtkRefractaRenderPipeline as a filter: medium in, lighting volume
 *          out, lights given as numbers (ParaView properties).
 *
 * Input: a Refracta medium (vtkImageData, validated by the pipeline with vtkMediumValidator).
 * The lights are rows of vtkRefractaPluginLightList (type, position, focal point, colour,
 * intensity, cone angle; world units, RADIOMETRIC_LIGHT_UNITS). The filter runs the plan and
 * light stages of its vtkRefractaRenderPipeline (UpdateLighting(): scene analysis, effect plan,
 * photon pass, and Lattice-Boltzmann multiple scattering where the plan calls for it) and
 * outputs the lighting volume on the medium's grid: `Radiance`, `RadianceDirection` and, with
 * multiple scattering, `MultipleScattering` (vtkRefractaLightingVolume), which
 * vtkRefractaImageRenderer (and RefractaRenderImage) takes on its second input.
 *
 * Field data of the output: the passes' own records, the effect plan (vtkEffectPlan::
 * RecordInFieldData: `PlanSummary`, `PlanEnabled`, ...) and the stage times `PlanSeconds` and
 * `LightingSeconds` (wall-clock seconds of this update, 0 for a stage that was reused), so
 * ParaView's Information panel shows what ran and what it cost. When the plan needs no light
 * pass (nothing scatters, or no light is on) the output is the medium's grid without arrays,
 * with the plan in its field data, and a warning says so.
 *
 * Knobs (defaults): Quality (vtkEffectPlan::DRAFT, INTERACTIVE (default), PRODUCTION: the
 * pipeline's presets), NumberOfPhotons (0 (default): the preset's), Seed (default 1),
 * MultipleScattering (default on). Errors of the pipeline (once per distinct message) leave
 * the output empty; the execution still counts as done, so ParaView does not re-run the filter
 * (and repeat the message) on every render until something changes.
 */
#ifndef vtkRefractaPluginLighting_h
#define vtkRefractaPluginLighting_h

#include "RefractaParaViewAdaptersModule.h" // for export macro
#include "vtkImageAlgorithm.h"
#include "vtkRefractaPluginQuality.h" // for PipelineQuality
#include "vtkSmartPointer.h"          // for members

class vtkRefractaPluginLightList;
class vtkRefractaRenderPipeline;

class REFRACTAPARAVIEWADAPTERS_EXPORT vtkRefractaPluginLighting : public vtkImageAlgorithm
{
public:
  static vtkRefractaPluginLighting* New();
  vtkTypeMacro(vtkRefractaPluginLighting, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Lights as rows of numbers; see vtkRefractaPluginLightList.
   */
  void SetLight(int index, double type, double px, double py, double pz, double fx, double fy,
    double fz, double r, double g, double b, double intensity, double coneAngle);
  void RemoveAllLights();
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
   * Seed of the photon pass's random streams; default 1.
   */
  void SetSeed(int seed);
  int GetSeed();
  ///@}

  ///@{
  /**
   * The photon pass's volume caustic subdivision (vtkPhotonTracer::VolumeCausticSubdivision,
   * 1..8, default 4; 1 off): light focused by glass into the fog is held in c^3 finer voxels
   * where it is dense.
   */
  void SetVolumeCausticSubdivision(int subdivision);
  int GetVolumeCausticSubdivision();
  ///@}

  ///@{
  /**
   * Run multiple scattering where the plan calls for it (default on).
   */
  void SetMultipleScattering(bool on);
  bool GetMultipleScattering();
  ///@}

  ///@{
  /**
   * Where single scattering comes from (vtkEffectPlan::SingleScatteringMethod: 0 auto (default),
   * 1 photons, 2 light rays, 3 interpolated), the pipeline's one setting.
   */
  void SetSingleScatteringMethod(int method);
  int GetSingleScatteringMethod();
  ///@}

  ///@{
  /**
   * How multiple scattering is computed (vtkEffectPlan::MultipleScatteringMethod: 0 auto
   * (default), 1 the lattice alone, 2 the first-collision split, 3 photons carrying every order)
   * the split's k (ScatteringOrders, 0: the plan's choice) and the lattice (Lattice: 0 the plan's
   * choice (default), 6 or 18 directions), the pipeline's settings.
   */
  void SetMultipleScatteringMethod(int method);
  int GetMultipleScatteringMethod();
  void SetScatteringOrders(int orders);
  int GetScatteringOrders();
  void SetLattice(int directions);
  int GetLattice();
  ///@}

  /**
   * The pipeline this filter runs (its plan, passes and statistics).
   */
  vtkRefractaRenderPipeline* GetPipeline();

  vtkMTimeType GetMTime() override;

protected:
  vtkRefractaPluginLighting();
  ~vtkRefractaPluginLighting() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  vtkSmartPointer<vtkRefractaRenderPipeline> Pipeline;
  vtkSmartPointer<vtkRefractaPluginLightList> Lights;
  refracta_plugin::PipelineQuality QualitySettings;

private:
  vtkRefractaPluginLighting(const vtkRefractaPluginLighting&) = delete;
  void operator=(const vtkRefractaPluginLighting&) = delete;
};

#endif
