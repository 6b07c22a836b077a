/**
 * @class   vtkRefractaViewPass
 * @brief   The view pass on the OpenCL device: one (curved) view ray per pixel through a medium
 *          and its lighting volume (Kernels/view_pass.cl).
 *
 * This is the engine shared by vtkRefractaImageRenderer (headless), vtkRefractiveVolumeMapper
 * (render window) and the refracta-render program. It keeps the medium and the lighting volume
 * on the device and uploads them again only when they change (pointer or MTime), so a camera
 * change costs one kernel launch.
 *
 * Per pixel it evaluates (Documentation/Physics.md)
 *   L = sum over steps of T [ p(g, cos) S1 + S_ms / (4 pi) + eps ] ds + T_exit L_bg(d_exit)
 * with the medium held constant at each step's midpoint and each step integrated exactly, so a
 * homogeneous medium gives the analytic answer for any step length.
 *
 * Settings (units, defaults):
 * - StepSize: view-ray step in voxels (multiples of the smallest spacing), clamped to
 *   [0.01, 16]; default 1 (one voxel, as Sun et al. argue). Every floating-point setting of this
 *   class (and of every Refracta class) clamps as vtkSetClampMacro does but refuses NaN with an
 *   error that keeps the old value (vtkRefractaSettings.h).
 * - RayMode: AUTO (default: curved rays when the medium's refractive index varies, by more than
 *   1e-6, and some sample of its gradient is non-zero: a medium voxelized with exact interfaces,
 *   whose n jumps only across the meshes, gets straight rays that refract at the surfaces),
 *   STRAIGHT, or CURVED.
 * - TransmittanceCutoff: a ray stops when every channel's transmittance is below it; [0, 1],
 *   default 1e-4 (the radiance it can miss is at most cutoff times the rest of the path's).
 * - MaxSteps: cap on steps per ray; 0 (default) means 4 (Nx + Ny + Nz) / StepSize, enough for
 *   any straight ray several times over; curved rays trapped by total internal reflection stop
 *   there and see no background.
 * - BackgroundColor: uniform background radiance (linear RGB), default (0, 0, 0).
 * - EnvironmentMap: an equirectangular image (vtkImageData, 3 or 4 components; unsigned char
 *   values are divided by 255, other types used as linear radiance) that replaces the colour.
 *   World directions map to (u, v) by vtkRefractaEnvironmentMap (VTK's skybox convention:
 *   front = up x right, u = atan2(x, z) / 2 pi + 1/2 across the image's x, v = atan2(y, |(x, z)|)
 *   / pi + 1/2 up its y, row 0 at the bottom; u = 0.5 is front = -z with the defaults).
 *   Defaults: right (1, 0, 0), up (0, 1, 0), as vtkRenderer's environment.
 *
 * - EmptySpaceSkipping: on (default) or off. Rays jump over macro cells (MacroCellSize^3 voxels)
 *   in which nothing can change them: extinction, emission, Radiance and MultipleScattering all
 *   zero and, for curved rays, grad n zero (so rays are straight there), within the cell dilated
 *   by 2 voxels (the trilinear footprint plus slack). Whole steps are skipped on the unchanged step
 *   grid, so the image equals the one without skipping up to float rounding. The occupancy grid is
 *   rebuilt only when the medium, the lighting volume or MacroCellSize changes.
 * - MacroCellSize: edge of a macro cell in voxels, clamped to [2, 64]; default 8.
 * - LaneMarching: on (default) or off. On a CPU device, a scene without surfaces (any medium
 *   and lighting volume, straight or curved rays; what vtkTransferFunctionMedium makes of a
 *   vtkVolumeProperty included) is marched by a kernel of its own, eight rays per work-item in
 *   SIMD lanes (Kernels/view_lanes.cl), with or without skipping: the same steps and the same
 *   image up to float rounding, 1.3-3x faster on PoCL than the general kernel
 *   (Documentation/Reference.md, "Rendering"). Surfaces and GPU devices use the general
 *   kernel; GetLastLaneMarching() says which ran.
 *
 * The lighting volume must be on the medium's grid and carry `Radiance` (S1, RGB) with
 * `RadianceDirection` (3, unit, in the grid-local frame), and/or `MultipleScattering` (S_ms, RGB),
 * optionally with `MultipleScatteringDirection` (its flux over its fluence F / phi_ms, grid-local,
 * length f <= 1: S_ms is shaded with the phase function of anisotropy g f about F, light spread
 * as a Henyey-Greenstein lobe of mean cosine f; without it, isotropically).
 * With S1 in lobes (vtkRefractaLightingVolume::RadianceLobeName(k) and
 * RadianceLobeDirectionName(k), complete pairs for k = 0 .. K - 1, K >= 2) each lobe is shaded
 * about its own direction instead of `Radiance` about `RadianceDirection`.
 *
 * Surfaces (SetSurfaces()): opaque two-sided Lambertian triangles (vtkRefractaSurfaceSet, world
 * coordinates) inside, behind, under or around the medium. A view ray, curved in the medium and
 * straight outside it, stops at the first surface it meets and adds T E rho / (pi n^2): E the
 * irradiance the photon pass stored per texel (the lighting volume's field array
 * vtkRefractaLightingVolume::SurfaceIrradianceName(); none: the surfaces are unlit, black),
 * reconstructed at the hit point (SurfaceFilter), rho the texel's albedo, T the transmittance of
 * the path, n the index at the hit (1 outside the medium's box). The pixel is then opaque (alpha
 * 1, transmittance 0). The set's BVH, triangles and atlas are uploaded once per Build() of the set
 * (GetNumberOfSurfaceUploads()); a camera move uploads nothing.
 *
 * Glass: triangles of a DIELECTRIC surface material are interfaces, not opaque. A ray meeting
 * one splits into a Fresnel-reflected leg (weight R) and a refracted leg (weight 1 - R; none under
 * total internal reflection), with the interpolated shading normal, each continuing as an
 * ordinary march (DielectricSplitDepth; Documentation/Physics.md, "Glass in the view pass"); pixels
 * over edges of glass take several rays (DielectricSupersampling). The
 * pixel's transmittance output is then the summed weight of the legs that end in the background
 * (or at the depth limit), its surface depth the distance to the first surface met.
 */
