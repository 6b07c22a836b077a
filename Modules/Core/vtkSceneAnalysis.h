/**
 * @class   vtkSceneAnalysis
 * @brief   Cheap facts about a medium and its lights that decide which effects a render needs.
 *
 * One vtkSMPTools pass over the medium (plus a few hundred straight probe rays per light) gives:
 * - the refractive-index range and the largest bending a ray can suffer crossing the volume,
 *   bounded by the integral of abs(grad n) / n along grid lines (radians), and the displacement
 *   that bending causes over the volume's diagonal, in voxels;
 * - the optical thickness tau along the three main axes (largest over all grid lines, per RGB
 *   channel) and toward each light (largest over probe rays through the light's footprint);
 * - the same for scattering only (tau_s, with sigma_s = albedo * sigma_t);
 * - the single-scattering albedo range, whether anything scatters or emits, how much of the
 *   volume is occupied (voxels that differ from vacuum), and how many lights carry power.
 * vtkEffectPlan turns these facts and a tolerance into decisions.
 *
 * Optical thickness uses the voxel values as piecewise-constant along grid lines (sum of
 * sigma_t * spacing), which is what the passes' trilinear interpolation integrates to within
 * the interpolation error.
 */
#ifndef vtkSceneAnalysis_h
#define vtkSceneAnalysis_h

#include "RefractaCoreModule.h" // for export macro
#include "vtkObject.h"
#include "vtkSmartPointer.h" // for members

#include <memory> // for std::unique_ptr
#include <string> // for std::string
#include <vector> // for std::vector

class vtkFieldData;
class vtkImageData;
class vtkLight;
class vtkLightCollection;
class vtkRefractaSurfaceSet;

