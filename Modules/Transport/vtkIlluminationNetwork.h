/**
 * @class   vtkIlluminationNetwork
 * @brief   Multiple scattering in a particle medium by illumination networks (papers/002).
 *
 * Input: a vtkPointSet of particles with the arrays of vtkRefractaParticleMedium (Radius and
 * Extinction required; Albedo, Anisotropy, Emission optional). Output: a vtkPolyData with the
 * particles (points, input point data, one vertex per particle) plus
 * vtkRefractaParticleMedium::DirectFluenceName(), DirectDirectionName() and MultipleFluenceName().
 * vtkParticleMediumDeposit turns that into a grid medium and lighting volume for the view pass.
 *
 * The method of Szirmay-Kalos, Sbert and Umenhoffer:
 * - D global sample directions (NumberOfDirections, default 128): a spherical Fibonacci set
 *   (evenly spread, so the quadrature error of one set is small) turned by a uniformly random
 *   rotation (seeded, Seed). Solve() iterates NumberOfRotations sets, each drawn afresh, and
 *   averages the particles' fluence over them, so the quadrature error of one set becomes noise
 *   that averages out instead of a fixed pattern.
 * - The visibility network V[p, i]: for each direction the particles are projected orthographically
 *   onto the plane perpendicular to it, binned into square pixels of side WindowPixelSize (a global
 *   line bundle; default sqrt(pi) times the mean radius, so a pixel has a particle's cross
 *   section) and sorted by depth along the direction; consecutive particles of a pixel see each
 *   other. This is the paper's depth peeling of M x M windows done as a sort (on the host, with
 *   vtkSMPTools over the directions; the paper's preprocessing step).
 * - Particle opacity alpha_p = 1 - exp(-sigma_t,p 4 r_p / 3) (the sphere's mean chord; the paper's
 *   diameter Delta s_p would overcount the volume of a sphere by 3/2).
 * - The E array: emission Le_p 4 r_p / 3 in every direction plus the reflection of the direct
 *   light, alpha_p a_p E_irr,p W_p[d_l, i] D / (4 pi), where E_irr,p is the light's irradiance at
 *   the particle attenuated by the particles in front of it (a line bundle from the light: an
 *   orthographic one for a directional light, a cube-map of pixels from a point light, inside or
 *   outside the cloud) and d_l the sample direction closest to the light's direction at p, as in
 *   the paper.
 * - The iteration I[p, i] = (1 - alpha_vp) I[vp, i] + E[vp, i] + a_vp alpha_vp sum_d I[vp, d]
 *   W_vp[d, i] with the Henyey-Greenstein phase matrix W (normalised per row, see
 *   Kernels/illumination_network.cl), SkyRadiance where no particle is seen; on the OpenCL device.
 * - Warm start: the network state I survives between updates. A change of the lights only
 *   recomputes E and continues the iteration from the previous solution (WarmStart, default on);
 *   ResetState() forgets it. A change of the particles or of D rebuilds everything.
 *
 * Each Update iterates until the largest change of I in one iteration, relative to the largest
 * I, is below Tolerance, or MaximumIterations. The power books of the last solution
 * (GetInjectedPower(), GetEscapedPower(), GetAbsorbedPower()) close at the fixed point:
 * injected = escaped + absorbed (Documentation/Physics.md derives it).
 *
 * Lights: one light, LightType POINT (LightPosition, LightIntensity in power per steradian),
 * DIRECTIONAL (LightDirection, the direction the light travels; LightIntensity is the irradiance
 * on a plane perpendicular to it) or NONE.
 */
#ifndef vtkIlluminationNetwork_h
#define vtkIlluminationNetwork_h

#include "RefractaTransportModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"
#include "vtkSmartPointer.h" // for the context

#include <memory> // for std::unique_ptr

class vtkOpenCLContext;