#ifndef vtkRefractaViewPass_h
#define vtkRefractaViewPass_h

#include "RefractaRenderingModule.h" // for export macro
#include "vtkNew.h"                  // for members
#include "vtkObject.h"
#include "vtkOpenCLMemoryPlan.h" // for the memory plan member
#include "vtkSmartPointer.h"     // for members

#ifndef __VTK_WRAP__
#include "vtkOpenCLHandle.h" // for cl_kernel
#endif

#include <memory> // for std::unique_ptr
#include <string> // for the problem sentences
#include <vector> // for std::vector

class vtkCamera;
class vtkImageData;
class vtkMatrix4x4;
class vtkOpenCLContext;
class vtkRefractaSurfaceSet;
struct vtkRefractaViewLaunch;

class REFRACTARENDERING_EXPORT vtkRefractaViewPass : public vtkObject
{
public:
  static vtkRefractaViewPass* New();
  vtkTypeMacro(vtkRefractaViewPass, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum RayModes
  {
    AUTO = 0,
    STRAIGHT = 1,
    CURVED = 2
  };

  enum SurfaceFilters
  {
    NEAREST_TEXEL = 0, ///< the hit texel's irradiance, piecewise constant
    LINEAR_TEXEL = 1   ///< linear within the hit texel between its corners' neighbour means
  };

  ///@{
  /**
   * OpenCL context; default vtkOpenCLContext::GetDefault().
   */
  void SetContext(vtkOpenCLContext* context);
  vtkOpenCLContext* GetContext();
  ///@}

  ///@{
  /**
   * View-ray step in voxels (see the class description). Default 1.
   */
  void SetStepSize(double value);
  vtkGetMacro(StepSize, double);
  ///@}

  ///@{
  /**
   * AUTO (default), STRAIGHT or CURVED.
   */
  vtkSetClampMacro(RayMode, int, AUTO, CURVED);
  vtkGetMacro(RayMode, int);
  ///@}

  ///@{
  /**
   * Transmittance below which a ray stops, [0, 1]. Default 1e-4.
   */
  void SetTransmittanceCutoff(double value);
  vtkGetMacro(TransmittanceCutoff, double);
  ///@}

  ///@{
  /**
   * Maximum steps per ray; 0 (default) = 4 (Nx + Ny + Nz) / StepSize.
   */
  vtkSetClampMacro(MaxSteps, int, 0, 1 << 28);
  vtkGetMacro(MaxSteps, int);
  ///@}

  ///@{
  /**
   * Empty-space skipping (see the class description). Default on.
   */
  vtkSetMacro(EmptySpaceSkipping, bool);
  vtkGetMacro(EmptySpaceSkipping, bool);
  vtkBooleanMacro(EmptySpaceSkipping, bool);
  ///@}

  ///@{
  /**
   * Eight-lane kernel where it applies (see the class description). Default on; off always runs
   * the general kernel (for comparisons).
   */
  vtkSetMacro(LaneMarching, bool);
  vtkGetMacro(LaneMarching, bool);
  vtkBooleanMacro(LaneMarching, bool);
  ///@}

  ///@{
  /**
   * Macro-cell edge in voxels for empty-space skipping, [2, 64]. Default 8.
   */
  vtkSetClampMacro(MacroCellSize, int, 2, 64);
  vtkGetMacro(MacroCellSize, int);
  ///@}

  ///@{
  /**
   * Uniform background radiance, linear RGB >= 0. Default (0, 0, 0).
   */
  void SetBackgroundColor(double x, double y, double z);
  void SetBackgroundColor(const double value[3]);
  vtkGetVector3Macro(BackgroundColor, double);
  ///@}

  ///@{
  /**
   * Equirectangular environment image (see the class description); nullptr (default) uses the
   * background colour.
   */
  void SetEnvironmentMap(vtkImageData* image);
  vtkImageData* GetEnvironmentMap();
  void SetEnvironmentUp(double x, double y, double z);
  void SetEnvironmentUp(const double value[3]);
  vtkGetVector3Macro(EnvironmentUp, double);
  void SetEnvironmentRight(double x, double y, double z);
  void SetEnvironmentRight(const double value[3]);
  vtkGetVector3Macro(EnvironmentRight, double);
  ///@}

  ///@{
  /**
   * Opaque surfaces seen by the view rays (see the class description); nullptr (default): none.
   * The set is built (cached) and uploaded in Render() when its Build() is new.
   */
  void SetSurfaces(vtkRefractaSurfaceSet* surfaces);
  vtkRefractaSurfaceSet* GetSurfaces();
  ///@}

  ///@{
  /**
   * How the surface irradiance is reconstructed at a hit (Documentation/Physics.md, "Surfaces in
   * the view pass"): LINEAR_TEXEL (default) interpolates within the hit texel between values at
   * its corners, each the mean of the texels of its triangle that touch the corner (exact for a
   * linear irradiance away from the triangle's edges, and it averages photon noise);
   * NEAREST_TEXEL reads the hit texel alone.
   */
  vtkSetClampMacro(SurfaceFilter, int, NEAREST_TEXEL, LINEAR_TEXEL);
  vtkGetMacro(SurfaceFilter, int);
  ///@}

  ///@{
  /**
   * Caustic atlas (Documentation/Physics.md "Caustic atlas"): where the lighting volume has the
   * photon pass's caustic irradiance (vtkRefractaLightingVolume::SurfaceCausticIrradianceName(),
   * light focused by glass, c x c finer than the atlas), an atlas texel where at least
   * CausticPhotonsPerFineTexel x c^2 caustic photons landed shows its caustic light from the fine
   * texels, the rest of its light from the atlas; other texels show the atlas alone, so broad,
   * dim refracted light keeps the atlas's lower noise. Default 64 photons per fine texel on
   * average (a fine texel's photon noise then about 1 / 8, less after the LINEAR_TEXEL filter
   * averages up to 6), chosen by measurement (Documentation/Benchmarks.md "Glass against ideal
   * optics").
   * 0 reads every caustic texel fine; a very large value never does.
   */
  void SetCausticPhotonsPerFineTexel(double value);
  vtkGetMacro(CausticPhotonsPerFineTexel, double);
  ///@}

  /**
   * After a Render() with a caustic atlas: the atlas texel sides (front and back count apart)
   * that showed their caustic light from their c x c fine texels (0 without a caustic atlas, or
   * where none had enough photons).
   */
  vtkIdType GetLastNumberOfFineCausticTexels() const;

  ///@{
  /**
   * Glass (dielectric surfaces, Documentation/Physics.md "Glass in the view pass"): at the first
   * DielectricSplitDepth interfaces of a path both the Fresnel-reflected and the refracted leg are
   * followed (weights R and 1 - R); deeper, only the likelier leg, with the path's whole weight.
   * 0 follows one leg everywhere; each level doubles the legs at most. Default 2, chosen by
   * measurement (the error table in Physics.md). Clamped to [0, 8].
   */
  vtkSetClampMacro(DielectricSplitDepth, int, 0, 8);
  vtkGetMacro(DielectricSplitDepth, int);
  ///@}

  ///@{
  /**
   * Glass edges (Documentation/Physics.md "Glass edges: supersampling"): a pixel whose footprint
   * holds an edge of glass (its four corner rays and its centre ray, straight from the eye, do not
   * all meet the same dielectric surface first, or one meets it at grazing incidence, |cos| below
   * DielectricGrazingCosine) is the mean of n x n paths through an n x n grid over its footprint
   * instead of its centre ray alone, n = DielectricSupersampling; other pixels keep one ray.
   * Without it the reflections and refractions at a ball's rim alias into speckle. 1 turns it off.
   * Default 3, chosen by measurement (Benchmarks.md, "The ball's rim"). Clamped to [1, 8].
   */
  vtkSetClampMacro(DielectricSupersampling, int, 1, 8);
  vtkGetMacro(DielectricSupersampling, int);
  ///@}

  ///@{
  /**
   * The grazing test of DielectricSupersampling: a ray meeting glass with |cos| of its angle of
   * incidence below this marks its pixel. Default 0.5 (a distant ball's outer 13% of radius: its
   * rim); 1 takes every pixel that sees glass, which also removes the aliasing of what is seen
   * through a ball at about twice the view pass's time of 0.5 (Physics.md "Glass edges:
   * supersampling"); 0 takes only silhouettes. Clamped to [0, 1].
   */
  void SetDielectricGrazingCosine(double value);
  vtkGetMacro(DielectricGrazingCosine, double);
  ///@}

  /**
   * Number of times surface geometry (BVH, triangles, atlas) was uploaded to the device.
   */
  int GetNumberOfSurfaceUploads();

  /**
   * Modification time, including the surface set's (its meshes, materials and matrices).
   */
  vtkMTimeType GetMTime() override;

  /**
   * Check and (when changed) upload the medium. Returns false after an error naming the problem.
   */
  bool SetMedium(vtkImageData* medium);

  /**
   * Check and (when changed) upload the lighting volume; nullptr means none (emission and
   * background only). Call after SetMedium(). Its field array SurfaceIrradianceName() (3
   * components, one tuple per texel of the surface set, finite and >= 0) lights the surfaces.
   * Its volume caustic (the field arrays vtkRefractaLightingVolume::VolumeCausticBricksName(),
   * VolumeCausticRadianceName() and VolumeCausticRadianceDirectionName(), all three or none)
   * adds the focused light's S1 from the fine voxels of every voxel with a brick.
   * `Radiance`, `RadianceDirection` and `MultipleScattering` are taken from their device copies
   * where the light passes kept them in this context (vtkOpenCLDeviceArrays; the render
   * pipeline's DeviceHandOff) and uploaded otherwise; the host arrays are still checked and scanned
   * for the empty-space skipping either way. S1's lobes are always uploaded, interleaved per
   * voxel (each lobe's S1, then its direction). Lobe arrays that are not complete pairs 0 .. K - 1
   * with K >= 2 are an error.
   * Returns false after an error.
   */
  bool SetLighting(vtkImageData* lighting);

  /**
   * How many of the lighting volume's arrays the last upload of one took from their device
   * copies instead of uploading them (0 to 4: Radiance, RadianceDirection, MultipleScattering
   * and MultipleScatteringDirection; with S1 in lobes 0 to 2).
   */
  vtkGetMacro(LastLightingArraysShared, int);

  /**
   * Subdivision c of the volume caustic of the lighting volume last set (1: none).
   */
  int GetLightingVolumeCausticSubdivision() const;

  /**
   * Whether the medium last set has emission and a grey extinction (the same in every channel,
   * as from any vtkVolumeProperty's scalar opacity), so that its extinction and emission are one
   * float4 per voxel on the device: one gather per step instead of two.
   */
  bool GetMediumIsPacked() const;

  /**
   * Render W x H pixels for `camera` (world coordinates). `propMatrix` (may be nullptr) maps the
   * medium's data coordinates to world (a vtkVolume's matrix). `depthLimit` (may be nullptr; W H
   * floats) caps each pixel's path length in the medium's world units (opaque geometry).
   * Fills `hdr` with W H RGBA floats (A = 1 - mean transmittance) and, when given,
   * `transmittance` with W H RGBA floats (the path's RGB transmittance, A = 0; 0 where a surface
   * is hit), `surfaceDepth` with W H floats: the path length from the ray's origin to the
   * surface it meets, in the units of `depthLimit` (grid-local, along the possibly curved path),
   * +infinity where it meets none, and `background` with W H RGBA floats: the part of `hdr`'s RGB
   * that is the background (BackgroundColor or EnvironmentMap) seen through the path, the sum
   * over its legs that escape of T L_bg(d_exit) (A = 0), which an exposure leaves alone (see
   * vtkRefractiveVolumeMapper). Returns false
   * after an error, or without a message when aborted (see SetAbortRender()).
   *
   * Progress and abort: the image is rendered in tiles of whole rows (see TilePixels)
   * (the same kernel with a global offset, so the image is identical to one launch); after each
   * tile Render() invokes vtkCommand::ProgressEvent on this object with the fraction of rows
   * done (a double, increasing to 1) and then, if AbortRender is set, stops and returns false
   * with GetLastRenderAborted() true and `hdr` untouched.
   */
  bool Render(vtkCamera* camera, int width, int height, vtkMatrix4x4* propMatrix,
    const float* depthLimit, std::vector<float>& hdr, std::vector<float>* transmittance = nullptr,
    std::vector<float>* surfaceDepth = nullptr, std::vector<float>* background = nullptr);

  ///@{
  /**
   * Facts about the last Render(): device seconds of the kernel (including the read-back), the
   * total number of steps marched, whether curved rays were used.
   */
  vtkGetMacro(LastSeconds, double);
  vtkGetMacro(LastTotalSteps, double);
  vtkGetMacro(LastCurved, bool);
  ///@}

  /**
   * The number of pixels of the last Render() taken as the mean of several paths
   * (DielectricSupersampling); 0 without glass or with DielectricSupersampling 1.
   */
  vtkGetMacro(LastNumberOfSupersampledPixels, vtkIdType);

  ///@{
  /**
   * Facts about empty space in the last Render(): whether the skipping kernel ran (it does when
   * EmptySpaceSkipping is on and at least one macro cell is empty), and the fraction of macro
   * cells rays must march through (1 when skipping is off).
   */
  vtkGetMacro(LastSkipping, bool);
  vtkGetMacro(LastActiveCellFraction, double);
  ///@}

  /**
   * Whether the last Render() ran the eight-lane kernel (LaneMarching).
   */
  vtkGetMacro(LastLaneMarching, bool);

  /**
   * Host seconds of the last build of the occupancy grid (done in Render() when the medium, the
   * lighting or MacroCellSize changed; not part of LastSeconds).
   */
  vtkGetMacro(OccupancySeconds, double);

  /**
   * Number of times a medium or lighting volume was uploaded to the device (for cache tests).
   */
  vtkGetMacro(NumberOfUploads, int);

  /**
   * Number of kernel launches (view passes) so far.
   */
  vtkGetMacro(NumberOfRenders, int);

  ///@{
  /**
   * Tiles of Render(): the first has TilePixels pixels (rounded down to whole rows, at least one;
   * default 65536); each later one is sized from the rate measured on the previous one to take
   * about TileSeconds (default 0.1 s; at most twice the previous tile's rows; 0: every tile has
   * TilePixels pixels). The image does not depend on them.
   */
  vtkSetClampMacro(TilePixels, int, 1, 1 << 30);
  vtkGetMacro(TilePixels, int);
  void SetTileSeconds(double value);
  vtkGetMacro(TileSeconds, double);
  ///@}

  ///@{
  /**
   * Abort request: when set, Render() stops after the current tile (see Render()). Set it from a
   * ProgressEvent observer; it stays set until cleared and does not modify the pass.
   */
  void SetAbortRender(bool abort) { this->AbortRender = abort; }
  bool GetAbortRender() const { return this->AbortRender; }
  ///@}

  ///@{
  /**
   * Whether the last Render() stopped on AbortRender, and the tiles it rendered.
   */
  vtkGetMacro(LastRenderAborted, bool);
  vtkGetMacro(LastNumberOfTiles, int);
  ///@}

  ///@{
  /**
   * Memory planning. Before it allocates an image's buffers, Render() plans them
   * (vtkOpenCLMemoryPlan): when the HDR buffer of the whole image (16 bytes a pixel) exceeds the
   * device's largest allocation, the image is rendered in buffer tiles of whole rows, each an
   * image of its own with the matching slice of the frustum (the pixels are the same);
   * GetLastNumberOfBufferTiles() counts them (1: one buffer). What still does not fit (a single
   * row, the device's global memory, the host's memory for the HDR image) fails before any
   * image buffer is allocated, with a message naming the size, the limit and the setting to lower
   * (the image size or the grid size). GetMemoryPlan() is the last plan;
   * GetPlannedDeviceMemoryBytes() its device total (one buffer tile plus the uploaded arrays).
   */
  vtkGetMacro(LastNumberOfBufferTiles, int);
  vtkGetMacro(PlannedDeviceMemoryBytes, double);
  vtkOpenCLMemoryPlan* GetMemoryPlan() { return this->MemoryPlan; }
  ///@}

  /**
   * Whether the current medium's refractive index varies (sources then count 1 / n^2 per step;
   * AUTO traces curved rays when its gradient is also non-zero somewhere, see GetLastCurved()).
   */
  bool GetMediumIsRefractive() const;

  ///@{
  /**
   * Why a camera and a prop matrix (nullptr: identity) cannot make view rays, as a sentence for
   * an error message; empty when they can. The camera needs a finite position, focal point and
   * view up, a view up off the direction of view, a view angle in (0, 180) degrees (perspective)
   * or a finite parallel scale > 0; the prop matrix must be finite, affine (last row 0 0 0 1)
   * and invertible. Render() and the render pipeline report these; GetPropMatrixProblem() is the
   * matrix's part alone (the light passes place the medium by it too).
   */
  static std::string GetRayFrameProblem(vtkCamera* camera, vtkMatrix4x4* propMatrix);
  static std::string GetPropMatrixProblem(vtkMatrix4x4* propMatrix);
  ///@}

#ifndef __VTK_WRAP__
  /**
   * A camera's rays in the grid-local frame of a medium, computed in double precision.
   * Perspective: origin Eye, direction normalize(W + sx U + sy V); parallel: origin
   * Eye + sx U + sy V, direction normalize(W); sx, sy in [-1, 1] over the image.
   */
  struct RayFrame
  {
    double Eye[3];
    double U[3];
    double V[3];
    double W[3];
    bool Parallel;
    double WorldToLocal[4][4]; // affine map from world points to grid-local points
  };
  // False when GetRayFrameProblem() is not empty, or without a medium or pixels.
  static bool ComputeRayFrame(vtkCamera* camera, vtkImageData* medium, vtkMatrix4x4* propMatrix,
    int width, int height, RayFrame& frame);
#endif

protected:
  vtkRefractaViewPass();
  ~vtkRefractaViewPass() override;

  double StepSize = 1.0;
  int RayMode = AUTO;
  double TransmittanceCutoff = 1e-4;
  int MaxSteps = 0;
  double BackgroundColor[3] = { 0.0, 0.0, 0.0 };
  double EnvironmentUp[3] = { 0.0, 1.0, 0.0 };
  double EnvironmentRight[3] = { 1.0, 0.0, 0.0 };
  bool EmptySpaceSkipping = true;
  int MacroCellSize = 8;
  bool LaneMarching = true;
  int SurfaceFilter = LINEAR_TEXEL;
  double CausticPhotonsPerFineTexel = 64;
  int DielectricSplitDepth = 2;
  int DielectricSupersampling = 3;
  double DielectricGrazingCosine = 0.5;
  bool LastSkipping = false;
  bool LastLaneMarching = false;
  double LastActiveCellFraction = 1.0;
  double OccupancySeconds = 0.0;
  double LastSeconds = 0.0;
  double LastTotalSteps = 0.0;
  bool LastCurved = false;
  vtkIdType LastNumberOfSupersampledPixels = 0;
  int NumberOfUploads = 0;
  int LastLightingArraysShared = 0;
  int NumberOfRenders = 0;
  int TilePixels = 65536;
  double TileSeconds = 0.1;
  bool AbortRender = false;
  bool LastRenderAborted = false;
  int LastNumberOfTiles = 0;
  int LastNumberOfBufferTiles = 0;
  double PlannedDeviceMemoryBytes = 0.0;
  vtkNew<vtkOpenCLMemoryPlan> MemoryPlan;

private:
  vtkRefractaViewPass(const vtkRefractaViewPass&) = delete;
  void operator=(const vtkRefractaViewPass&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;

  bool PlanImageMemory(
    vtkOpenCLContext* context, int width, int height, bool depth, int hostImages, int& bufferRows);
  // Checks and uploads the volume caustic's field arrays of `lighting` (`voxels` voxels); none is
  // not an error.
  bool SetVolumeCaustic(vtkImageData* lighting, vtkIdType voxels);
#ifndef __VTK_WRAP__
  // Runs `launch`'s kernel over rows [0, height) of a buffer tile, in tiles of whole work-groups.
  bool RunTiles(vtkOpenCLContext* context, const vtkRefractaViewLaunch& launch, int width,
    int height, int firstRow, int imageHeight, int& rowsPerTile);
#endif
};

#endif
