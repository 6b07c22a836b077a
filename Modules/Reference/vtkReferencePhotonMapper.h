/**
 * @class   vtkReferencePhotonMapper
 * @brief   CPU, double-precision, consistent reference for light refracted before it scatters:
 *          stochastic progressive photon mapping in the participating medium.
 *
 * vtkReferenceRenderer (unbiased path tracing with light connections) cannot converge where light
 * bends before it scatters: a connection ray from a scattering vertex must reach a small light
 * through the curved index field, which it almost never does (a caustic behind a glass sphere, a
 * GRIN lens). This sibling estimator traces light the other way: photons leave the lights, follow
 * the same curved rays and scatter in the same medium, and view rays gather them. It takes every
 * setting of vtkReferenceRenderer (camera, lights and their extents, surfaces, background,
 * integrator tolerance and step, depth limits, seed, image size, jitter, exposure; SamplesPerPixel
 * is the number of view rays per pixel and pass, default 1 here) and traces through the same
 * RK5(4) integrator, medium, lights, surfaces and environment, so the two estimators converge to
 * the same image: use vtkReferenceRenderer where it converges (emission, clouds, dense media seen
 * under direct light) and this class where refracted light matters.
 *
 * **Estimator** (Documentation/Physics.md, "Reference photon mapping"): the probabilistic
 * formulation of progressive photon mapping of Knaus and Zwicker (2011) with the volumetric
 * point-point (3D kernel) density estimate of Jarosz, Nowrouzezahrai, Sadeghi and Jensen (2011).
 * Pass i (i = 1..Passes) is an independent estimate:
 * - PhotonsPerPass photons are emitted (an emitter chosen uniformly: directional discs and the
 *   illuminating background from a launch disc around the scene, light spheres from their
 *   surface with cosine-weighted directions) and traced by delta tracking; at every real
 *   collision in the medium the photon is stored with power / sigma_t there, then scatters on
 *   (albedo, HG, Russian roulette) or reflects diffusely at surfaces;
 * - every pixel traces SamplesPerPixel view rays: emission and the background as in the path
 *   tracer, next-event estimation and a diffuse bounce at surfaces, and in the medium the
 *   in-scattered source sigma_t(x) albedo(x) / (n(x)^2 V_i) * sum_p HG(w_p, -w_view) power_p /
 *   sigma_t(x_p) over the photons within radius r_i of x (V_i the volume of the part of that
 *   sphere inside the medium's box, where photons can be: 4/3 pi r_i^3 away from the faces),
 *   gathered at every tentative collision along the ray with ratio-tracking weights
 *   (GatherSpacing > 0, the default) or at the path's first real collision only (GatherSpacing
 *   0);
 * - the radius shrinks with the volumetric schedule r_{i+1}^3 = r_i^3 (i + Alpha) / (i + 1), so
 *   the variance of pass i grows like i^(1 - Alpha) while its bias (O(r_i^2)) vanishes; the image
 *   is the mean of the passes: its variance falls like Passes^-Alpha (error ~ Passes^(-Alpha/2))
 *   and its bias like Passes^(-2 (1 - Alpha) / 3).
 * The photons of a pass live in a hashed uniform grid (cells 2 r_i wide).
 *
 * **Error estimate**: passes are dealt round-robin to Streams independent streams (pass i to
 * stream i mod Streams); `StandardError` is the spread of the stream means over sqrt(Streams)
 * (the standard error of the image's Monte Carlo noise; the kernel bias, the same sign in every
 * stream, is not in it: it is measured against analytic cases and the path tracer in the tests).
 * Field data `CheckpointPasses`, `CheckpointSeconds` and `CheckpointError` give the estimate's
 * own convergence: at Streams x 2^k passes (k = 0, 1, ...) and at the end, the relative RMS
 * standard error over the pixels that see the medium (RMS of StandardError / mean of HDR).
 *
 * **Output**: as vtkReferenceRenderer (`HDR`, `StandardError`, `RGB`), field data
 * `SamplesPerPixel`, `Passes`, `PhotonsPerPass`, `Streams`, `Alpha`, `InitialRadius` and
 * `FinalRadius` (world units), `StoredPhotons` (over all passes), `RenderSeconds`, `Seed`,
 * `TruncatedPaths`, `NonFiniteSamples`, `LightRadius`, and the checkpoint arrays above.
 *
 * **Determinism**: photon p of pass i and the view rays of pixel q in pass i draw from their own
 * streams derived from (Seed, i, p or q); photons are stored and sorted in emission order, so an
 * image is bit-identical for a seed whatever the number of threads.
 *
 * **Bad input** (vtkErrorMacro and an empty output): Alpha outside [0.5, 1), Passes,
 * PhotonsPerPass or Streams < 1, InitialRadius <= 0, and everything vtkReferenceRenderer refuses.
 *
 * Limits: the kernel is not cut at interfaces inside the box where sigma_t jumps to 0 (a clear
 * region next to fog), a bias that vanishes with the radius like the rest (the box faces are
 * accounted for); light that reaches the camera from surfaces
 * is estimated by the path tracer's connections (surface caustics converge no faster than
 * there).
 */
