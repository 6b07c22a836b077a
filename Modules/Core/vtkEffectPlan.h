/**
 * @class   vtkEffectPlan
 * @brief   Which light-transport effects a scene needs, decided from a vtkSceneAnalysis.
 *
 * For each effect the plan estimates how much the image would change, relative to its own
 * magnitude, if the effect were skipped, and turns the effect off when that estimate is at or
 * below the Tolerance. Every estimate is an upper bound built from the analysis:
 *
 * - Refraction (off: straight rays, no gradient lookups): min(1, d), d the largest displacement
 *   of a bent ray in voxels; a shift of d voxels changes a pixel by at most d times the largest
 *   relative contrast between neighbouring voxels, taken as 1.
 * - Absorption (off: extinction ignored, so nothing scatters either): 1 - exp(-tau_max).
 * - SingleScattering (off: no photon pass): 1 if a powered light exists and anything scatters,
 *   else 0 (scattered light may be all the camera sees, e.g. a lit fog on black).
 * - MultipleScattering (off: no Lattice-Boltzmann pass): q = albedo_max (1 - exp(-tau_max)) when
 *   single scattering is on, else 0. Every further order of scattering carries at most q of the
 *   previous one, so multiply scattered light is at most q of all scattered light.
 * - Emission (off: emission ignored): 1 if anything emits, else 0.
 * - SurfaceLighting (off: the photon pass ignores the opaque surfaces, and is not run for them):
 *   1 if a powered light exists and the scene has surfaces (vtkSceneAnalysis::SetSurfaces), else
 *   0. Light on a surface (its shadows, the caustics a clear glass ball focuses on a floor) comes
 *   only from the photon pass, so surfaces turn the photon pass on even in a medium that does not
 *   scatter at all.
 *
 * Each effect can be forced on or off (SetEffectMode), overriding the decision; the plan
 * records why it chose what it chose. The plan prints itself (PrintSelf), summarises
 * itself on one line (GetSummary), and writes itself into field data (RecordInFieldData), so that
 * every output of a run says what was simulated.
 *
 * Quality presets set the tolerance: Draft 0.05, Interactive 0.02, Production 0.005.
 */
#ifndef vtkEffectPlan_h
#define vtkEffectPlan_h

#include "RefractaCoreModule.h" // for export macro
#include "vtkObject.h"

#include <string> // for std::string

class vtkFieldData;
class vtkImageData;
class vtkSceneAnalysis;