class REFRACTACORE_EXPORT vtkSceneAnalysis : public vtkObject
{
public:
  static vtkSceneAnalysis* New();
  vtkTypeMacro(vtkSceneAnalysis, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The medium to analyse (a vtkImageData with Refracta arrays).
   */
  void SetMedium(vtkImageData* medium);
  vtkImageData* GetMedium();
  ///@}

  ///@{
  /**
   * The lights (world coordinates). Switched-off lights and lights without power are counted
   * as absent.
   */
  void AddLight(vtkLight* light);
  void RemoveAllLights();
  void SetLights(vtkLightCollection* lights);
  int GetNumberOfLights() const { return static_cast<int>(this->Lights.size()); }
  ///@}

  ///@{
  /**
   * The surfaces of the scene (vtkRefractaSurfaceSet, world coordinates; default none): opaque
   * ones and exact dielectric interfaces. Only their presence is analysed: GetNumberOfSurfaces()
   * counts those with polygons or strips, GetNumberOfInterfaceSurfaces() the dielectric ones
   * among them (they refract, whatever the index field's gradient says).
   */
  void SetSurfaces(vtkRefractaSurfaceSet* surfaces);
  vtkRefractaSurfaceSet* GetSurfaces();
  ///@}

  /**
   * Compute the facts. Returns false (with a vtkErrorMacro naming the problem) when the medium
   * is missing or invalid; the facts are then those of an empty scene.
   *
   * The medium's facts (validation, ranges, line integrals) are kept with the medium's MTime and
   * reused while the same medium is unmodified, so that a light or surface change re-runs only
   * the light probes (a light move in an interactive view); the medium's extinction is kept for
   * those probes (12 bytes per voxel). GetNumberOfMediumScans() counts the full passes.
   */
  bool Analyze();

  /**
   * How many times Analyze() scanned the whole medium (the others reused its facts).
   */
  vtkGetMacro(NumberOfMediumScans, int);

  ///@{
  /**
   * Refractive index range over the voxels.
   */
  vtkGetVector2Macro(RefractiveIndexRange, double);
  ///@}

  /**
   * Upper bound of the total bending angle of a ray crossing the volume along a grid line
   * (radians): the largest sum of abs(grad n) / n * spacing along any grid line.
   */
  vtkGetMacro(MaximumBendingAngle, double);

  /**
   * MaximumBendingAngle times the volume's diagonal, divided by the smallest spacing: how many
   * voxels a bent ray can end up away from a straight one.
   */
  vtkGetMacro(MaximumDisplacementInVoxels, double);

  /**
   * Largest optical thickness (any RGB channel) along grid lines of axis 0, 1 or 2.
   */
  double GetMaximumOpticalThickness(int axis) const;

  /**
   * Largest optical thickness over the three axes and all channels.
   */
  vtkGetMacro(MaximumOpticalThickness, double);

  /**
   * Largest scattering optical thickness (sigma_s = albedo * sigma_t) over axes and channels.
   */
  vtkGetMacro(MaximumScatteringThickness, double);

  /**
   * Largest optical depth of one scattering voxel: the largest sigma_t (any channel with an
   * albedo above 0) times the largest spacing. Above a few, light is scattered within a fraction of
   * a voxel of a dense region's surface, which the passes' voxel samples do not resolve: the light
   * scattered there is underestimated (by about 2x at 4; light rays sample exp(-tau / 2) at a
   * voxel's centre where the voxel's mean is (1 - exp(-tau)) / tau). IsUnderResolved() says when.
   */
  vtkGetMacro(MaximumVoxelOpticalDepth, double);

  /**
   * Whether MaximumVoxelOpticalDepth exceeds 4: the medium's dense scattering parts need a
   * finer grid for their scattered light (refracta-render prints a warning).
   */
  bool IsUnderResolved() const
  {
    return this->HasScattering && this->MaximumVoxelOpticalDepth > 4.0;
  }

  /**
   * Largest optical thickness along probe rays from light `i` through the volume (0 for a
   * light without power or out of range).
   */
  double GetOpticalThicknessTowardLight(int i) const;

  ///@{
  /**
   * Single-scattering albedo range over voxels with extinction > 0 ([0, 0] if none).
   */
  vtkGetVector2Macro(AlbedoRange, double);
  ///@}

  ///@{
  /**
   * Whether any voxel scatters (sigma_s > 0) or emits (emission > 0), and the largest emission.
   */
  vtkGetMacro(HasScattering, bool);
  vtkGetMacro(HasEmission, bool);
  vtkGetMacro(MaximumEmission, double);
  ///@}

  /**
   * How anisotropic the medium's scattering is: the mean of |g| (Anisotropy) weighted by the
   * scattering coefficient, sum sigma_s |g| / sum sigma_s over the voxels (sigma_s the mean over
   * the RGB channels of albedo * sigma_t); 0 where nothing scatters. vtkEffectPlan chooses the
   * lattice by it.
   */
  vtkGetMacro(MeanAnisotropy, double);

  /**
   * Fraction of voxels that differ from vacuum (n > 1, extinction > 0 or emission > 0).
   */
  vtkGetMacro(OccupiedFraction, double);

  /**
   * Number of lights that are switched on and carry power.
   */
  vtkGetMacro(NumberOfPoweredLights, int);

  /**
   * Number of powered positional lights in or next to the medium: a voxel within 2 voxels of the
   * light (Chebyshev distance from the voxel nearest to it, in the grid's frame; the light may be
   * just outside the grid) has extinction. Concentrated sources in the medium, whose single
   * scattering the lattice's few directions carry as ray effects (vtkEffectPlan's
   * multiple-scattering method).
   */
  vtkGetMacro(NumberOfLightsInsideMedium, int);

  ///@{
  /**
   * Whether the background lights the scene too (vtkPhotonTracer::BackgroundIlluminates, set by
   * the pipeline; default off): a source of light like a powered light for vtkEffectPlan.
   */
  vtkSetMacro(EnvironmentLight, bool);
  vtkGetMacro(EnvironmentLight, bool);
  ///@}

  ///@{
  /**
   * Whether the background view rays see behind the medium has structure (an environment map or
   * the procedural checker; set by the pipeline from its view pass; default off, a uniform
   * colour). Then a view ray's deflection shows as a shift of that structure, which vtkEffectPlan
   * weighs by its angle (see its refraction estimate), not only by the voxels a ray moves.
   */
  vtkSetMacro(BackgroundHasStructure, bool);
  vtkGetMacro(BackgroundHasStructure, bool);
  ///@}

  /**
   * Number of surfaces (of SetSurfaces) with at least one polygon or triangle strip.
   */
  vtkGetMacro(NumberOfSurfaces, int);

  /**
   * Number of those surfaces that are exact dielectric interfaces
   * (vtkRefractaSurfaceMaterial::DIELECTRIC).
   */
  vtkGetMacro(NumberOfInterfaceSurfaces, int);

  /**
   * Number of particles the medium was deposited from (its field array
   * vtkRefractaParticleMedium::DepositedParticlesName(), written by vtkParticleMediumDeposit);
   * 0 for a grid medium.
   */
  vtkGetMacro(NumberOfDepositedParticles, vtkIdType);

  /**
   * Write the facts as field-data arrays named "Analysis<Fact>".
   */
  void RecordInFieldData(vtkFieldData* fieldData) const;

  /**
   * The facts on one line.
   */
  std::string GetSummary() const;

protected:
  vtkSceneAnalysis();
  ~vtkSceneAnalysis() override;

  void Reset();
  bool ScanMedium();

  // The medium's facts from the last scan, and what they were computed from.
  struct MediumCache;
  std::unique_ptr<MediumCache> Cache;
  int NumberOfMediumScans = 0;

  vtkSmartPointer<vtkImageData> Medium;
  std::vector<vtkSmartPointer<vtkLight>> Lights;

  double RefractiveIndexRange[2] = { 1.0, 1.0 };
  double MaximumBendingAngle = 0.0;
  double MaximumDisplacementInVoxels = 0.0;
  double AxisOpticalThickness[3] = { 0.0, 0.0, 0.0 };
  double MaximumOpticalThickness = 0.0;
  double MaximumScatteringThickness = 0.0;
  double MaximumVoxelOpticalDepth = 0.0;
  std::vector<double> LightOpticalThickness;
  double AlbedoRange[2] = { 0.0, 0.0 };
  bool HasScattering = false;
  double MeanAnisotropy = 0.0;
  bool HasEmission = false;
  double MaximumEmission = 0.0;
  double OccupiedFraction = 0.0;
  int NumberOfPoweredLights = 0;
  int NumberOfLightsInsideMedium = 0;
  bool EnvironmentLight = false;
  bool BackgroundHasStructure = false;
  int NumberOfSurfaces = 0;
  int NumberOfInterfaceSurfaces = 0;
  vtkIdType NumberOfDepositedParticles = 0;
  vtkSmartPointer<vtkRefractaSurfaceSet> Surfaces;

private:
  vtkSceneAnalysis(const vtkSceneAnalysis&) = delete;
  void operator=(const vtkSceneAnalysis&) = delete;
};

#endif
