/**
 * @class   vtkLatticeBoltzmannLighting
 * @brief   Multiple scattering by Lattice-Boltzmann lighting in blocks (Bernabei et al. III-C).
 *
 * Inputs: port 0 the medium (a Refracta medium, see vtkRefractaMedium; `Extinction`, `Albedo`,
 * `Anisotropy` are used, missing ones take their defaults; `Occupancy` is not used: the
 * coefficients are already the voxel's effective ones). Port 1 the lighting volume on the same
 * grid, as the photon pass produces it (Documentation/Physics.md): `Radiance` (RGB, required),
 * S1 = sigma_s phi1, the power per unit volume scattered out of the direct beam, and
 * `RadianceDirection` (3, optional), its mean travel direction.
 *
 * S1 is the source of the diffuse field: it is injected into the lattice as scattered light
 * (isotropically, or by the Henyey-Greenstein phase function around `RadianceDirection`, see
 * SourceDistribution) and vtkLatticeBoltzmannSolver iterates the lattice to its steady state, the
 * diffuse field of light scattered at least once.
 *
 * With the first-collision split (vtkPhotonTracer::ScatteringOrders k) the source is instead the
 * light the photons handed on after k scatterings (`MultipleScatteringSource` and its direction,
 * in the lighting volume or in the photon orders of port 2, SetPhotonOrdersConnection()), and the
 * photons' own `MultipleScattering` (orders up to k) is added to the lattice's.
 *
 * Output: the grid of the lighting volume with `Radiance` and `RadianceDirection` passed through
 * (single scattering), the new `MultipleScattering` (RGB) S_ms = sigma_s phi_ms, the power per
 * unit volume scattered out of the diffuse field (second and higher orders), its
 * `MultipleScatteringDirection` (3: the flux of that light over its fluence, from the lattice's
 * distributions, vtkLatticeBoltzmannSolver::ComputeMultipleScatteringDirection, merged with the
 * photons' orders' with the split; the photons' own where they carried every order), about which
 * the view pass shades S_ms, the lighting volume's field data, and the field data
 * `LatticeBoltzmannIterations` (int), `LatticeBoltzmannResidual` (double, relative change per
 * step at the last check) and `LatticeBoltzmannConverged` (int, 0 or 1).
 *
 * Knobs (all forwarded to vtkLatticeBoltzmannSolver): Lattice (6 or 18, default 6), BlockSize
 * (voxels, default 4; 0 = unblocked), StepsPerExchange (default 4), Boundary (default vacuum),
 * SourceDistribution (default phase function), CollisionModel (default diffusion matched),
 * Tolerance (default 1e-4), CheckInterval (steps, default 8), ProbeSpacing (voxels, default 8),
 * MaximumIterations (default 5000).
 *
 * Bad input (an invalid medium, a missing or mismatched lighting volume, a `Radiance` that is
 * negative or not finite) is reported with vtkErrorMacro and leaves the output empty.
 *
 * Progress and abort: ProgressEvent rises monotonically to 1; the solve covers 0.02 to 0.98 with
 * vtkLatticeBoltzmannSolver::Solve()'s estimate (iterations done or the log-scale way from the
 * first residual to Tolerance, whichever is further), reported every CheckInterval steps.
 * AbortExecute is looked at when RequestData starts (set while the pass upstream ran) and after
 * every progress report, i.e. between check intervals: the run
 * then stops, leaves the output empty, releases the device buffers, reports no error (RequestData
 * returns 1) and sets GetLastRunAborted(); after AbortExecuteOff() the next Update() solves from
 * the start.
 */
#ifndef vtkLatticeBoltzmannLighting_h
#define vtkLatticeBoltzmannLighting_h

#include "RefractaTransportModule.h" // for export macro
#include "vtkImageAlgorithm.h"
#include "vtkSmartPointer.h" // for the context

class vtkFloatArray;
class vtkImageData;
class vtkLatticeBoltzmannSolver;
class vtkOpenCLContext;

