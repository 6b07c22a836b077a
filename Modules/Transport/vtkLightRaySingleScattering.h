/**
 * @class   vtkLightRaySingleScattering
 * @brief   Noise-free single scattering where light travels straight: per-voxel light rays, or
 *          Ren et al.'s (2008) gradient-based interpolation with dynamic sampling.
 *
 * Input port 0: a Refracta medium (vtkImageData, vtkRefractaMedium arrays; validated with
 * vtkMediumValidator). The refractive index is ignored: every light ray is straight, so this
 * pass is right only where nothing refracts (vtkEffectPlan decides; photons remain for curved
 * paths). Lights as vtkPhotonTracer takes them (Documentation/Physics.md): directional irradiance
 * E, point intensity I, spot I cos^e inside the cone, colour x intensity, LightRadius and
 * DirectionalLightAngularRadius for extended lights; surfaces (SetSurfaces, MediumToWorld) cast
 * shadows.
 *
 * Output: a lighting volume (vtkRefractaLightingVolume) on the medium's grid with
 * - `Radiance` (3): S1 = sigma_s phi, phi the fluence of the unscattered beams (RGB, power per
 *   unit volume scattered out of them, the same quantity as vtkPhotonTracer's, evaluated at the
 *   voxel centre instead of averaged over the voxel, except at sharp voxels: SharpVoxelBoxMeans);
 * - `RadianceDirection` (3): the unit mean travel direction of that light, each light weighted by
 *   its fluence (sum of RGB); zero where nothing scatters;
 * - with two or more lights over an anisotropic medium, the same two fields per lobe
 *   (MaximumRadianceLobes): vtkRefractaLightingVolume::RadianceLobeName(k) and
 *   RadianceLobeDirectionName(k), S1 and mean direction of the lights of lobe k (they sum to
 *   `Radiance`), which the view pass shades each about its own direction.
 * Field data: `SingleScatteringMethod` (string: light_rays or interpolated), `NumberOfSamples`,
 * `EvaluatedPoints` (points at which light rays were marched), `UncoveredVoxels`, `BoxMeanVoxels`,
 * `RadianceLobes` (the lobes made, 1: none).
 *
 * Method LIGHT_RAYS (the paper's per-voxel baseline, Kajiya and Von Herzen's first pass): for
 * every voxel that scatters and every light, a straight ray from the voxel centre to the light;
 * its optical depth is integrated exactly through the piecewise-constant voxels (the photon
 * pass's model), whole 8^3 macro cells at a time where nothing attenuates; surfaces end it.
 * Extended lights use LightQuadrature equal-solid-angle directions over the cap they subtend
 * (deterministic, so still noise-free): soft shadows.
 *
 * Method INTERPOLATED (Ren et al. 2008, sections 4 and 5): phi and the flux vector are computed by
 * light rays at sparse samples x_j with their gradient (central differences at +-Delta, Delta the
 * voxel spacing; the points are clamped into the box of voxel centres, so the difference is
 * one-sided at the medium's faces, where the light field is discontinuous, and a vertex outside
 * the box takes the first-order value from its clamped point), and interpolated at every voxel by
 * eq. 4, L(x) = sum W_j (L_j + (x - x_j).grad L_j) / sum W_j with W_j = R_j / |x - x_j| over the
 * samples whose valid sphere holds x. The samples come from dynamic sampling: the vertices of a
 * 16^3 grid G1 (whose valid spheres, radius = the grid interval, touch a scattering voxel) are the
 * first set; each sample's local shading error (eq. 6) E_j = R_j^3 sum_i |L~(x_ij) - L(x_ij)|
 * D(x_ij) tau_j / 6 at x_ij = x_j +- R_j on the three axes (L~ the sample's own first-order
 * estimate, eq. 7; D = sigma_s, largest channel of the product; tau_j the transmittance to
 * ViewPoint when one is set, else 1, an upper bound for any view, computed at G1 and inherited by
 * the descendants as in the paper) is compared with epsilon = ErrorTolerance x (largest sigma_s phi
 * seen at G1) x R_1^3; a sample above it is replaced by the vertices of the next grid (32^3, 64^3,
 * ... up to MaximumGridResolution and half the medium's resolution) within R_j + (sqrt 3 / 2)
 * h_{k+1} of it (the margin makes the new valid spheres cover the old one). Samples of the finest
 * grid are kept whatever their error. Differences from the paper: the first set is the G1 vertices,
 * not the centres of a Gaussian density model (our media are voxels); eq. 4 is evaluated per voxel
 * over the grid vertices in reach (the same sum the paper's splats accumulate, without float
 * atomics); optical depths are exact voxel integrals instead of samples every Delta / 2.
 *
 * Bad input (errors, empty output): no medium, an invalid medium, a non-finite or negative light.
 * Warnings (the output is still right): no lights or no scattering (a zero lighting volume), a
 * light inside an opaque voxel (optical depth > 30 across it).
 */