class REFRACTATRANSPORT_EXPORT vtkIlluminationNetwork : public vtkPolyDataAlgorithm
{
public:
  static vtkIlluminationNetwork* New();
  vtkTypeMacro(vtkIlluminationNetwork, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum LightTypes
  {
    NO_LIGHT = 0,
    POINT_LIGHT = 1,
    DIRECTIONAL_LIGHT = 2
  };

  ///@{
  /**
   * Number D of global sample directions, in [6, 1024]. Default 128.
   */
  vtkSetClampMacro(NumberOfDirections, int, 6, 1024);
  vtkGetMacro(NumberOfDirections, int);
  ///@}

  ///@{
  /**
   * Number of randomly rotated direction sets Solve() averages over, in [1, 1024]. Default 1.
   */
  vtkSetClampMacro(NumberOfRotations, int, 1, 1024);
  vtkGetMacro(NumberOfRotations, int);
  ///@}

  ///@{
  /**
   * Seed of the rotations. Default 1.
   */
  vtkSetMacro(Seed, unsigned int);
  vtkGetMacro(Seed, unsigned int);
  ///@}

  ///@{
  /**
   * Side of a line bundle's pixel, world units; 0 (default): sqrt(pi) times the mean radius.
   */
  void SetWindowPixelSize(double value);
  vtkGetMacro(WindowPixelSize, double);
  ///@}

  ///@{
  /**
   * Convergence: relative change of I per iteration below Tolerance (default 1e-4), checked every
   * CheckInterval iterations (default 4), at most MaximumIterations (default 2000) per rotation.
   * Tolerance 0 with MaximumIterations 1 is the paper's interactive mode: one iteration per frame
   * (update), warm-started, without a warning that it did not converge.
   */
  void SetTolerance(double value);
  vtkGetMacro(Tolerance, double);
  vtkSetClampMacro(CheckInterval, int, 1, 1024);
  vtkGetMacro(CheckInterval, int);
  vtkSetClampMacro(MaximumIterations, int, 1, 1 << 30);
  vtkGetMacro(MaximumIterations, int);
  ///@}

  ///@{
  /**
   * Continue from the previous solution when only the light changed. Default on.
   */
  vtkSetMacro(WarmStart, bool);
  vtkGetMacro(WarmStart, bool);
  vtkBooleanMacro(WarmStart, bool);
  ///@}

  ///@{
  /**
   * The light (see the class description). Defaults: POINT_LIGHT at the origin, intensity 1.
   */
  vtkSetClampMacro(LightType, int, NO_LIGHT, DIRECTIONAL_LIGHT);
  vtkGetMacro(LightType, int);
  void SetLightPosition(double x, double y, double z);
  void SetLightPosition(const double value[3]);
  vtkGetVector3Macro(LightPosition, double);
  void SetLightDirection(double x, double y, double z);
  void SetLightDirection(const double value[3]);
  vtkGetVector3Macro(LightDirection, double);
  void SetLightIntensity(double x, double y, double z);
  void SetLightIntensity(const double value[3]);
  vtkGetVector3Macro(LightIntensity, double);
  ///@}

  ///@{
  /**
   * Radiance entering the lines where no particle is seen (RGB). Default 0.
   */
  void SetSkyRadiance(double x, double y, double z);
  void SetSkyRadiance(const double value[3]);
  vtkGetVector3Macro(SkyRadiance, double);
  ///@}

  /**
   * The OpenCL context (default: vtkOpenCLContext::GetDefault()).
   */
  void SetContext(vtkOpenCLContext* context);
  vtkOpenCLContext* GetContext();

  /**
   * Forget the network state: the next update starts cold (I = 0).
   */
  void ResetState();

  ///@{
  /**
   * Results of the last update: iterations run (all rotations), the last relative change, whether
   * every rotation converged, the line-bundle pixel side used.
   */
  vtkGetMacro(Iterations, int);
  vtkGetMacro(Residual, double);
  vtkGetMacro(Converged, bool);
  vtkGetMacro(PixelSize, double);
  ///@}

  ///@{
  /**
   * Power books of the last rotation's solution, RGB (power units of LightIntensity times area):
   * injected into the network (E and sky), escaped at the ends of the lines, absorbed by the
   * particles. Injected = escaped + absorbed at convergence.
   */
  vtkGetVector3Macro(InjectedPower, double);
  vtkGetVector3Macro(EscapedPower, double);
  vtkGetVector3Macro(AbsorbedPower, double);
  ///@}

  /**
   * Device and host bytes a network of n particles and d directions needs (the four N x D RGB
   * arrays and V): the update refuses inputs whose network exceeds the device's limits.
   */
  static double NetworkBytes(long long n, int d);

protected:
  vtkIlluminationNetwork();
  ~vtkIlluminationNetwork() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int NumberOfDirections = 128;
  int NumberOfRotations = 1;
  unsigned int Seed = 1;
  double WindowPixelSize = 0.0;
  double Tolerance = 1e-4;
  int CheckInterval = 4;
  int MaximumIterations = 2000;
  bool WarmStart = true;
  int LightType = POINT_LIGHT;
  double LightPosition[3] = { 0, 0, 0 };
  double LightDirection[3] = { 0, 0, -1 };
  double LightIntensity[3] = { 1, 1, 1 };
  double SkyRadiance[3] = { 0, 0, 0 };

  int Iterations = 0;
  double Residual = -1.0;
  bool Converged = false;
  double PixelSize = 0.0;
  double InjectedPower[3] = { 0, 0, 0 };
  double EscapedPower[3] = { 0, 0, 0 };
  double AbsorbedPower[3] = { 0, 0, 0 };

private:
  vtkIlluminationNetwork(const vtkIlluminationNetwork&) = delete;
  void operator=(const vtkIlluminationNetwork&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;

  // Reads the particles and builds the networks when the input, D, the pixel or the seed changed;
  // recomputes E for the light; zeroes I unless warm-starting.
  bool PrepareNetwork(vtkPointSet* input);
  // Builds V, the phase matrices and their device copies for the current direction set.
  bool BuildDirectionSet();
  // Computes E for the light and the current directions and uploads it.
  bool UpdateEmitted();
  // Draws the next rotation; carries I over to it by nearest directions (a warm start).
  bool RotateDirections();
  // Iterates the network until Tolerance or MaximumIterations.
  bool Iterate();
  // Reads I back: accumulates the particles' fluence and computes the power books.
  bool Gather(std::vector<double>& multipleFluence);
  // Solves NumberOfRotations direction sets and writes the output.
  bool SolveRotations(vtkPolyData* output);
  vtkSmartPointer<vtkOpenCLContext> Context;
};

#endif