class REFRACTATRANSPORT_EXPORT vtkLatticeBoltzmannLighting : public vtkImageAlgorithm
{
public:
  static vtkLatticeBoltzmannLighting* New();
  vtkTypeMacro(vtkLatticeBoltzmannLighting, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Connect the lighting volume (port 1).
   */
  void SetLightingConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }
  void SetLightingData(vtkDataObject* data) { this->SetInputData(1, data); }

  /**
   * Connect the photon orders (port 2, optional): the output of a vtkPhotonTracer run with
   * ScatteringOrders != 0 on the same medium, when single scattering (port 1) comes from another
   * pass (vtkLightRaySingleScattering). Its `MultipleScatteringSource` (and direction) is then the
   * lattice's source and its `MultipleScattering` is added to the lattice's; without a source
   * (the photons carried every order) its `MultipleScattering` is the output's and no lattice
   * runs. Without port 2 the lighting volume itself may carry those arrays (a tracer with
   * ScatteringOrders on port 1).
   */
  void SetPhotonOrdersConnection(vtkAlgorithmOutput* output)
  {
    this->SetInputConnection(2, output);
  }

  ///@{
  /**
   * See vtkLatticeBoltzmannSolver.
   */
  vtkSetClampMacro(Lattice, int, 6, 18);
  vtkGetMacro(Lattice, int);
  vtkSetClampMacro(BlockSize, int, 0, 8);
  vtkGetMacro(BlockSize, int);
  vtkSetClampMacro(StepsPerExchange, int, 1, 64);
  vtkGetMacro(StepsPerExchange, int);
  vtkSetClampMacro(Boundary, int, 0, 1);
  vtkGetMacro(Boundary, int);
  vtkSetClampMacro(SourceDistribution, int, 0, 1);
  vtkGetMacro(SourceDistribution, int);
  vtkSetClampMacro(CollisionModel, int, 0, 1);
  vtkGetMacro(CollisionModel, int);
  void SetTolerance(double value);
  vtkGetMacro(Tolerance, double);
  vtkSetClampMacro(CheckInterval, int, 1, 4096);
  vtkGetMacro(CheckInterval, int);
  vtkSetClampMacro(ProbeSpacing, int, 1, 4096);
  vtkGetMacro(ProbeSpacing, int);
  vtkSetClampMacro(MaximumIterations, int, 0, 1 << 30);
  vtkGetMacro(MaximumIterations, int);
  vtkSetMacro(KeepDeviceCopies, bool);
  vtkGetMacro(KeepDeviceCopies, bool);
  vtkBooleanMacro(KeepDeviceCopies, bool);
  ///@}

  /**
   * OpenCL context (default vtkOpenCLContext::GetDefault()).
   */
  void SetContext(vtkOpenCLContext* context);

  /**
   * Whether the last RequestData stopped because AbortExecute was set (its output is empty).
   */
  vtkGetMacro(LastRunAborted, bool);

protected:
  vtkLatticeBoltzmannLighting();
  ~vtkLatticeBoltzmannLighting() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  // Solves the lattice on `medium` from the source of `sources` (vtkRefractaLightingVolume::
  // LatticeSourceName) into `ms`, plus `addend` (the split's photon S_ms) when given: 1 done,
  // 0 aborted, -1 failed (reported).
  int Solve(vtkLatticeBoltzmannSolver* solver, vtkImageData* medium, vtkImageData* sources,
    vtkFloatArray* ms, vtkDataArray* addend);

  int Lattice = 6;
  int BlockSize = 4;
  int StepsPerExchange = 4;
  int Boundary = 0;
  int SourceDistribution = 1;
  int CollisionModel = 1;
  double Tolerance = 1e-4;
  int CheckInterval = 8;
  int ProbeSpacing = 8;
  int MaximumIterations = 5000;
  bool KeepDeviceCopies = false;
  bool LastRunAborted = false;
  vtkSmartPointer<vtkOpenCLContext> Context;

private:
  vtkLatticeBoltzmannLighting(const vtkLatticeBoltzmannLighting&) = delete;
  void operator=(const vtkLatticeBoltzmannLighting&) = delete;
};

#endif