#ifndef vtkLightRaySingleScattering_h
#define vtkLightRaySingleScattering_h

#include "RefractaTransportModule.h" // for export macro
#include "vtkImageAlgorithm.h"
#include "vtkRefractaLightingVolume.h" // for MAXIMUM_RADIANCE_LOBES
#include "vtkSmartPointer.h" // for members

#include <vector> // for the sample positions

struct _cl_kernel; // cl_kernel, for RunChunked
class vtkDoubleArray;
class vtkIntArray;
class vtkLight;
class vtkLightCollection;
class vtkMatrix4x4;
class vtkOpenCLContext;
class vtkRefractaSurfaceSet;

class REFRACTATRANSPORT_EXPORT vtkLightRaySingleScattering : public vtkImageAlgorithm
{
public:
  static vtkLightRaySingleScattering* New();
  vtkTypeMacro(vtkLightRaySingleScattering, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Methods
  {
    LIGHT_RAYS = 0,
    INTERPOLATED = 1
  };

  ///@{
  /**
   * LIGHT_RAYS (default) or INTERPOLATED (see the class description).
   */
  vtkSetClampMacro(Method, int, LIGHT_RAYS, INTERPOLATED);
  vtkGetMacro(Method, int);
  void SetMethodToLightRays() { this->SetMethod(LIGHT_RAYS); }
  void SetMethodToInterpolated() { this->SetMethod(INTERPOLATED); }
  static const char* GetMethodName(int method);
  ///@}

  ///@{
  /**
   * The lights (world coordinates, the medium's data frame); switched-off lights are ignored.
   */
  void AddLight(vtkLight* light);
  void RemoveAllLights();
  void SetLights(vtkLightCollection* lights);
  vtkLightCollection* GetLights();
  ///@}

  ///@{
  /**
   * Opaque surfaces that shadow the light rays (nullptr, default: none) and the medium's placement
   * in their world (a rigid matrix; nullptr: identity), as vtkPhotonTracer takes them.
   */
  void SetSurfaces(vtkRefractaSurfaceSet* surfaces);
  vtkRefractaSurfaceSet* GetSurfaces();
  void SetMediumToWorld(vtkMatrix4x4* matrix);
  vtkMatrix4x4* GetMediumToWorld();
  ///@}

  ///@{
  /**
   * OpenCL context; nullptr (default) means vtkOpenCLContext::GetDefault().
   */
  void SetContext(vtkOpenCLContext* context);
  vtkOpenCLContext* GetContext();
  ///@}

  ///@{
  /**
   * Extended lights, as vtkPhotonTracer's: LightRadius (world units, default 0: point and spot
   * lights are delta lights) and DirectionalLightAngularRadius (degrees, < 45, default 0).
   * LightQuadrature (default 16) directions per extended light and point.
   */
  void SetLightRadius(double value);
  vtkGetMacro(LightRadius, double);
  void SetDirectionalLightAngularRadius(double value);
  vtkGetMacro(DirectionalLightAngularRadius, double);
  vtkSetClampMacro(LightQuadrature, int, 1, 1024);
  vtkGetMacro(LightQuadrature, int);
  ///@}

  ///@{
  /**
   * Dynamic sampling (INTERPOLATED): ErrorTolerance epsilon relative to the brightest G1 sphere
   * (default 0.002), the coarsest grid's resolution (default 16 cells along the longest axis) and
   * the finest (default 64; never more than half the medium's resolution).
   */
  void SetErrorTolerance(double value);
  vtkGetMacro(ErrorTolerance, double);
  vtkSetClampMacro(CoarsestGridResolution, int, 2, 4096);
  vtkGetMacro(CoarsestGridResolution, int);
  vtkSetClampMacro(MaximumGridResolution, int, 2, 4096);
  vtkGetMacro(MaximumGridResolution, int);
  ///@}

  ///@{
  /**
   * Viewer position for eq. 6's transmittance to the viewer (world units, the medium's data
   * frame). Off by default: tau = 1, samples placed for every view.
   */
  void SetViewPoint(double x, double y, double z);
  void SetViewPoint(const double value[3]);
  vtkGetVector3Macro(ViewPoint, double);
  vtkSetMacro(UseViewPoint, bool);
  vtkGetMacro(UseViewPoint, bool);
  vtkBooleanMacro(UseViewPoint, bool);
  ///@}

  ///@{
  /**
   * Box means at sharp voxels (default on). Where the trilinear sigma_t changes steeply within a
   * voxel's box (over the voxel and its 26 neighbours, 0 past the grid's faces, half the range of
   * sigma_t times the largest spacing above 0.25, i.e. a jump of optical depth per voxel above
   * 0.5, and something there scatters: the faces of dense bodies and the empty voxels beside
   * them), S1 at the centre misses the light scattered in the ramp between a dense centre and an
   * empty one (a dense slab at an optical depth of 1 per voxel: -26% of the reference's image).
   * Those voxels get the mean of sigma_s phi over their box instead, the quantity every photon
   * deposit estimates, computed without noise (-4.2% on that slab, photons -5.4%): parallel
   * lines along each light's direction, 4 x 4 per face the light enters by, carrying the
   * fluence from a plane 4 voxels upstream (five light rays, or one per line where the fluence
   * there is not log-linear) through the medium in front of the box and then through its pieces
   * (light_rays.cl, Documentation/Physics.md, "Single scattering without noise"). Smooth media
   * have no sharp voxels and are unchanged. Cost: 40-70 microseconds per sharp voxel and light
   * on the 2-core CPU (the light-ray pass 1.6x to 4.4x slower on a dense slab or ball at 128^3).
   */
  vtkSetMacro(SharpVoxelBoxMeans, bool);
  vtkGetMacro(SharpVoxelBoxMeans, bool);
  vtkBooleanMacro(SharpVoxelBoxMeans, bool);
  ///@}

  ///@{
  /**
   * The most lobes S1 is kept in (default 2, 1 to vtkRefractaLightingVolume::
   * MAXIMUM_RADIANCE_LOBES; 1: `Radiance` alone). The view pass shades S1 with the phase
   * function about one mean direction per voxel: right for the light of one light, wrong where
   * lights from different sides cross (their mean points between them; two lights at g = 0.5,
   * Refracta.SingleScatteringAgainstReference: -14% over the image, -23% in places). So each
   * lobe, a group of lights, gets its own S1 and mean direction: lobe k is light k (of those
   * switched on with power) where there are no more lights than lobes (then exact), else the
   * lights grouped by their travel direction at the medium's centre (the lobes' first lights
   * spread as far apart in angle as they go, the strongest first; every other light joins the
   * lobe nearest in angle). Lobes are made only
   * where they change the image: two or more lights, and some scattering voxel with anisotropy
   * g != 0 (the phase function is isotropic otherwise). Cost: 6 floats per voxel and lobe on the
   * host and the device, and the view pass reads every lobe. GetLastNumberOfLobes(): the lobes of
   * the last run (1: none stored).
   */
  vtkSetClampMacro(MaximumRadianceLobes, int, 1, vtkRefractaLightingVolume::MAXIMUM_RADIANCE_LOBES);
  vtkGetMacro(MaximumRadianceLobes, int);
  vtkGetMacro(LastNumberOfLobes, int);
  ///@}

  ///@{
  /**
   * The last run: seconds (total, of which dynamic sampling and the final per-voxel stage), the
   * samples of the interpolation (total and per grid level), the points at which light rays were
   * marched, voxels no valid sphere covered (computed by their own rays; expected 0), and the
   * sharp voxels given box means (SharpVoxelBoxMeans) with the seconds they took.
   */
  vtkGetMacro(TotalSeconds, double);
  vtkGetMacro(SamplingSeconds, double);
  vtkGetMacro(VoxelSeconds, double);
  vtkGetMacro(NumberOfSamples, int);
  vtkGetMacro(NumberOfEvaluatedPoints, long long);
  vtkGetMacro(NumberOfUncoveredVoxels, int);
  vtkGetMacro(NumberOfBoxMeanVoxels, long long);
  vtkGetMacro(BoxMeanSeconds, double);
  const std::vector<int>& GetSamplesPerLevel() const { return this->SamplesPerLevel; }
  ///@}

  /**
   * Whether the last run was aborted (AbortExecute set, e.g. by a ProgressEvent observer): the
   * output is then empty and no error is reported. Progress is reported per chunk of voxels (and
   * of sharp voxels for their box means, and per grid level of the interpolation); the abort is
   * checked at the same points.
   */
  vtkGetMacro(LastRunAborted, bool);

  /**
   * The last run's final samples: positions (grid-local, 3 components) and grid levels (0: G1).
   */
  vtkDoubleArray* GetSamplePositions();
  vtkIntArray* GetSampleLevels();

  /**
   * The direct irradiance on the Lambertian texels of GetSurfaces() (built here if needed) lit
   * by GetLights() through `medium` along straight rays: per texel, the mean over its four
   * sample points (vtkRefractaSurfaceSet::GetTexelSamplePoints) of sum over lights of
   * E_l T_l V_l max(+-n . q_l, 0) (T the medium's transmittance, V 0 where a surface, glass
   * included, blocks the ray, n the triangle's winding normal: + for the front side, - for the
   * back, as the photons' atlas counts them; extended lights by their quadrature directions).
   * Irradiance in the units of vtkPhotonTracer's SurfaceIrradiance, 6 floats per texel (front
   * RGB, back RGB; vtkRefractaLightingVolume::SurfaceSide) into `irradiance` (0 on glass
   * texels): with vtkPhotonTracer::SkipDirectSurfaceLight the photons leave exactly this part out,
   * and the sum of both is their whole irradiance without its noise. Uses MediumToWorld,
   * LightRadius, DirectionalLightAngularRadius, LightQuadrature and the context as RequestData
   * does. Returns false after an error (an invalid medium, no surfaces, a bad light).
   */
  bool ComputeSurfaceIrradiance(vtkImageData* medium, std::vector<float>& irradiance);

  /// Seconds of the last ComputeSurfaceIrradiance() and the points it marched (4 per texel).
  vtkGetMacro(SurfaceSeconds, double);
  vtkGetMacro(NumberOfSurfacePoints, long long);

  struct Internals;

protected:
  vtkLightRaySingleScattering();
  ~vtkLightRaySingleScattering() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  bool SetUp(Internals& run);
  bool SetUpLights(Internals& run);
  bool SetUpSurfaces(Internals& run);
  bool Upload(Internals& run);
  bool RunLightRays(Internals& run);
  bool RunInterpolation(Internals& run);
  bool RunBoxMeans(Internals& run);
  // The four sample points (grid-local) and triangle normals of every Lambertian texel.
  void MakeTexelSamples(Internals& run, std::vector<float>& points, std::vector<float>& normals);
  // Groups the lights into lobes (MaximumRadianceLobes): run.Lobes and each light's lobe.
  void AssignLobes(Internals& run);
  // phi and flux (4 floats per point each) at the points, per block of the lobes (light_rays.cl:
  // block 0 all lights, 1 + k lobe k; one block without lobes).
  bool EvaluatePoints(Internals& run, const std::vector<float>& points, const void* lights,
    int lightCount, std::vector<std::vector<float>>& phi, std::vector<std::vector<float>>& flux);
  void WriteOutput(Internals& run, vtkImageData* output);
  // Runs the 1D `kernel` over `count` work-items in chunks, reporting progress from `first` to
  // `last` and stopping (run.Aborted) when AbortExecute is set.
  bool RunChunked(
    Internals& run, _cl_kernel* kernel, size_t count, const char* label, double first, double last);

  int Method = LIGHT_RAYS;
  vtkSmartPointer<vtkLightCollection> Lights;
  vtkSmartPointer<vtkRefractaSurfaceSet> Surfaces;
  vtkSmartPointer<vtkMatrix4x4> MediumToWorld;
  vtkSmartPointer<vtkOpenCLContext> Context;
  double LightRadius = 0.0;
  double DirectionalLightAngularRadius = 0.0;
  int LightQuadrature = 16;
  double ErrorTolerance = 0.002;
  int CoarsestGridResolution = 16;
  int MaximumGridResolution = 64;
  double ViewPoint[3] = { 0, 0, 0 };
  bool UseViewPoint = false;
  bool SharpVoxelBoxMeans = true;
  int MaximumRadianceLobes = 2;

  int LastNumberOfLobes = 1;
  double TotalSeconds = 0;
  double SamplingSeconds = 0;
  double VoxelSeconds = 0;
  int NumberOfSamples = 0;
  long long NumberOfEvaluatedPoints = 0;
  int NumberOfUncoveredVoxels = 0;
  long long NumberOfBoxMeanVoxels = 0;
  double BoxMeanSeconds = 0;
  double SurfaceSeconds = 0;
  long long NumberOfSurfacePoints = 0;
  bool LastRunAborted = false;
  std::vector<int> SamplesPerLevel;
  vtkSmartPointer<vtkDoubleArray> SamplePositions;
  vtkSmartPointer<vtkIntArray> SampleLevels;

private:
  vtkLightRaySingleScattering(const vtkLightRaySingleScattering&) = delete;
  void operator=(const vtkLightRaySingleScattering&) = delete;
};

#endif
