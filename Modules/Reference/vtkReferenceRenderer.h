/**
 * @class   vtkReferenceRenderer
 * @brief   CPU, double-precision, unbiased Monte Carlo renderer of a Refracta medium: the ground
 *          truth the OpenCL pipeline is measured against.
 *
 * Input port 0 is a medium (vtkImageData with the arrays of vtkRefractaMedium; validated with
 * vtkMediumValidator, missing arrays take their defaults). The output is a W x H x 1 vtkImageData
 * with point arrays
 * - `HDR` (float, 4 components): linear RGB radiance, A = 1;
 * - `StandardError` (float, 3): per pixel standard error of the mean of the samples
 *   (sample standard deviation / sqrt(N)); -1 when SamplesPerPixel is 1 (undefined);
 * - `RGB` (unsigned char, 3, the active scalars): clamp(Exposure * HDR, 0, 1), then the sRGB
 *   transfer function, then round(255 x);
 * and field data `SamplesPerPixel`, `RenderSeconds`, `Seed`, `TruncatedPaths`, `NonFiniteSamples`
 * (samples that came out NaN/Inf, dropped and counted; 0 expected), `LightRadius`.
 * Pixel (i, j) is point (i, j, 0); j = 0 is the bottom row (VTK's convention).
 *
 * The physics are those of Documentation/Physics.md, solved without approximation:
 * - rays follow d/ds(n dx/ds) = grad n in the grid-local frame, integrated in arc length s with
 *   an adaptive Dormand-Prince RK5(4) step with error control on (x, v = n dx/ds), |v| renormalised
 *   to n after each step (IntegratorTolerance, MaximumStep). n and all other fields are sampled
 *   trilinearly, clamped to the edge voxels. grad n is the `RefractiveIndexGradient` array when
 *   present, else per-voxel central differences of `RefractiveIndex` (one-sided at the edge
 *   voxels), in both cases interpolated trilinearly like every other array (so grad n is
 *   continuous, which the error control needs). Where n is the same in every voxel and there is no
 *   gradient array, rays are straight lines (fast path); otherwise blocks of 4^3 cells whose whole
 *   trilinear footprint has one n and zero grad n are crossed in one straight move. Outside the
 *   box rays are straight and the medium is empty; the ray direction is continuous across the box
 *   faces (no refraction at the faces: the box face is not an interface, see Physics.md);
 * - free flights by delta tracking (ratio tracking for light connections) against per-block
 *   majorants: blocks of 4^3 cells, each majorant the largest sigma_t over the block's trilinear
 *   footprint grown by one voxel (valid for any path within one voxel of the block), raised to
 *   4 / (smallest spacing) where the footprint emits so that emission is sampled at least 4 times
 *   per voxel; positions along the curved path are advanced by arc length;
 * - emission eps is collected along the view ray up to its first real collision (estimator
 *   eps / majorant at every tentative collision); it is seen, it does not illuminate;
 * - the background (BackgroundColor or the EnvironmentMap) is seen by view rays that leave
 *   unscattered and unreflected; it illuminates nothing unless BackgroundIlluminates is on (see
 *   "Background light" below);
 * - at a real collision the path carries on with weight albedo; the light reaching the vertex is
 *   estimated by one connection ray whose direction is drawn from the one-sample MIS mixture
 *   0.5 HG + 0.5 (one emitter chosen uniformly: the uniform cone towards a light, or the
 *   background's distribution when it illuminates), weighted by HG / mixture (<= 2). The CURVED
 *   ray is then traced from there: if it reaches a light (or escapes, for directional lights and
 *   an illuminating background) without a real collision or a surface in the way, that radiance
 *   is added. The mixture pdf is positive wherever HG is, so this stays unbiased where rays bend.
 *   The path continues in an HG direction. Russian roulette from depth RouletteDepth
 *   (survival = min(1, max throughput)).
 * - surfaces (SetSurfaces, see below) are met on every straight segment and on the chord of every
 *   curved integrator step; each reflection counts as a scattering event (MaximumScatteringDepth,
 *   RouletteDepth, MaximumPathVertices);
 * - Channels: when Extinction and Albedo are grey (the three components equal in every voxel) one
 *   path carries RGB; otherwise each sample traces one path per channel.
 *
 * **Lights** (vtkLight, scene or camera lights through GetTransformedPosition/FocalPoint,
 * headlights at the camera; switched-off lights ignored; colour = DiffuseColor * Intensity).
 * Delta lights cannot be reached by a curved ray, so lights have a small extent:
 * - directional: a disc at infinity of angular radius DirectionalLightAngularRadius (degrees,
 *   default 0.5) around the direction the light comes from, uniform radiance E / (pi sin^2 delta)
 *   so that its irradiance on a plane perpendicular to it is E;
 * - point / spot: a sphere of radius LightRadius (world units; must be set > 0 for positional
 *   lights: 0, the default, is a delta light as in every pass, which this renderer refuses with
 *   an error naming 1% of the medium diagonal as a value to use) whose radiance towards a direction
 * w is I(w) / (pi r^2) (I(w) = the intensity of Physics.md, cos^e inside the cone for spots), so
 * its radiant intensity is I(w). As the extents go to 0 the image converges to the delta-light
 * answer (error O(extent^2)). Lights are not seen directly by view rays (like the pipeline's view
 * pass). A ray is tested against light spheres on each integrator chord.
 *
 * **Surfaces** (vtkRefractaSurfaceSet, world coordinates, built when the renderer runs): opaque
 * two-sided Lambertian triangles, inside, around or outside the medium's box. Outside the box rays
 * are straight and meet surfaces (and, for connections, light spheres) before the box; after
 * leaving the box a ray does not enter it again until it is reflected (a convex box). Rays are
 * intersected with the set's host BVH (vtkRefractaBVH: double precision, the watertight test of
 * Woop, Benthin and Wald), so no path leaks through the edges of a closed mesh. A hit's albedo is
 * the set's baked albedo of the texel holding it (vtkRefractaSurfaceSet::TexelIndex, the lookup of
 * the OpenCL passes), so the reference sees the colour the passes see, checker and scalar colours
 * included. At a hit the path is continued (weight albedo) after next-event estimation: one
 * connection ray drawn from the one-sample MIS mixture 0.5 cosine + 0.5 (a uniformly chosen
 * emitter: a light's cone, or the background when it illuminates), weighted
 * (cos / pi) / mixture, with the transmittance through the medium by ratio tracking and surfaces
 * occluding; then a cosine-weighted bounce about the normal on the side the path arrived from.
 * Rays leaving a surface start 1e-9 of the scene's size off it. Surfaces are not emitters.
 *
 * **Background light** (BackgroundIlluminates, off by default; refracta-render's
 * `background.illuminates`): the background becomes an emitter at infinity, sampled at every
 * medium and surface vertex together with the lights (same mixture as above: 0.5 HG or cosine +
 * 0.5 emitters, each emitter chosen with probability 1 / (number of lights + 1)). An environment
 * map is sampled by luminance: texel (i, j) with probability proportional to its solid angle times
 * the largest Rec. 709 luminance of it and its 8 neighbours (so the pdf is positive wherever the
 * bilinear lookup is), then uniformly in solid angle within it (u uniform, sin(latitude) uniform);
 * a uniform colour uniformly over the sphere. A connection ray that escapes collects the
 * background's radiance (and that of the directional discs it points into). The background still
 * reaches the camera directly only along view rays that escape unscattered.
 *
 * **Camera**: vtkCamera converted to the grid-local frame; perspective with the vertical full
 * ViewAngle and aspect W / H, or parallel with ParallelScale = half the viewport height; rays
 * through pixel centres ((i + 0.5) / W, (j + 0.5) / H), or jittered in the pixel when PixelJitter
 * is on (off by default, to compare pixel for pixel with the pipeline). Window centre, view shear
 * and UseHorizontalViewAngle are ignored.
 *
 * **Environment map**: an equirectangular vtkImageData (Wx x Hy x 1, point scalars with 3 or 4
 * components; unsigned char values are divided by 255, others used as linear radiance). A WORLD
 * direction (the medium's direction matrix is applied) maps to (u, v) by vtkRefractaEnvironmentMap
 * with EnvironmentUp / EnvironmentRight (defaults (0, 1, 0), (1, 0, 0)): VTK's skybox convention,
 * the same as the view pass (u = 0.5 is front = up x right, row 0 the -up pole), looked up
 * bilinearly with pixel centres at ((i + 0.5) / Wx, (j + 0.5) / Hy), wrapping in u and clamping
 * in v. When set it replaces BackgroundColor.
 *
 * **Determinism**: every pixel has its own random stream derived from (Seed, pixel index), and a
 * pixel is rendered by a single thread, so an image is bit-identical for a seed whatever the number
 * of threads.
 */
