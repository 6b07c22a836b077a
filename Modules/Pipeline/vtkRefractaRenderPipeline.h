/**
 * @class   vtkRefractaRenderPipeline
 * @brief   The one render pipeline every Refracta front end uses: scene analysis, effect plan,
 *          quality presets, photon pass, multiple scattering and view pass, with their device
 *          state kept between renders.
 *
 * `refracta-render`, vtkRefractiveVolumeMapper, vtkRefractaImageRenderer, the benchmarks and
 * the cross-module tests all render through this class, so the passes are wired in one place.
 *
 * Inputs: the medium (SetMedium: a Refracta medium, see vtkRefractaMedium; validated on
 * Render), the lights (AddLight: vtkLights in world coordinates, switched on; point, spot and
 * directional), the camera (SetCamera, world coordinates) and the medium's placement in the world
 * (SetPropMatrix: data -> world, a vtkProp3D's matrix; default identity). A precomputed lighting
 * volume (SetLightingData) replaces the light passes.
 *
 * Stages, each re-run only when something it reads changed since its last run (VTK modification
 * times, not keys):
 * 1. **PLAN**: vtkSceneAnalysis of the medium with the lights, vtkEffectPlan::Decide, and the
 *    medium pruned by the plan (refraction, absorption, emission). Runs when the medium, the
 *    plan's settings, the lights or the placement change; a light change alone keeps the pruned
 *    medium (and so the device upload) unless a light-independent decision changed.
 * 2. **LIGHTING**: when the plan enables single scattering and a powered light is on: the photon
 *    pass (GetPhotonTracer()), then, when multiple scattering is on, the Lattice-Boltzmann solver
 *    (GetLatticeSolver()) through vtkPhotonDiffusionSchedule, interleaved or sequential
 *    (MultipleScatteringSchedule); with surfaces (SetSurfaces()) the photons scatter for real
 *    instead and carry the multiple scattering themselves, so that it lights the surfaces
 *    (vtkPhotonTracer::AnalogScattering; no lattice runs). Runs when the pruned medium, a light,
 *    the placement or a light pass setting changed. Skipped entirely (and the lighting volume
 *    dropped) when the plan turns single scattering off.
 * 3. **VIEW**: vtkRefractaViewPass (GetViewPass()) for the camera. Runs when an earlier stage ran,
 *    or the camera, the image size, the depth limits, the placement or a view setting changed;
 *    otherwise the previous image is returned as it is.
 * So a camera move runs the view pass only; a light move or a surface move runs the light passes
 * and the view pass on the medium already on the device; a medium change runs everything.
 *
 * Progress and abort: Render() invokes vtkCommand::StartEvent and EndEvent around each stage that
 * runs (call data: the stage's name, a const char*), and vtkCommand::ProgressEvent (call data: a
 * double* in [0, 1], monotone over the whole render) with the stages weighted by their
 * measured cost (see StageWeights in the .cxx). AbortRender() (from any observer, or another
 * thread) stops the running pass at its next check and Render() returns false with
 * GetLastRenderAborted() true; the stages that did not finish re-run on the next Render().
 *
 * Statistics of the last Render(): GetStageRan(stage), GetStageSeconds(stage), and the counters
 * GetNumberOfPlanRuns(), GetNumberOfLightPassRuns(), GetNumberOfViewPassRuns().
 */
#ifndef vtkRefractaRenderPipeline_h
#define vtkRefractaRenderPipeline_h

#include "RefractaPipelineModule.h" // for export macro
#include "vtkObject.h"

#include <memory> // for std::unique_ptr
#include <string> // for FailPlanOnce
#include <vector> // for std::vector

class vtkAlgorithm;
class vtkCamera;
class vtkEffectPlan;
class vtkImageData;
class vtkLatticeBoltzmannSolver;
class vtkLight;
class vtkLightRaySingleScattering;
class vtkLightCollection;
class vtkMatrix4x4;
class vtkOpenCLContext;
class vtkPhotonDiffusionSchedule;
class vtkPhotonTracer;
class vtkRefractaSurfaceSet;
class vtkRefractaViewPass;
class vtkSceneAnalysis;