class REFRACTACORE_EXPORT vtkEffectPlan : public vtkObject
{
public:
  static vtkEffectPlan* New();
  vtkTypeMacro(vtkEffectPlan, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Effect
  {
    REFRACTION = 0,
    ABSORPTION,
    SINGLE_SCATTERING,
    MULTIPLE_SCATTERING,
    EMISSION,
    SURFACE_LIGHTING,
    NUMBER_OF_EFFECTS
  };

  enum Mode
  {
    AUTOMATIC = 0,
    FORCE_ON,
    FORCE_OFF
  };

  enum Quality
  {
    DRAFT = 0,
    INTERACTIVE,
    PRODUCTION
  };

  ///@{
  /**
   * Largest relative image change an effect may cause and still be skipped. Default 0.01.
   */
  void SetTolerance(double value);
  vtkGetMacro(Tolerance, double);
  ///@}

  /**
   * Choose a quality preset: it sets the tolerance (DRAFT 0.05, INTERACTIVE 0.02, PRODUCTION
   * 0.005) and the pass settings below, which BenchmarkAccuracyTime chose from its measured
   * Pareto front of error against time (README, "Accuracy and time"). Default INTERACTIVE for
   * the recommendations (GetRecommended*), but not applied: until SetQuality() is called the
   * tolerance keeps its own default, 0.01 (GetQualityApplied() says which; PrintSelf too).
   */
  void SetQuality(int quality);
  vtkGetMacro(Quality, int);
  vtkGetMacro(QualityApplied, bool);

  ///@{
  /**
   * The pass settings of the current quality preset, for the application to apply:
   * photon count (vtkPhotonTracer::NumberOfPhotons), the photon tracer's MinimumStep (voxels)
   * and octree PrimaryTolerance (SecondaryTolerance = 4x that), the Lattice-Boltzmann
   * Tolerance and BlockSize, the view pass StepSize (voxels) and the grid resolution (voxels
   * along the longest axis) at which the benchmark scenes reached the preset's error.
   */
  int GetRecommendedNumberOfPhotons() const;
  double GetRecommendedPhotonMinimumStep() const;
  double GetRecommendedOctreeTolerance() const;
  double GetRecommendedLatticeTolerance() const;
  int GetRecommendedLatticeBlockSize() const;
  double GetRecommendedViewStep() const;
  int GetRecommendedResolution() const;
  ///@}

  /**
   * Where single scattering comes from (Documentation/Physics.md, "Single scattering without
   * noise"): PHOTONS (vtkPhotonTracer: curved paths, caustics, surface irradiance, sky light),
   * LIGHT_RAYS (vtkLightRaySingleScattering per voxel: straight paths, no noise) or INTERPOLATED
   * (the same pass's gradient-based interpolation, Ren et al. 2008). AUTOMATIC_METHOD (default):
   * photons when refraction is on, surfaces are lit or the sky lights the scene; otherwise the
   * interpolation when its measured error (InterpolationMeasuredError) is within the tolerance
   * and voxels x powered lights reach InterpolationBreakEvenWork (where it was measured faster,
   * BenchmarkSingleScattering), else light rays.
   */
  enum SingleScatteringMethod
  {
    AUTOMATIC_METHOD = 0,
    PHOTONS,
    LIGHT_RAYS,
    INTERPOLATED,
    NUMBER_OF_METHODS
  };

  ///@{
  /**
   * The method setting (default AUTOMATIC_METHOD) and, after Decide(), the method chosen and
   * why. Names ("auto", "photons", "light_rays", "interpolated") are the scene file's.
   */
  vtkSetClampMacro(SingleScatteringMethod, int, AUTOMATIC_METHOD, INTERPOLATED);
  vtkGetMacro(SingleScatteringMethod, int);
  int GetChosenSingleScatteringMethod() const { return this->ChosenMethod; }
  const char* GetSingleScatteringMethodReason() const { return this->MethodReason.c_str(); }
  static const char* GetSingleScatteringMethodName(int method);
  static int GetSingleScatteringMethodFromName(const char* name); // -1: unknown
  /** RMS error of the interpolation at its default ErrorTolerance, measured (1.2% to 1.8%). */
  static constexpr double InterpolationMeasuredError = 0.02;
  /** Voxels x lights from which the interpolation was measured faster (64^3 x 8: 1.7x). */
  static constexpr double InterpolationBreakEvenWork = 1 << 21;
  ///@}

  /**
   * How multiple scattering is computed (Documentation/Physics.md, "Ray effects of the grid
   * multiple scattering"): LATTICE_ONLY (the Lattice-Boltzmann solver from S1, the paper's
   * method: its 6 or 18 directions draw ray effects around concentrated light, the "+" of a
   * point light in fog), FIRST_COLLISION_SPLIT (photons carry the first k orders,
   * vtkPhotonTracer::ScatteringOrders, the lattice the rest) or PHOTONS_EVERY_ORDER (photons carry
   * every order, no lattice). AUTOMATIC_MULTIPLE_METHOD (default): photons where lit surfaces
   * need them (the lattice knows no surfaces); where a powered positional light is inside the
   * medium (vtkSceneAnalysis::GetNumberOfLightsInsideMedium(): a concentrated source), or where
   * refraction moves light by a voxel or more (GetMaximumDisplacementInVoxels() >= 1: it can
   * focus the light into a concentrated source, e.g. a GRIN lens), the split with the smallest k
   * whose measured ray-effect anisotropy (GetRayEffectAnisotropy() for the lattice in use,
   * LatticeDirections) is within the tolerance; else the lattice alone (measured as close to the
   * reference as any split there, and cheaper).
   */
  enum MultipleScatteringMethod
  {
    AUTOMATIC_MULTIPLE_METHOD = 0,
    LATTICE_ONLY,
    FIRST_COLLISION_SPLIT,
    PHOTONS_EVERY_ORDER,
    NUMBER_OF_MULTIPLE_METHODS
  };

  ///@{
  /**
   * The multiple-scattering method setting (default AUTOMATIC_MULTIPLE_METHOD; names "auto",
   * "lattice", "split", "photons"), the split's order setting ScatteringOrders (default 0: chosen
   * by the tolerance; k > 0 forces k), the lattice the Lattice-Boltzmann solver runs on
   * (LatticeDirections: AUTOMATIC_LATTICE (0, default), 6 or 18; other values are refused with an
   * error) and, after Decide(), what was chosen: GetChosenMultipleScatteringMethod(),
   * GetChosenScatteringOrders() (the value for vtkPhotonTracer::ScatteringOrders: 0 lattice only,
   * k, or -1 every order), GetChosenLatticeDirections() (6 or 18; the anisotropy table of the
   * split's k is that lattice's), and why.
   *
   * AUTOMATIC_LATTICE: D3Q18 where the medium scatters strongly forward or backward
   * (vtkSceneAnalysis::GetMeanAnisotropy() >= D3Q18Anisotropy), else D3Q6. D3Q6's six directions
   * pull the multiply scattered light's direction onto the grid's axes, which the view pass's
   * lobe about that direction shows: measured against the path-traced reference on a ball of
   * optical diameter 6 (Documentation/Physics.md, "The direction of multiple scattering"), the
   * worst of six lightings is 7.7% / 6.5% (relative RMSE, D3Q6 / D3Q18) at g = 0.3, 11.5% / 8.8%
   * at 0.5, 17.3% / 11.7% at 0.6, 25.3% / 13.3% at 0.65 and 99.6% / 20.6% at 0.8; D3Q18 costs
   * about 4x D3Q6's time and 3x its lattice memory.
   */
  vtkSetClampMacro(MultipleScatteringMethod, int, AUTOMATIC_MULTIPLE_METHOD, PHOTONS_EVERY_ORDER);
  vtkGetMacro(MultipleScatteringMethod, int);
  vtkSetClampMacro(ScatteringOrders, int, 0, 1000);
  vtkGetMacro(ScatteringOrders, int);
  void SetLatticeDirections(int directions);
  vtkGetMacro(LatticeDirections, int);
  int GetChosenMultipleScatteringMethod() const { return this->ChosenMultipleMethod; }
  int GetChosenScatteringOrders() const { return this->ChosenOrders; }
  int GetChosenLatticeDirections() const { return this->ChosenLattice; }
  const char* GetMultipleScatteringMethodReason() const { return this->MultipleReason.c_str(); }
  static const char* GetMultipleScatteringMethodName(int method);
  static int GetMultipleScatteringMethodFromName(const char* name); // -1: unknown
  enum LatticeChoice
  {
    AUTOMATIC_LATTICE = 0 ///< LatticeDirections: the plan chooses D3Q6 or D3Q18
  };
  static constexpr double D3Q18Anisotropy = 0.6;
  ///@}

  ///@{
  /**
   * Whether the device can hold the D3Q18 lattice for this medium (default true): an input of
   * the next Decide(), not a setting (it does not modify the plan), which the pipeline sets from
   * vtkLatticeBoltzmannSolver::FitsInMemory where CallsForD3Q18(analysis) says the automatic
   * lattice would be D3Q18 (LatticeDirections automatic, the analysed medium's mean |g| >=
   * D3Q18Anisotropy). Where it cannot, the automatic lattice stays D3Q6 and the reason says why.
   */
  bool CallsForD3Q18(vtkSceneAnalysis* analysis) const;
  void SetD3Q18FitsInMemory(bool fits) { this->D3Q18FitsInMemory = fits; }
  vtkGetMacro(D3Q18FitsInMemory, bool);
  ///@}

  /**
   * Measured ray-effect anisotropy of the lattice's S_ms when photons carry the first k orders
   * (k = 0: the lattice alone): |axis / diagonal - 1| of MultipleScattering at distance 1 from a
   * point light in a homogeneous isotropic fog (albedo 0.95, sigma_t 2, 41^3 voxels of 0.1;
   * RefractaTransport.MultipleScatteringIsotropy), for lattice 6 or 18. Beyond the measured k
   * it is the last value. D3Q6: 2.57, 0.74, 0.27, 0.11, 0.049, 0.024, 0.012, 0.0085, 0.0038 for
   * k = 0..8; D3Q18: 0.34, 0.094, 0.028, 0.0076, 0.0016 for k = 0..4.
   */
  static double GetRayEffectAnisotropy(int lattice, int orders);

  ///@{
  /**
   * Force an effect on or off, or leave it to the analysis (AUTOMATIC, the default).
   */
  void SetEffectMode(int effect, int mode);
  int GetEffectMode(int effect) const;
  ///@}

  /**
   * Decide every effect from the analysis (which must have been run). Returns false for a null
   * analysis. Deciding does not change this object's MTime (which tracks the settings only).
   */
  bool Decide(vtkSceneAnalysis* analysis);

  /**
   * Whether an effect is simulated (after Decide()).
   */
  bool IsEnabled(int effect) const;

  /**
   * The estimated relative image change if the effect were skipped.
   */
  double GetEstimatedContribution(int effect) const;

  /**
   * Why the effect is on or off, e.g. "off: estimated change 0.002 <= tolerance 0.01".
   */
  const char* GetReason(int effect) const;

  /**
   * Name of an effect ("Refraction", "Absorption", ...), or nullptr out of range.
   */
  static const char* GetEffectName(int effect);

  /**
   * One line: "refraction on (...), absorption on, ...".
   */
  std::string GetSummary() const;

  /**
   * Make `pruned` a shallow copy of `medium` without the arrays of the effects that are off, so
   * that every pass, which already prunes itself on what a medium carries, does only the planned
   * work: refraction off drops RefractiveIndexGradient and makes RefractiveIndex uniform at its
   * mean (straight rays, no gradient lookups; sources still count 1 / n^2), or drops it when that
   * mean is 1; absorption off drops Extinction (nothing attenuates, so nothing
   * scatters); emission off drops Emission. Single and multiple scattering are decided per pass
   * by the caller (IsEnabled): no photon pass, no Lattice-Boltzmann pass. Returns false for null
   * arguments or before Decide().
   */
  bool ApplyToMedium(vtkImageData* medium, vtkImageData* pruned) const;

  /**
   * Write the plan as field data: "PlanEnabled" (one 0/1 per effect, in enum order),
   * "PlanEstimatedContribution", "PlanTolerance" and "PlanSummary" (a string array).
   */
  void RecordInFieldData(vtkFieldData* fieldData) const;

protected:
  vtkEffectPlan() = default;
  ~vtkEffectPlan() override = default;

  void DecideEffect(int effect, double estimate, const char* detail);
  void DecideSingleScatteringMethod(vtkSceneAnalysis* analysis);
  void DecideMultipleScatteringMethod(vtkSceneAnalysis* analysis);
  std::string DecideLattice(vtkSceneAnalysis* analysis);

  double Tolerance = 0.01;
  int Quality = INTERACTIVE;
  bool QualityApplied = false; // whether SetQuality() has set the tolerance
  int Modes[NUMBER_OF_EFFECTS] = { AUTOMATIC, AUTOMATIC, AUTOMATIC, AUTOMATIC, AUTOMATIC,
    AUTOMATIC };
  bool Enabled[NUMBER_OF_EFFECTS] = { true, true, true, true, true, true };
  double Estimates[NUMBER_OF_EFFECTS] = { 0, 0, 0, 0, 0, 0 };
  std::string Reasons[NUMBER_OF_EFFECTS];
  bool Decided = false;
  int SingleScatteringMethod = AUTOMATIC_METHOD;
  int ChosenMethod = PHOTONS;
  std::string MethodReason;
  int MultipleScatteringMethod = AUTOMATIC_MULTIPLE_METHOD;
  int ScatteringOrders = 0;
  int LatticeDirections = AUTOMATIC_LATTICE;
  int ChosenMultipleMethod = LATTICE_ONLY;
  int ChosenLattice = 6;
  bool D3Q18FitsInMemory = true;
  int ChosenOrders = 0;
  std::string MultipleReason;

private:
  vtkEffectPlan(const vtkEffectPlan&) = delete;
  void operator=(const vtkEffectPlan&) = delete;
};

#endif