#ifndef vtkReferenceRenderer_h
#define vtkReferenceRenderer_h

#include "RefractaReferenceModule.h" // for export macro
#include "vtkImageAlgorithm.h"
#include "vtkSmartPointer.h" // for members

#include <vector> // for WriteImage

#ifndef __VTK_WRAP__
namespace refracta
{
namespace reference
{
struct Scene;
struct View;
}
}
#endif

class vtkCamera;
class vtkLight;
class vtkLightCollection;
class vtkRefractaSurfaceSet;

class REFRACTAREFERENCE_EXPORT vtkReferenceRenderer : public vtkImageAlgorithm
{
public:
  static vtkReferenceRenderer* New();
  vtkTypeMacro(vtkReferenceRenderer, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The camera (world coordinates). Required.
   */
  void SetCamera(vtkCamera* camera);
  vtkCamera* GetCamera();
  ///@}

  ///@{
  /**
   * The lights (world coordinates). None by default: then only emission and the background are
   * seen.
   */
  void AddLight(vtkLight* light);
  void RemoveAllLights();
  void SetLights(vtkLightCollection* lights);
  vtkLightCollection* GetLights();
  ///@}

  ///@{
  /**
   * Output image size in pixels, each in [1, 16384]. Default 256 x 256.
   */
  void SetImageSize(int width, int height);
  vtkGetVector2Macro(ImageSize, int);
  ///@}

  ///@{
  /**
   * Uniform background radiance (linear RGB, >= 0), seen by unscattered view rays. Default black.
   */
  void SetBackgroundColor(double x, double y, double z);
  void SetBackgroundColor(const double value[3]);
  vtkGetVector3Macro(BackgroundColor, double);
  ///@}

  ///@{
  /**
   * Equirectangular environment image replacing the background colour (see the class
   * documentation for the mapping). Default none.
   */
  void SetEnvironmentMap(vtkImageData* image);
  vtkImageData* GetEnvironmentMap();
  ///@}

  ///@{
  /**
   * World vectors orienting the environment map (vtkRefractaEnvironmentMap): Up is the v = 1
   * pole, Right is u = 0.75. Defaults (0, 1, 0) and (1, 0, 0), as vtkRenderer and the view pass.
   */
  void SetEnvironmentUp(double x, double y, double z);
  void SetEnvironmentUp(const double value[3]);
  vtkGetVector3Macro(EnvironmentUp, double);
  void SetEnvironmentRight(double x, double y, double z);
  void SetEnvironmentRight(const double value[3]);
  vtkGetVector3Macro(EnvironmentRight, double);
  ///@}

  ///@{
  /**
   * Whether the background (the EnvironmentMap, else BackgroundColor) also lights the scene: off
   * (default), it is only seen by view rays that leave unscattered; on, it is an emitter like
   * the lights, sampled at every vertex (see the class documentation).
   */
  vtkSetMacro(BackgroundIlluminates, bool);
  vtkGetMacro(BackgroundIlluminates, bool);
  vtkBooleanMacro(BackgroundIlluminates, bool);
  ///@}

  ///@{
  /**
   * Opaque two-sided Lambertian surfaces (world coordinates; built with
   * vtkRefractaSurfaceSet::Build() when the renderer runs). Default none. Paths meet them inside
   * and outside the medium (see the class documentation).
   */
  void SetSurfaces(vtkRefractaSurfaceSet* surfaces);
  vtkRefractaSurfaceSet* GetSurfaces();
  ///@}

  ///@{
  /**
   * Monte Carlo samples (paths) per pixel, >= 1. Default 16.
   */
  vtkSetClampMacro(SamplesPerPixel, int, 1, 1 << 24);
  vtkGetMacro(SamplesPerPixel, int);
  ///@}

  ///@{
  /**
   * Seed of the random streams. Default 0.
   */
  vtkSetMacro(Seed, unsigned int);
  vtkGetMacro(Seed, unsigned int);
  ///@}

  ///@{
  /**
   * Largest number of scattering events along a path: 0 shows only unscattered view rays
   * (emission and background), 1 single scattering, -1 (default) unlimited (Russian roulette).
   */
  vtkSetClampMacro(MaximumScatteringDepth, int, -1, VTK_INT_MAX);
  vtkGetMacro(MaximumScatteringDepth, int);
  ///@}

  ///@{
  /**
   * Scattering depth from which Russian roulette terminates paths (survival probability
   * min(1, largest throughput component)). Default 8.
   */
  vtkSetClampMacro(RouletteDepth, int, 1, VTK_INT_MAX);
  vtkGetMacro(RouletteDepth, int);
  ///@}

  ///@{
  /**
   * Safety limit on scattering events per path (a path reaching it is dropped and counted in the
   * field data `TruncatedPaths`, a bias the user can see). Default 100000.
   */
  vtkSetClampMacro(MaximumPathVertices, int, 1, VTK_INT_MAX);
  vtkGetMacro(MaximumPathVertices, int);
  ///@}

  ///@{
  /**
   * Local error tolerance of the RK5(4) integrator per step, relative to the smallest voxel
   * spacing (position) and to the largest n (v = n dx/ds). Default 1e-7.
   */
  void SetIntegratorTolerance(double value);
  vtkGetMacro(IntegratorTolerance, double);
  ///@}

  ///@{
  /**
   * Largest integrator step in units of the smallest voxel spacing. Default 1.
   */
  void SetMaximumStep(double value);
  vtkGetMacro(MaximumStep, double);
  ///@}

  ///@{
  /**
   * Angular radius of directional lights, degrees, in [1e-4, 45]. Default 0.5.
   */
  void SetDirectionalLightAngularRadius(double value);
  vtkGetMacro(DirectionalLightAngularRadius, double);
  ///@}

  ///@{
  /**
   * Radius of point and spot light spheres, world units. 0 (default) is a delta light, as in every
   * Refracta pass; this estimator cannot reach a delta point or spot light (paths connect to a
   * light by hitting its sphere), so RequestData refuses positional lights with LightRadius 0
   * and names a radius to use. Set it explicitly (e.g. 1% of the medium diagonal, the value the
   * renderer used to substitute silently) and give vtkPhotonTracer the same value to compare.
   */
  void SetLightRadius(double value);
  vtkGetMacro(LightRadius, double);
  ///@}

  ///@{
  /**
   * Jitter view rays uniformly inside their pixel (anti-aliasing). Off by default: rays go
   * through pixel centres like the pipeline's.
   */
  vtkSetMacro(PixelJitter, bool);
  vtkGetMacro(PixelJitter, bool);
  vtkBooleanMacro(PixelJitter, bool);
  ///@}

  ///@{
  /**
   * Exposure multiplying HDR before the 8-bit tone mapping (clamp, sRGB). Default 1.
   */
  void SetExposure(double value);
  vtkGetMacro(Exposure, double);
  ///@}

  /**
   * Henyey-Greenstein phase function (per steradian), g in (-1, 1), cosTheta between the incoming
   * and outgoing travel directions; evaluated without cancellation near abs(g) = 1.
   */
  static double HenyeyGreensteinPhase(double g, double cosTheta);

  /**
   * Draw an outgoing direction from HG around the travel direction `in` (unit) with the uniform
   * numbers u1 (for cos theta) and u2 (for the azimuth) in [0, 1).
   */
  static void SampleHenyeyGreenstein(
    double g, const double in[3], double u1, double u2, double out[3]);

  /**
   * Integrate a ray through `medium` (world coordinates) with this renderer's integrator settings,
   * ignoring extinction: from `origin` in the unit `direction`, for `arcLength` world units of
   * path (straight outside the medium). Writes the end point and the unit end direction. Returns
   * the number of accepted integrator steps, or -1 when the medium is invalid.
   */
  int TraceRay(vtkImageData* medium, const double origin[3], const double direction[3],
    double arcLength, double endPoint[3], double endDirection[3]);

protected:
  vtkReferenceRenderer();
  ~vtkReferenceRenderer() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestUpdateExtent(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  vtkMTimeType GetMTime() override;

#ifndef __VTK_WRAP__
  /**
   * Validates the medium and this renderer's settings and builds what every estimator of the
   * module shares: the medium, lights, surfaces and background in the grid-local frame, the
   * tracers with the integrator settings, and the camera. False (after vtkErrorMacro naming the
   * bad input) when something is invalid.
   */
  bool BuildScene(
    vtkImageData* medium, refracta::reference::Scene& scene, refracta::reference::View& view);
#endif

  /**
   * Writes the W x H output arrays `HDR`, `StandardError` and `RGB` (the active scalars) from
   * per-pixel RGB means and standard errors (3 values a pixel).
   */
  void WriteImage(vtkImageData* output, int W, int H, const std::vector<double>& mean,
    const std::vector<double>& stderrs);

  /**
   * Adds a one-value field data array (vtkIntArray when integer, else vtkDoubleArray).
   */
  static void AddFieldValue(vtkImageData* output, const char* name, double value, bool integer);

  vtkSmartPointer<vtkCamera> Camera;
  vtkSmartPointer<vtkLightCollection> Lights;
  vtkSmartPointer<vtkImageData> EnvironmentMap;
  vtkSmartPointer<vtkRefractaSurfaceSet> Surfaces;
  bool BackgroundIlluminates = false;
  int ImageSize[2] = { 256, 256 };
  double BackgroundColor[3] = { 0.0, 0.0, 0.0 };
  double EnvironmentUp[3] = { 0.0, 1.0, 0.0 };
  double EnvironmentRight[3] = { 1.0, 0.0, 0.0 };
  int SamplesPerPixel = 16;
  unsigned int Seed = 0;
  int MaximumScatteringDepth = -1;
  int RouletteDepth = 8;
  int MaximumPathVertices = 100000;
  double IntegratorTolerance = 1e-7;
  double MaximumStep = 1.0;
  double DirectionalLightAngularRadius = 0.5;
  double LightRadius = 0.0;
  bool PixelJitter = false;
  double Exposure = 1.0;

private:
  vtkReferenceRenderer(const vtkReferenceRenderer&) = delete;
  void operator=(const vtkReferenceRenderer&) = delete;
};

#endif