class REFRACTAPIPELINE_EXPORT vtkRefractaRenderPipeline : public vtkObject
{
public:
  static vtkRefractaRenderPipeline* New();
  vtkTypeMacro(vtkRefractaRenderPipeline, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Stage
  {
    PLAN = 0,
    LIGHTING = 1,
    VIEW = 2,
    NUMBER_OF_STAGES = 3
  };

  enum LightUnitsType
  {
    RADIOMETRIC_LIGHT_UNITS = 0, ///< intensity x colour is irradiance (directional, W m^-2) or
                                 ///< radiant intensity (point and spot, W sr^-1), as the passes use
    VTK_LIGHT_UNITS = 1          ///< as VTK's shading reads a light (see SetLightUnits)
  };

  enum ScheduleMode
  {
    AUTOMATIC_SCHEDULE = 0, ///< sequential, but interleaved on GPUs where the lattice's coarse
                            ///< start does not apply (see the .cxx)
    SEQUENTIAL_SCHEDULE = 1,
    INTERLEAVED_SCHEDULE = 2
  };

  /**
   * Name of a stage ("plan", "lighting", "view"), or "" for an invalid index.
   */
  static const char* GetStageName(int stage);

  ///@{
  /**
   * The medium (data coordinates). Required.
   */
  void SetMedium(vtkImageData* medium);
  vtkImageData* GetMedium();
  ///@}

  ///@{
  /**
   * Opaque surfaces of the scene (world coordinates; default none). The photon pass lights them
   * (the plan's SurfaceLighting effect turns it on whenever a powered light and a surface exist)
   * and the view pass shows them. Moving a surface (its matrix or mesh) re-runs the light passes
   * and the view, never the plan's medium stage; adding or removing surfaces re-plans.
   */
  void SetSurfaces(vtkRefractaSurfaceSet* surfaces);
  vtkRefractaSurfaceSet* GetSurfaces();
  ///@}

  /**
   * The surfaces the passes used in the last Render(): the set of SetSurfaces itself, or, when
   * the medium carries exact dielectric interfaces (vtkMeshVoxelizer::EXACT_INTERFACES writes them
   * into its field data, see vtkRefractaMedium), an internal set holding the same surfaces plus
   * those interfaces (vtkRefractaSurfaceSet::AddMediumInterfaces), placed by the prop matrix.
   * So every pass (photons, light rays, the scene analysis, the view) meets the medium's glass as
   * exact Snell and Fresnel interfaces, whatever the front end. The interfaces are left out when
   * the plan's REFRACTION effect is forced off (straight rays everywhere). nullptr: no surfaces.
   */
  vtkRefractaSurfaceSet* GetSceneSurfaces();

  ///@{
  /**
   * Whether the background (the view pass's EnvironmentMap, else its BackgroundColor, oriented by
   * its EnvironmentUp / EnvironmentRight) also lights the scene: the photon pass emits photons
   * from it (vtkPhotonTracer::BackgroundIlluminates) and the plan counts it as a source of light.
   * Default off: the background is only seen.
   */
  vtkSetMacro(BackgroundIlluminates, bool);
  vtkGetMacro(BackgroundIlluminates, bool);
  vtkBooleanMacro(BackgroundIlluminates, bool);
  ///@}

  ///@{
  /**
   * A precomputed lighting volume on the medium's grid (`Radiance`, `RadianceDirection`,
   * `MultipleScattering`, see vtkRefractaImageRenderer); replaces the light passes. Default none.
   */
  void SetLightingData(vtkImageData* lighting);
  vtkImageData* GetLightingData();
  ///@}

  ///@{
  /**
   * The lights, in world coordinates. Only lights that are switched on count.
   */
  void AddLight(vtkLight* light);
  void RemoveAllLights();
  void SetLights(vtkLightCollection* lights);
  vtkLightCollection* GetLights();
  ///@}

  ///@{
  /**
   * The camera (world coordinates). Required for Render().
   */
  void SetCamera(vtkCamera* camera);
  vtkCamera* GetCamera();
  ///@}

  ///@{
  /**
   * The medium's data -> world matrix (a vtkVolume's matrix). nullptr (default): identity.
   */
  void SetPropMatrix(vtkMatrix4x4* matrix);
  vtkMatrix4x4* GetPropMatrix();
  ///@}

  ///@{
  /**
   * The passes and decisions, to configure directly (their knobs, units and defaults are
   * documented in their classes). The photon tracer's lights are set by this pipeline.
   */
  vtkSceneAnalysis* GetSceneAnalysis();
  vtkEffectPlan* GetEffectPlan();
  vtkPhotonTracer* GetPhotonTracer();

  ///@{
  /**
   * Where single scattering comes from: vtkEffectPlan::SetSingleScatteringMethod
   * (AUTOMATIC_METHOD (default), PHOTONS, LIGHT_RAYS, INTERPOLATED); the plan records the method
   * it chose and why (vtkEffectPlan::GetChosenSingleScatteringMethod, field data
   * `PlanSingleScatteringMethod`). LIGHT_RAYS and INTERPOLATED run GetLightRays()
   * (vtkLightRaySingleScattering, with the photon tracer's LightRadius,
   * DirectionalLightAngularRadius and MaximumRadianceLobes: set those on GetPhotonTracer()) and,
   * with multiple scattering, vtkLatticeBoltzmannLighting on
   * its output (with the lattice solver's Tolerance and BlockSize).
   */
  void SetSingleScatteringMethod(int method);
  int GetSingleScatteringMethod();
  vtkLightRaySingleScattering* GetLightRays();
  ///@}

  ///@{
  /**
   * How multiple scattering is computed: vtkEffectPlan::SetMultipleScatteringMethod
   * (AUTOMATIC_MULTIPLE_METHOD (default), LATTICE_ONLY, FIRST_COLLISION_SPLIT,
   * PHOTONS_EVERY_ORDER) and vtkEffectPlan::SetScatteringOrders (the split's k; default 0: the
   * plan's choice by the tolerance). The plan records what it chose and why (field data
   * `PlanMultipleScatteringMethod`); the photon tracer then carries that many orders
   * (vtkPhotonTracer::ScatteringOrders) and the lattice (GetLatticeSolver()) the rest. With light
   * rays for single scattering the photons still run for the orders they carry
   * (vtkLatticeBoltzmannLighting's port 2). SetLattice: vtkEffectPlan::SetLatticeDirections,
   * the lattice the solver runs on: vtkEffectPlan::AUTOMATIC_LATTICE (0, default: D3Q18 where the
   * medium scatters strongly forward or backward, mean |g| >= 0.6, else D3Q6), 6 or 18; each
   * light pass sets GetLatticeSolver()'s Lattice to the plan's choice (field data
   * `PlanLatticeDirections`), so set it here, not there.
   */
  void SetMultipleScatteringMethod(int method);
  int GetMultipleScatteringMethod();
  void SetScatteringOrders(int orders);
  int GetScatteringOrders();
  void SetLattice(int directions);
  int GetLattice();
  ///@}
  vtkLatticeBoltzmannSolver* GetLatticeSolver();
  vtkRefractaViewPass* GetViewPass();
  ///@}

  /**
   * Apply a quality preset (vtkEffectPlan::DRAFT, INTERACTIVE or PRODUCTION) to the plan (its
   * tolerance) and to every pass: photon count, photon minimum step, octree tolerances, lattice
   * tolerance and block size, and the view step, as measured by BenchmarkAccuracyTime
   * (Documentation/Benchmarks.md). Setting a knob on a pass afterwards overrides the preset's
   * value. An unknown preset is reported by the plan and changes nothing.
   */
  void SetQuality(int quality);

  /**
   * Set the photon tracer's octree tolerances: primary `epsilon` and secondary 4 epsilon, the
   * ratio the paper's and our measurements use (the one place this rule lives).
   */
  void SetOctreeTolerance(double epsilon);

  ///@{
  /**
   * How a light's intensity is read. RADIOMETRIC_LIGHT_UNITS (default): as the passes define it
   * (Documentation/Physics.md). VTK_LIGHT_UNITS: as VTK's own shading reads it, so that a scene
   * lit for VTK's mappers is exposed alike: VTK shades a surface of diffuse colour rho facing a
   * light of intensity I with rho I, which is a Lambertian surface's radiance rho E / pi under
   * irradiance E = pi I. So a directional light becomes irradiance pi I, and a positional light
   * (which VTK does not attenuate with distance by default) becomes the radiant intensity
   * pi I d^2 that gives the same irradiance at the distance d from the light to the medium's
   * centre, d at least the distance from the centre to the box's nearest face (a light inside
   * the medium near its centre would otherwise go dark: pi I d^2 -> 0; lights outside the box
   * are always that far). vtkRefractiveVolumeMapper uses VTK_LIGHT_UNITS.
   */
  vtkSetClampMacro(LightUnits, int, RADIOMETRIC_LIGHT_UNITS, VTK_LIGHT_UNITS);
  vtkGetMacro(LightUnits, int);
  ///@}

  ///@{
  /**
   * Run multiple scattering at all (default on). Off forces the plan's MULTIPLE_SCATTERING
   * decision off without changing its mode.
   */
  vtkSetMacro(MultipleScattering, bool);
  vtkGetMacro(MultipleScattering, bool);
  vtkBooleanMacro(MultipleScattering, bool);
  ///@}

  ///@{
  /**
   * How the photon pass and the lattice share the device (vtkPhotonDiffusionSchedule): default
   * AUTOMATIC_SCHEDULE.
   */
  vtkSetClampMacro(MultipleScatteringSchedule, int, AUTOMATIC_SCHEDULE, INTERLEAVED_SCHEDULE);
  vtkGetMacro(MultipleScatteringSchedule, int);
  ///@}

  ///@{
  /**
   * Relight from the last field: when only the lights changed, the lattice starts from the last
   * render's multiple-scattering field instead of from zero (vtkPhotonDiffusionSchedule's
   * WarmStart, with the solver's coarse correction, vtkLatticeBoltzmannSolver::CoarseWarmStart),
   * to the same tolerance; the image then depends on the previous render within that tolerance.
   * It saves steps for small changes of the light (Table I, a 2 degree turn: 136 + 14 coarse
   * against 168 + 19 from zero), not for BenchmarkInteractive's light move (the spot moved by a
   * fifth of the volume: 168 against 176 fine steps at 2^20 photons, plus the coarse ones).
   * Default off (every render equals a fresh pipeline's).
   */
  vtkSetMacro(LatticeWarmStart, bool);
  vtkGetMacro(LatticeWarmStart, bool);
  vtkBooleanMacro(LatticeWarmStart, bool);
  ///@}

  ///@{
  /**
   * Hand the lighting volume from pass to pass on the device (default on): the photon pass keeps
   * its output arrays' device buffers (vtkPhotonTracer::KeepDeviceCopies), the lattice takes its
   * source from them and keeps its S_ms the same way (vtkLatticeBoltzmannSolver::
   * KeepDeviceCopies), and the view pass takes `Radiance`, `RadianceDirection` and
   * `MultipleScattering` from them (vtkOpenCLDeviceArrays) instead of uploading the host arrays
   * the passes have just read back. The image is the same to the bit either way; off, every
   * hand-off goes through the host (the A/B of BenchmarkInteractive --host-hand-off).
   */
  vtkSetMacro(DeviceHandOff, bool);
  vtkGetMacro(DeviceHandOff, bool);
  vtkBooleanMacro(DeviceHandOff, bool);
  ///@}

  ///@{
  /**
   * The direct light on lit surfaces by straight light rays (default on): where the photons fly
   * straight and only the lights (not the sky) light the scene, the photon pass leaves the
   * light that reaches a surface first out of its atlas (vtkPhotonTracer::SkipDirectSurfaceLight)
   * and vtkLightRaySingleScattering::ComputeSurfaceIrradiance adds it without noise (shadows of
   * the medium's absorption and of the surfaces, glass included, whose light the photons still
   * carry: caustics, light bounced between surfaces, light the medium scattered).
   * GetLastDirectSurfaceLightByRays() says whether the last light stage did. Off: photons
   * carry all of it (Documentation/Physics.md, "Direct light on surfaces").
   */
  vtkSetMacro(DirectSurfaceLightByRays, bool);
  vtkGetMacro(DirectSurfaceLightByRays, bool);
  vtkBooleanMacro(DirectSurfaceLightByRays, bool);
  vtkGetMacro(LastDirectSurfaceLightByRays, bool);
  ///@}

  ///@{
  /**
   * OpenCL context of every pass. Default vtkOpenCLContext::GetDefault().
   */
  void SetContext(vtkOpenCLContext* context);
  vtkOpenCLContext* GetContext();
  ///@}

  /**
   * Run the stages that changed and render `width` x `height` pixels. `depthLimit` (nullptr or
   * width x height floats) caps each pixel's path length in world units (opaque geometry drawn
   * before the medium). Returns false after an error (a vtkErrorMacro names it, once per
   * distinct message; GetImage() is then empty) or an abort (the last image is kept). Errors
   * include a camera that cannot make rays (a non-finite position, focal point or view up, a
   * view up along the view, a view angle outside (0, 180) or a parallel scale <= 0) and a prop
   * matrix that cannot place the medium (not finite, singular, or not affine).
   */
  bool Render(int width, int height, const float* depthLimit = nullptr);

  /**
   * Run the plan and light stages that changed, without a camera or a view: for front ends that
   * want the lighting volume only (GetLighting(), e.g. the ParaView plugin's lighting filter).
   * Same caching, events, errors and abort as Render(); the view stage is left as it was.
   */
  bool UpdateLighting();

  ///@{
  /**
   * The last image: width x height RGBA floats, linear radiance with A = 1 - mean transmittance
   * (GetImage), the path's RGB transmittance with A = 0 (GetTransmittance), and the part of the
   * image's RGB that is the background seen through the path, A = 0 (GetBackgroundPart; see
   * vtkRefractaViewPass::Render). Row 0 at the bottom.
   */
  const std::vector<float>& GetImage() const;
  const std::vector<float>& GetTransmittance() const;
  const std::vector<float>& GetBackgroundPart() const;
  ///@}

  /**
   * The medium the passes saw (pruned by the plan), or nullptr before the first plan.
   */
  vtkImageData* GetPlannedMedium();

  /**
   * The lighting volume the view pass saw (light passes' output or the lighting data), or nullptr.
   */
  vtkImageData* GetLighting();

  ///@{
  /**
   * Stop the running pass at its next check (photon chunk, lattice check interval, view tile).
   * Safe to call from an observer of this object's events. Cleared at the start of Render().
   */
  void AbortRender();
  vtkGetMacro(LastRenderAborted, bool);
  ///@}

  ///@{
  /**
   * Statistics of the last Render() and counters over all renders.
   */
  bool GetStageRan(int stage) const;
  double GetStageSeconds(int stage) const;
  vtkGetMacro(NumberOfPlanRuns, int);
  vtkGetMacro(NumberOfMediumUpdates, int); ///< plans that prepared (pruned, uploaded) a medium
  vtkGetMacro(NumberOfLightPassRuns, int);
  vtkGetMacro(NumberOfViewPassRuns, int);
  ///@}

  /**
   * Report this pipeline's errors and warnings, and those of its passes, as events of `owner`
   * (a front end such as a filter or a mapper): observers of the owner's ErrorEvent and
   * WarningEvent receive them, and with no such observer they go to vtkOutputWindow as usual.
   * Call once; nullptr restores the default. `owner` must outlive this pipeline or call
   * SetEventOwner(nullptr) first.
   */
  void SetEventOwner(vtkObject* owner);

  /**
   * Latest modification time of everything a render reads besides the medium and the lighting
   * data: this object's settings, the plan, the passes, the lights, the camera, the placement and
   * the environment map. For front ends that are vtkAlgorithms.
   */
  vtkMTimeType GetInputsMTime();

  /**
   * Whether the last light stage used the interleaved schedule.
   */
  vtkGetMacro(LastScheduleInterleaved, bool);

protected:
  vtkRefractaRenderPipeline();
  ~vtkRefractaRenderPipeline() override;

  bool RunStages(bool view, int width, int height, const float* depthLimit);
  bool RunPlan();
  // Reports `message` unless it was the last one reported, forgets the planned medium; false.
  bool FailPlanOnce(const std::string& message);
  bool RunLighting();
  vtkAlgorithm* PrepareLightRays(vtkPhotonTracer* tracer, int method);
  // The light rays see the lights, surfaces, placement, light extents and lobes the photons saw.
  void ConfigureLightRays(vtkPhotonTracer* tracer);
  // Adds the direct surface light the photons left out to in.Lighting's SurfaceIrradiance.
  bool AddDirectSurfaceLight(vtkPhotonTracer* tracer);
  bool RunView(int width, int height, const float* depthLimit);
  bool PlanIsStale();
  bool BackgroundIsNewerThan(vtkMTimeType time);
  bool LightingIsStale();
  vtkMTimeType GetLightsMTime();
  void ReportProgress(int stage, double fraction);

  bool MultipleScattering = true;
  int LightUnits = RADIOMETRIC_LIGHT_UNITS;
  int MultipleScatteringSchedule = AUTOMATIC_SCHEDULE;
  bool LatticeWarmStart = false;
  bool DeviceHandOff = true;
  bool DirectSurfaceLightByRays = true;
  bool LastDirectSurfaceLightByRays = false;
  bool BackgroundIlluminates = false;
  bool LastRenderAborted = false;
  bool LastScheduleInterleaved = false;
  int NumberOfPlanRuns = 0;
  int NumberOfMediumUpdates = 0;
  int NumberOfLightPassRuns = 0;
  int NumberOfViewPassRuns = 0;

private:
  vtkRefractaRenderPipeline(const vtkRefractaRenderPipeline&) = delete;
  void operator=(const vtkRefractaRenderPipeline&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