#ifndef vtkReferencePhotonMapper_h
#define vtkReferencePhotonMapper_h

#include "RefractaReferenceModule.h" // for export macro
#include "vtkReferenceRenderer.h"

class REFRACTAREFERENCE_EXPORT vtkReferencePhotonMapper : public vtkReferenceRenderer
{
public:
  static vtkReferencePhotonMapper* New();
  vtkTypeMacro(vtkReferencePhotonMapper, vtkReferenceRenderer);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Number of passes (independent photon maps), >= 1. Default 64.
   */
  vtkSetMacro(Passes, int);
  vtkGetMacro(Passes, int);
  ///@}

  ///@{
  /**
   * Photons emitted per pass, >= 1. Default 100000.
   */
  vtkSetMacro(PhotonsPerPass, int);
  vtkGetMacro(PhotonsPerPass, int);
  ///@}

  ///@{
  /**
   * Radius of the first pass's gather sphere, in units of the medium's smallest voxel spacing,
   * > 0. Default 2.
   */
  vtkSetMacro(InitialRadius, double);
  vtkGetMacro(InitialRadius, double);
  ///@}

  ///@{
  /**
   * Radius reduction parameter of r_{i+1}^3 = r_i^3 (i + Alpha) / (i + 1), in [0.5, 1). Smaller
   * shrinks the radius faster (less bias, more noise). Default 2/3.
   */
  vtkSetMacro(Alpha, double);
  vtkGetMacro(Alpha, double);
  ///@}

  ///@{
  /**
   * Number of independent streams the passes are dealt to for the error estimate, >= 1
   * (at most Passes are used). Default 8.
   */
  vtkSetMacro(Streams, int);
  vtkGetMacro(Streams, int);
  ///@}

  ///@{
  /**
   * Where view rays gather photons, >= 0. 0: at the view path's first real collision in the
   * medium only (delta tracking; one gather per path). > 0: at every tentative collision along
   * the path, which come at least every GatherSpacing x the pass's radius on average where there
   * is extinction, each weighted by its probability of being real while the path goes on with
   * the rest (ratio tracking) to the next surface or the background: the in-scattered light is
   * summed along the whole view ray, the variance of where one collision falls is gone, and the
   * estimate stays consistent. Default 2 (Documentation/Benchmarks.md, "Ground truth for
   * refracted light", measures the choice).
   */
  vtkSetMacro(GatherSpacing, double);
  vtkGetMacro(GatherSpacing, double);
  ///@}

  /**
   * Radius of pass `pass` (1-based) for an initial radius r1 and Alpha: the schedule above.
   */
  static double PassRadius(double r1, double alpha, int pass);

protected:
  vtkReferencePhotonMapper();
  ~vtkReferencePhotonMapper() override;

  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  int Passes = 64;
  int PhotonsPerPass = 100000;
  double InitialRadius = 2.0;
  double Alpha = 2.0 / 3.0;
  int Streams = 8;
  double GatherSpacing = 2.0;

private:
  // False (after vtkErrorMacro naming the setting and its valid range) when a setting of the
  // estimator is out of range.
  bool CheckSettings();

  vtkReferencePhotonMapper(const vtkReferencePhotonMapper&) = delete;
  void operator=(const vtkReferencePhotonMapper&) = delete;
};

#endif
