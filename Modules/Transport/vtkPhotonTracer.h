/**
 * @class   vtkPhotonTracer
 * @brief   Light pass of Sun et al. 2008: photons from vtkLights marched along curved paths
 *          through a Refracta medium, depositing the in-scattered power into a radiance volume.
 *
 * Input port 0: a Refracta medium (vtkImageData, see vtkRefractaMedium; validated with
 * vtkMediumValidator). Lights: AddLight(), RemoveAllLights(), SetLights(); switched-off lights
 * are ignored (Documentation/Physics.md: directional irradiance E, point intensity I, spot
 * I cos^e inside the cone; colour x intensity). The host converts every light into the grid-local
 * frame in double precision, so an origin at 1e6 loses nothing.
 *
 * Output: a vtkImageData on the medium's grid with float point arrays
 * - `Radiance` (3): S1 = sigma_s * fluence of the unscattered (refracted, attenuated) beam, the
 *   power per unit volume scattered out of it (sigma_s is inside it);
 * - `RadianceDirection` (3): the power-weighted mean travel direction of the deposits, unit
 *   length (zero where nothing was deposited), in the grid-local frame;
 * - with two lights or more over an anisotropic medium, the same two fields per lobe of lights
 *   (MaximumRadianceLobes: vtkRefractaLightingVolume::RadianceLobeName(k),
 *   RadianceLobeDirectionName(k));
 * and field data: `NumberOfPhotons` (generated), `PhotonsMarched`, `PhotonsMissed` (generated but
 * carrying no power into the volume: missed the box or fell outside a spot's cone), `TotalSteps`,
 * `TotalVoxelPieces` (voxel crossings deposited), `TerminatedEscaped`, `TerminatedRoulette`,
 * `TerminatedStepCap`, `TerminatedInvalid` (non-finite state; expected 0), and RGB energies
 * `EnergyEmitted`, `EnergyAbsorbed`, `EnergyEscaped`, `EnergyScattered`, `EnergyRemaining`,
 * `EnergyRouletteKilled`, `EnergyRouletteGained`. The books close exactly (up to float and
 * fixed-point rounding): Emitted = Absorbed + Escaped + Scattered + Remaining, where Remaining =
 * power carried at the step cap + RouletteKilled - RouletteGained (the last two are equal in
 * expectation: Russian roulette is unbiased).
 *
 * Surfaces (SetSurfaces(), a vtkRefractaSurfaceSet; default none): opaque two-sided Lambertian
 * triangles anywhere in the scene, inside, around or outside the medium's box. Lights then emit
 * towards the union of the medium's (proxy) box and the surfaces' bounds; photons fly in straight
 * lines outside the box and curved inside it, and every step or flight is tested against the
 * surfaces' BVH. A photon that meets a surface adds its power to the irradiance of the hit
 * texel's side it arrived on, loses (1 - albedo) of it to the surface and is reflected diffusely
 * on that side (cosine-weighted, Russian roulette on the albedo) or ends there; reflected photons
 * go on depositing in-scattered power in the medium. Output: the field-data array
 * vtkRefractaLightingVolume::SurfaceIrradianceName() (6 components, one tuple per texel of the
 * set's atlas: irradiance, power per unit area, RGB on the front then on the back),
 * `EnergySurface` (RGB, absorbed by surfaces), `SurfaceHits` and `TerminatedSurface` (photons
 * that ended on a surface). With surfaces the books read Emitted = Absorbed + Surface + Escaped +
 * Scattered + Remaining. The set's device arrays (BVH, triangles, texel albedo) are uploaded once
 * per build of the set and kept between runs, like the medium's; moving a surface rebuilds the set
 * and re-runs this pass, never the medium's octree (see GetLastRunReusedSurfaces()).
 * Dielectric surfaces (vtkRefractaSurfaceMaterial::DIELECTRIC) are exact interfaces: a photon is
 * reflected with the Fresnel probability or refracted by Snell's law, keeping its power, and
 * deposits nothing; `EnergyInterfaceReflected` and `EnergyInterfaceTransmitted` (RGB) book the
 * power of every such event (their sum is the power that met interfaces),
 * `InterfaceReflections` and `InterfaceTransmissions` count them (Documentation/Physics.md,
 * "Dielectric interfaces").
 *
 * Environment light (BackgroundIlluminates, default off): the background (EnvironmentMap, an
 * equirectangular vtkImageData oriented by EnvironmentUp / EnvironmentRight as
 * vtkRefractaEnvironmentMap documents, or else the uniform BackgroundColor) emits photons too, as
 * Szirmay-Kalos et al. light their media with the sky. Directions are importance-sampled by
 * luminance x solid angle (a 2D CDF over the texels; the uniform sky is one texel covering the
 * sphere), the map taken as constant over each texel; each photon starts on a disc of radius R
 * perpendicular to its direction that covers the sphere (centre, radius R) around the emission box,
 * so a photon carries L(w) pi R^2 / (N pdf(w)) and the irradiance of the sky on any surface in
 * the box comes out right (uniform sky L: pi L on each side of an unoccluded plane). The map is in
 * the surfaces' world (MediumToWorld applied), like the view pass's background. The environment
 * shares NumberOfPhotons with the lights in proportion to its power towards the box, and its
 * photons are booked in EnergyEmitted like the lights' (vtkPhotonTracerEnvironment.cxx,
 * Kernels/photon_environment.cl).
 *
 * Work, in stages (each timed, see Get*Seconds()):
 * 1. Octree (only when n varies and AdaptiveStepping is on): the dense level array built on the
 *    device from a min/max pyramid of n, with PrimaryTolerance eps (unlimited step inside a node)
 *    and SecondaryTolerance eps' (step capped at SecondaryStepLimit voxels), any grid size.
 * 2. Generation: NumberOfPhotons shared among the lights in proportion to their power towards
 *    the volume; low-discrepancy (R2) samples over each light's footprint on the medium's box, or
 *    on the tighter proxy box around the voxels that differ from empty space (UseProxyBounds).
 * 3. Marching: step = clamp(octree step, MinimumStep, MaximumStep) (or FixedStep), midpoint
 *    update of x' = v/n, v' = grad n with |dv| <= MaximumTurn * n and |v| renormalised to n,
 *    halved where grad n changes fast over the step (StepTolerance);
 *    every step's chord is walked voxel by voxel, attenuating with sigma_t sampled in each voxel
 *    piece and depositing sigma_s's share of the loss there.
 * 4. Smoothing (optional): the paper's 3x3x3 filter with a mirror boundary: total-conserving,
 *    and a uniform field stays uniform up to the faces, edges and corners; neighbours that an
 *    opaque surface separates exchange nothing.
 * Only the work the medium needs is compiled in: straight rays (no gradient or octree lookups;
 * a RefractiveIndexGradient array is then ignored) when n is constant or its gradient, given or
 * computed, is zero everywhere (a medium voxelized with exact interfaces: paths bend only at the
 * surfaces, Documentation/Physics.md "Straight between interfaces"), no piece walk when nothing
 * attenuates, no deposits when nothing scatters (see GetUsedCurvedRays() etc.).
 *
 * Lengths of the step knobs are in voxels (multiples of the smallest spacing). Results are
 * deterministic for a Seed on a given device (64-bit fixed-point accumulation).
 *
 * Progress and abort: ProgressEvent goes up monotonically from 0 to 1 with weights from the
 * measured cost of the stages (octree up to 0.01, generation 0.02, marching 0.02 to 0.99 in
 * proportion to the photons finished, resolve and smoothing to 1). The march runs in batches of
 * photons (PhotonBatchSize; automatic: sized to about 0.05 s each from the measured rate; with
 * StepsPerChunk, one progress report per chunk) and AbortExecute is checked after every stage and
 * every batch or chunk. An abort is not an error: RequestData returns 1 with an empty output,
 * releases the device buffers, reports no warning and sets GetLastRunAborted(); after
 * AbortExecuteOff() the next Update() runs from the start. The batch size does not change the
 * result (fixed-point deposits, per-photon random streams).
 */
#ifndef vtkPhotonTracer_h
#define vtkPhotonTracer_h

#include "RefractaTransportModule.h" // for export macro
#include "vtkImageAlgorithm.h"
#include "vtkRefractaLightingVolume.h" // for MAXIMUM_RADIANCE_LOBES
#include "vtkSmartPointer.h" // for members

#ifndef __VTK_WRAP__
#include "vtkOpenCLHandle.h" // for cl_mem in the chunk callback
#include <functional>        // for the chunk callback
#include <memory>            // for std::unique_ptr
#include <vector>            // for the environment's radiance table
#endif

class vtkFloatArray;
class vtkImageData;
class vtkLight;
class vtkLightCollection;
class vtkMatrix4x4;
class vtkOpenCLContext;
class vtkRefractaGridCuts;
class vtkRefractaSurfaceSet;
namespace vtkPhotonTracerDetail
{
struct ScratchPool;
struct PhotonStreams;
}

class REFRACTATRANSPORT_EXPORT vtkPhotonTracer : public vtkImageAlgorithm
{
public:
  static vtkPhotonTracer* New();
  vtkTypeMacro(vtkPhotonTracer, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The lights (world coordinates). SetLights() replaces the collection (nullptr: none).
   */
  void AddLight(vtkLight* light);
  void RemoveAllLights();
  void SetLights(vtkLightCollection* lights);
  vtkLightCollection* GetLights();
  ///@}

  ///@{
  /**
   * Opaque surfaces lit by the photons (see the class description). nullptr (default) or an
   * empty set: none. The set is built (vtkRefractaSurfaceSet::Build) when this pass runs.
   */
  void SetSurfaces(vtkRefractaSurfaceSet* surfaces);
  vtkRefractaSurfaceSet* GetSurfaces();
  ///@}

  ///@{
  /**
   * Placement of the medium in the surfaces' world: the matrix from the medium's data frame (the
   * frame of its vtkImageData and of the lights given here) to the world coordinates of the
   * surfaces, a vtkProp3D's matrix; it must be rigid (rotation and translation). nullptr
   * (default): the identity.
   */
  void SetMediumToWorld(vtkMatrix4x4* matrix);
  vtkMatrix4x4* GetMediumToWorld();
  ///@}

  ///@{
  /**
   * Environment light (see the class description). BackgroundIlluminates (default off) makes the
   * background emit photons: EnvironmentMap when set (an equirectangular vtkImageData, W x H x 1,
   * 3 or 4 component point scalars; unsigned char divided by 255, other types linear radiance in
   * W / (m^2 sr) per channel), else the uniform BackgroundColor (linear RGB radiance, default
   * black: no light). EnvironmentUp / EnvironmentRight (world vectors, defaults (0, 1, 0) and
   * (1, 0, 0)) orient the map as vtkRefractaEnvironmentMap documents. Negative or non-finite
   * radiance is an error.
   */
  vtkSetMacro(BackgroundIlluminates, bool);
  vtkGetMacro(BackgroundIlluminates, bool);
  vtkBooleanMacro(BackgroundIlluminates, bool);
  void SetBackgroundColor(double x, double y, double z);
  void SetBackgroundColor(const double value[3]);
  vtkGetVector3Macro(BackgroundColor, double);
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
   * Analog scattering with surfaces (default off). Without it the pass is deterministic
   * attenuation: a photon deposits the scattered part of its power (S1, `Radiance`) and flies on
   * with the unscattered part, and the light scattered at least once is left to the
   * Lattice-Boltzmann solver, which knows no surfaces: light the medium scatters towards a surface
   * never lights it. With AnalogScattering on (it takes effect only with surfaces and a medium
   * that scatters; GetUsedAnalogScattering() says whether it did), a photon still deposits the
   * expected scattered power of every voxel piece, but then really scatters there with the
   * piece's share of scattered power (a Henyey-Greenstein direction from the medium's
   * `Anisotropy`, at an exponentially distributed point), so scattered light reaches, lights and
   * is reflected by the surfaces. Deposits of photons that have neither scattered nor been
   * reflected by a surface since their light go to `Radiance` (S1) as before; those of photons
   * that have (diffuse light: its one mean direction per voxel would not describe it) go to a
   * point array vtkRefractaLightingVolume::MultipleScatteringName() (S_ms, power per unit
   * volume, smoothed like Radiance), which then replaces the lattice's, with its flux over its
   * fluence in MultipleScatteringDirectionName() (the deposits' directions weighted by their
   * power, smoothed alike; length <= 1; with ScatteringOrders' split that of the orders up to
   * k), about which the view pass shades S_ms. The books stay exact per
   * photon: Emitted = Absorbed + Surface + Escaped + Remaining, with EnergyScattered 0 (nothing
   * is handed on to a lattice). See Documentation/Physics.md, "Surfaces and multiple scattering".
   */
  vtkSetMacro(AnalogScattering, bool);
  vtkGetMacro(AnalogScattering, bool);
  vtkBooleanMacro(AnalogScattering, bool);
  vtkGetMacro(UsedAnalogScattering, bool);
  ///@}

  ///@{
  /**
   * Leave the direct light on the surfaces out of `SurfaceIrradiance` (default off): a photon
   * that meets a Lambertian surface before any other surface, any glass and any scattering
   * deposits nothing there (it is reflected and goes on as before, and the books do not change),
   * so that a caller adds that part without noise from straight light rays
   * (vtkLightRaySingleScattering::ComputeSurfaceIrradiance; vtkRefractaRenderPipeline does).
   * It takes effect only where those rays give the same light: photons that fly straight (no
   * refraction in the medium), delta lights only (no environment light, which light rays do not
   * carry, and LightRadius and DirectionalLightAngularRadius 0: a fixed quadrature would band their
   * penumbrae), and Lambertian triangles to light; GetLastSkippedDirectSurfaceLight() says whether
   * the last run left it out.
   */
  vtkSetMacro(SkipDirectSurfaceLight, bool);
  vtkGetMacro(SkipDirectSurfaceLight, bool);
  vtkBooleanMacro(SkipDirectSurfaceLight, bool);
  vtkGetMacro(LastSkippedDirectSurfaceLight, bool);
  ///@}

  ///@{
  /**
   * First-collision split (issue 14; default 0: off). With k = ScatteringOrders > 0 and a medium
   * that scatters, the photons carry the first k scattering orders themselves, with the analog
   * scattering described above (also without surfaces), and hand the rest to the
   * Lattice-Boltzmann solver: a photon that has scattered k times deposits as usual, and what it
   * scatters (the power that becomes light scattered k + 1 times) goes to the point arrays
   * vtkRefractaLightingVolume::MultipleScatteringSourceName() (power per unit volume, smoothed
   * like Radiance) and MultipleScatteringSourceDirectionName() (its mean travel direction),
   * booked as EnergyScattered; the photon flies on with the unscattered part only. The output's
   * MultipleScattering then holds the orders the photons carried (light scattered 1 .. k times,
   * scattered again), and vtkLatticeBoltzmannLighting and vtkPhotonDiffusionSchedule solve the
   * lattice from the handed-on source and add its S_ms. The lattice's ray effects (its six or
   * eighteen directions) come from concentrated sources; after k scatterings the source is spread
   * out, so they fade (Documentation/Physics.md, "Ray effects of the grid multiple scattering").
   * EVERY_ORDER (-1): the photons carry every order (analog scattering also without surfaces)
   * and hand nothing on: MultipleScattering is complete and no lattice is needed. With surfaces
   * and AnalogScattering on, the photons carry every order whatever this says.
   * GetUsedScatteringOrders() says what the last run did: 0 (nothing scatters, or no split), k,
   * or EVERY_ORDER.
   */
  enum
  {
    EVERY_ORDER = -1
  };
  vtkSetClampMacro(ScatteringOrders, int, EVERY_ORDER, 1000);
  vtkGetMacro(ScatteringOrders, int);
  vtkGetMacro(UsedScatteringOrders, int);
  ///@}

  /**
   * Whether the last run emitted photons from the environment, and their share of the photons.
   */
  vtkGetMacro(UsedEnvironment, bool);
  vtkGetMacro(EnvironmentPhotons, int);

  ///@{
  /**
   * OpenCL context; nullptr (default) means vtkOpenCLContext::GetDefault().
   */
  void SetContext(vtkOpenCLContext* context);
  vtkOpenCLContext* GetContext();
  ///@}

  ///@{
  /**
   * Number of photons generated over all lights. Default 65536.
   */
  vtkSetClampMacro(NumberOfPhotons, int, 1, 1 << 28);
  vtkGetMacro(NumberOfPhotons, int);
  ///@}

  ///@{
  /**
   * Seed of the random streams (Russian roulette) and of the sample rotations. Default 1.
   */
  vtkSetMacro(Seed, unsigned int);
  vtkGetMacro(Seed, unsigned int);
  ///@}

  ///@{
  /**
   * Octree tolerances on the refractive index range within a node (section 4.2 and 5.3):
   * primary eps (default 0.005): unlimited step inside the node; secondary eps' (default 0.02):
   * step capped at SecondaryStepLimit voxels (default 8). eps' <= eps disables the secondary.
   */
  void SetPrimaryTolerance(double value);
  vtkGetMacro(PrimaryTolerance, double);
  void SetSecondaryTolerance(double value);
  vtkGetMacro(SecondaryTolerance, double);
  void SetSecondaryStepLimit(double value);
  vtkGetMacro(SecondaryStepLimit, double);
  ///@}

  ///@{
  /**
   * Adaptive step bounds in voxels: MinimumStep (default 1), MaximumStep (default 64).
   */
  void SetMinimumStep(double value);
  vtkGetMacro(MinimumStep, double);
  void SetMaximumStep(double value);
  vtkGetMacro(MaximumStep, double);
  ///@}

  ///@{
  /**
   * AdaptiveStepping on (default): octree steps; off: every step is FixedStep voxels
   * (default 1). Irrelevant when n is constant (rays go straight to the exit in one step).
   */
  vtkSetMacro(AdaptiveStepping, bool);
  vtkGetMacro(AdaptiveStepping, bool);
  vtkBooleanMacro(AdaptiveStepping, bool);
  void SetFixedStep(double value);
  vtkGetMacro(FixedStep, double);
  ///@}

  ///@{
  /**
   * Largest optical depth (max over RGB of sigma_t at the step's start x length) of one curved
   * step; 0 (default) is off. Attenuation is integrated voxel by voxel whatever the step, so
   * this only shortens steps; see the README for whether it helps.
   */
  void SetExtinctionStepLimit(double value);
  vtkGetMacro(ExtinctionStepLimit, double);
  ///@}

  ///@{
  /**
   * Russian roulette threshold as a fraction of a photon's initial power (largest channel):
   * below it a photon survives with probability power / threshold and is boosted to the
   * threshold. Default 0.001; 0 disables roulette.
   */
  void SetRouletteThreshold(double value);
  vtkGetMacro(RouletteThreshold, double);
  ///@}

  ///@{
  /**
   * Step cap per photon (default 10000): a photon still marching then stops, its power is
   * counted in EnergyRemaining and TerminatedStepCap. Never a hang.
   */
  vtkSetClampMacro(MaximumNumberOfSteps, int, 1, 100000000);
  vtkGetMacro(MaximumNumberOfSteps, int);
  ///@}

  ///@{
  /**
   * Dielectric interface events per photon (default 64): a photon meeting more ends there, its
   * power counted in EnergyRemaining and TerminatedStepCap. Light scattered inside a glass body
   * past the critical angle circles by total internal reflection (exactly so in a sphere) and
   * would otherwise run to MaximumNumberOfSteps; a photon crossing ordinary glass meets a few.
   * Inside a dielectric surface with an inside medium (a glass body, see
   * vtkRefractaSurfaceMaterial::UseInsideMedium) photons attenuate and scatter with that medium,
   * not the grid's, so clear glass in fog no longer scatters (Physics.md "Glass bodies").
   */
  vtkSetClampMacro(MaximumNumberOfInterfaceEvents, int, 1, 100000000);
  vtkGetMacro(MaximumNumberOfInterfaceEvents, int);
  ///@}

  ///@{
  /**
   * Caustic atlas subdivision c (default 4, chosen by measurement: Documentation/Benchmarks.md
   * "Glass against ideal optics"; 1 turns it off; at most 16). A photon
   * whose path since the light or its last diffuse event (Lambertian bounce, volume scattering)
   * met a dielectric interface (an LS+D path, a caustic photon) deposits on a Lambertian
   * triangle also into a finer atlas, every texel of the surface set's atlas cut again c x c,
   * and is counted in its atlas texel (Documentation/Physics.md "Caustic atlas"); the output then
   * holds the field-data arrays vtkRefractaLightingVolume::SurfaceCausticIrradianceName() and
   * SurfaceCausticPhotonsName() beside SurfaceIrradianceName(), which keeps the whole flux (the
   * fine array resolves its caustic part; the view pass reads it where enough photons landed).
   * Scenes without dielectric surfaces have no caustic photons: nothing is allocated and the
   * output is unchanged. Memory (both sides of every texel): 48 c^2 + 16 bytes per atlas texel
   * on the device while tracing, 24 c^2 + 16 in the output; c is lowered for a run until the
   * fine texels fit in MaximumNumberOfCausticTexels (GetLastCausticSubdivision()).
   */
  vtkSetClampMacro(CausticSubdivision, int, 1, 16);
  vtkGetMacro(CausticSubdivision, int);
  ///@}

  ///@{
  /**
   * Most fine texels of the caustic atlas (default 2^22: 200 MB on the device while tracing).
   * A run whose atlas has T texels uses the largest c' <= CausticSubdivision with T c'^2 within
   * it (no caustic atlas if that is 1).
   */
  vtkSetClampMacro(MaximumNumberOfCausticTexels, vtkIdType, 1, VTK_ID_MAX);
  vtkGetMacro(MaximumNumberOfCausticTexels, vtkIdType);
  ///@}

  /**
   * The caustic atlas's subdivision in the last run (1: none; see CausticSubdivision).
   */
  vtkGetMacro(LastCausticSubdivision, int);

  ///@{
  /**
   * Volume caustic subdivision c (default 4; 1 turns it off; at most 8). Light that dielectric
   * interfaces focus into the medium (the shaft behind a glass lens, narrowing to its focus) is
   * finer than the voxels. Where enough caustic photons (refracted or reflected by an interface
   * since their light, not scattered since) cross a voxel, the voxel gets a brick of c^3 fine
   * voxels, and those photons' S1 deposits there go into the brick's fine voxels, each the share
   * of the piece's length inside it, instead of into the voxel (Documentation/Physics.md
   * "Volume caustics"). The output then holds the field-data arrays
   * vtkRefractaLightingVolume::VolumeCausticBricksName(), VolumeCausticRadianceName() and
   * VolumeCausticRadianceDirectionName(); `Radiance` holds the rest, so the two add up to the
   * light of a run without bricks. Which voxels get bricks is decided by a pilot march of one
   * photon in 8 (about 12% more marching): a voxel that an estimated
   * VolumeCausticPiecesPerFineVoxel x c^3 caustic pieces cross. A lattice solve takes the
   * bricks' light back into their voxels (vtkRefractaLightingVolume::ReadLatticeSource()). Used
   * only in an unchunked march (StepsPerChunk 0: the interleaved lattice reads the accumulators
   * while photons fly) with dielectric surfaces in a scattering medium; otherwise nothing is
   * allocated and the output is unchanged (GetLastVolumeCausticSubdivision() 1).
   * Memory: 64 bytes per fine voxel on the device while tracing (and 64 per voxel for the pilot),
   * 24 in the output.
   */
  vtkSetClampMacro(VolumeCausticSubdivision, int, 1, 8);
  vtkGetMacro(VolumeCausticSubdivision, int);
  ///@}

  ///@{
  /**
   * The most lobes S1 is kept in (default 2, 1 to vtkRefractaLightingVolume::
   * MAXIMUM_RADIANCE_LOBES; 1: `Radiance` alone), as vtkLightRaySingleScattering's
   * MaximumRadianceLobes: with two lights or more over a medium that scatters with g != 0, the S1
   * of each group of lights (lobe k: light k while there are no more lights than lobes, the sky
   * counting as a light, else the lights grouped by direction) also goes to its own accumulators,
   * resolved into RadianceLobeName(k) and RadianceLobeDirectionName(k), so that the view pass
   * shades each about its own direction. The volume caustic's bricks keep one direction. Cost: 48
   * bytes per voxel and lobe on the device while tracing (a photon deposits into its lobe's
   * accumulators, summed into Radiance's after the march), 24 in the output.
   * GetLastNumberOfLobes(): the last run's (1: none).
   */
  vtkSetClampMacro(MaximumRadianceLobes, int, 1, vtkRefractaLightingVolume::MAXIMUM_RADIANCE_LOBES);
  vtkGetMacro(MaximumRadianceLobes, int);
  vtkGetMacro(LastNumberOfLobes, int);
  ///@}

  ///@{
  /**
   * Most fine voxels of the volume caustic's bricks (default 2^20: 64 MiB on the device while
   * tracing). A run uses the largest c' <= VolumeCausticSubdivision whose bricks fit (no volume
   * caustic if none does).
   */
  vtkSetClampMacro(MaximumNumberOfVolumeCausticVoxels, vtkIdType, 1, VTK_ID_MAX);
  vtkGetMacro(MaximumNumberOfVolumeCausticVoxels, vtkIdType);
  ///@}

  ///@{
  /**
   * Caustic voxel pieces a fine voxel must expect for its voxel to get a brick (default 4, chosen by
   * measurement: Documentation/Benchmarks.md "The light shaft below the ball"; a
   * voxel needs VolumeCausticPiecesPerFineVoxel x c^3 from the pilot's estimate). Lower values
   * put bricks where fewer caustic photons pass and make their fine voxels noisier.
   */
  void SetVolumeCausticPiecesPerFineVoxel(double value);
  vtkGetMacro(VolumeCausticPiecesPerFineVoxel, double);
  ///@}

  ///@{
  /**
   * The volume caustic of the last run: its subdivision (1: none) and its number of bricks.
   */
  vtkGetMacro(LastVolumeCausticSubdivision, int);
  vtkGetMacro(LastNumberOfVolumeCausticBricks, vtkIdType);
  ///@}

  ///@{
  /**
   * Largest change of v = n dx/ds in one step, as a fraction of n (default 0.5): a steep index
   * step turns a ray over a few steps instead of throwing it out of the grid.
   */
  void SetMaximumTurn(double value);
  vtkGetMacro(MaximumTurn, double);
  ///@}

  ///@{
  /**
   * Local error tolerance of a curved step, a fraction of n (default 0.02; 0 turns the control
   * off). After each midpoint update, the change of grad n over the step (h times the largest
   * change between its start, middle and end) and the drift of |v| from n are compared with
   * StepTolerance * n; while either is larger the step is halved, at most 6 times (to 1/64 of the
   * octree or fixed step, so below MinimumStep). Both vanish where grad n is uniform, so steps
   * shrink only at steep index changes; there the control keeps light beyond the critical angle
   * from leaking through an interface (Documentation/Physics.md, "Step control").
   */
  void SetStepTolerance(double value);
  vtkGetMacro(StepTolerance, double);
  ///@}

  ///@{
  /**
   * Final 3x3x3 smoothing of Radiance and RadianceDirection (and of MultipleScattering and the
   * split's lattice source: every deposit field), default on: the binomial (1, 2, 1) / 4 per axis
   * of Sun et al. 2008, total-conserving. Two voxels whose centres an opaque (Lambertian)
   * triangle of the surface set separates exchange nothing, so light does not seep through a
   * wall (PhotonSurfaces.SmoothingDoesNotCrossAnOpaqueWall: the first slab behind a wall in fog
   * fell from 1678 to 1e-3, float rounding of the last step).
   */
  vtkSetMacro(Smoothing, bool);
  vtkGetMacro(Smoothing, bool);
  vtkBooleanMacro(Smoothing, bool);
  ///@}

  ///@{
  /**
   * Largest relative change the smoothing may make to deposits that fall off as exp(-sigma_t x)
   * (light entering an optically thick medium; default 0.01). Each pair of neighbours along an
   * axis exchanges a share g / 4 of their difference, with g = min(1, 2 SmoothingBias /
   * (cosh(tau) - 1)) and tau = h sigma_t across one voxel (the larger sigma_t of the two, largest
   * channel): the full filter where a voxel is optically thin (tau <= 0.2 at the default), fading
   * out where it is thick, where the plain filter moves light from a dense surface's first voxels
   * into the thinner ones outside, which the camera sees unattenuated (the dense cube of the
   * accuracy benchmark: 6% too bright). Conservation and a uniform field's uniformity hold for any
   * value; 1e30 (the maximum) gives the plain filter everywhere. Physics.md, "Smoothing of the
   * photon deposits".
   */
  void SetSmoothingBias(double value);
  vtkGetMacro(SmoothingBias, double);
  ///@}

  ///@{
  /**
   * Extent of the lights (default 0: delta lights). LightRadius (world units) makes point and
   * spot lights spheres of that radius whose radiance towards w is I(w) / (pi r^2): the same
   * radiant intensity, emitted from the sphere's projected disc. DirectionalLightAngularRadius
   * (degrees, < 45) makes directional lights discs at infinity of that angular radius, with the
   * same irradiance on a plane facing them. These are vtkReferenceRenderer's extended lights, so
   * both renderers see the same lights (soft shadows, caustics blurred by the source's size).
   */
  void SetLightRadius(double value);
  vtkGetMacro(LightRadius, double);
  void SetDirectionalLightAngularRadius(double value);
  vtkGetMacro(DirectionalLightAngularRadius, double);
  ///@}

  ///@{
  /**
   * Start photons on the bounds of the voxels that differ from empty space (n != 1 or
   * sigma_t > 0), grown by two voxels, instead of the whole medium box (default on).
   */
  vtkSetMacro(UseProxyBounds, bool);
  vtkGetMacro(UseProxyBounds, bool);
  vtkBooleanMacro(UseProxyBounds, bool);
  ///@}

  ///@{
  /**
   * Wall-clock seconds of the last run's stages (device work included), and the device memory
   * the last run allocated at its peak (bytes).
   */
  vtkGetMacro(OctreeSeconds, double);
  vtkGetMacro(GenerationSeconds, double);
  vtkGetMacro(MarchingSeconds, double);
  vtkGetMacro(SmoothingSeconds, double);
  vtkGetMacro(PeakDeviceMemoryBytes, double);
  ///@}

  ///@{
  /**
   * Memory planning: before it allocates anything, a run estimates its device buffers (index,
   * gradient, octree, coefficients, photon state, accumulators, smoothing) and host copies from
   * the grid size and NumberOfPhotons and checks them against the context's limits
   * (vtkOpenCLMemoryPlan). What does not fit fails the run at once with a message naming the
   * buffer, the limit and the setting to lower (NumberOfPhotons or the grid size).
   * GetPlannedDeviceMemoryBytes() / GetPlannedHostMemoryBytes() are the last plan's totals
   * (bytes); GetPeakDeviceMemoryBytes() is what the run then allocated.
   */
  vtkGetMacro(PlannedDeviceMemoryBytes, double);
  vtkGetMacro(PlannedHostMemoryBytes, double);
  ///@}

  ///@{
  /**
   * The plan of the last run: curved rays (n varies with a non-zero gradient), attenuation,
   * deposits (something scatters), voxels cut at their node planes (sigma_t bends steeply at some
   * node, a dense body's face: the walk's pieces then integrate the trilinear sigma_t; Physics.md,
   * "Dense surfaces"), octree built, gradient computed on the device.
   */
  vtkGetMacro(UsedCurvedRays, bool);
  vtkGetMacro(UsedExtinction, bool);
  vtkGetMacro(UsedDeposit, bool);
  vtkGetMacro(UsedNodePlaneCuts, bool);
  vtkGetMacro(UsedOctree, bool);
  vtkGetMacro(ComputedGradient, bool);
  ///@}

  ///@{
  /**
   * Chunked marching (for the interleaved photon/diffusion schedule, see
   * vtkLatticeBoltzmannLighting's README section): with StepsPerChunk k > 0 every photon
   * advances at most k steps per launch (curved rays: marcher steps; straight rays: one voxel
   * edge per step) and the ChunkCallback runs after each launch has been enqueued, before the
   * next one, with the deposit accumulators so far. Default 0: each photon is marched to its end
   * in one launch. The result is the same either way (same steps, same deposits, same books).
   */
  vtkSetClampMacro(StepsPerChunk, int, 0, 1 << 24);
  vtkGetMacro(StepsPerChunk, int);
  ///@}

  /**
   * Launches of the last chunked march (0 when not chunked).
   */
  vtkGetMacro(NumberOfChunks, int);

  ///@{
  /**
   * Photons per batch of the unchunked march (rounded up to whole work-groups of 64): the march
   * stops between batches to report progress and look at AbortExecute. 0 (default): automatic,
   * each batch sized from the rate measured so far to take about 0.05 s (1024 photons at least,
   * at most twice the previous batch). The result does not depend on it. GetNumberOfBatches():
   * batches of the last run.
   */
  vtkSetClampMacro(PhotonBatchSize, int, 0, 1 << 28);
  vtkGetMacro(PhotonBatchSize, int);
  vtkGetMacro(NumberOfBatches, int);
  ///@}

  /**
   * Whether the last RequestData stopped because AbortExecute was set (its output is empty).
   */
  vtkGetMacro(LastRunAborted, bool);

  /**
   * Whether the last run reused the medium of the run before (its host copy and its device
   * buffers: refractive index, gradient, octree, extinction, albedo) instead of reading and
   * uploading it again and rebuilding the octree. It does when the input is the same object with
   * the same MTime, on the same context, with the same octree settings (PrimaryTolerance,
   * SecondaryTolerance, AdaptiveStepping, UseProxyBounds): a light change then re-runs the
   * photon generation and marching only. An aborted or failed run drops the kept medium.
   */
  vtkGetMacro(LastRunReusedMedium, bool);

  ///@{
  /**
   * March each light's photons in an order in which neighbouring photons start close together
   * (default on): the generation's lattice points sorted by their cell in a grid over the light's
   * footprint (Morton order, about four points per cell). Which points are traced and each one's
   * random stream stay the same, and deposits are integer sums, so the output is the same to the
   * bit either way; what changes is that a photon finds the voxels its neighbour just touched
   * still in the cache (on the 2-core CPU the adaptive march of 2^16 photons at 128^3 ran 1.5x as
   * many voxel pieces per second; Benchmarks.md). The sky's photons keep their order.
   */
  vtkSetMacro(CoherentPhotonOrder, bool);
  vtkGetMacro(CoherentPhotonOrder, bool);
  vtkBooleanMacro(CoherentPhotonOrder, bool);
  ///@}

  ///@{
  /**
   * Keep the run's scratch device buffers (the deposit accumulators, the photons' state, the
   * resolve's and the smoothing's work arrays: about 120 bytes per voxel plus 64 per photon) for
   * the next run of the same sizes, which then borrows them instead of creating them. Off by
   * default: a run leaves only its medium on the device. vtkRefractaRenderPipeline turns it on
   * for its persistent tracer, where every light move re-runs the tracer: on a CPU device each
   * fresh buffer's first fill faults all its pages in (a light move at 128^3 filled 240 MiB of
   * fresh buffers in 0.83 s, the kept ones in about 0.04 s; Benchmarks.md). Turning it off, or
   * ReleaseScratchBuffers(), frees them.
   */
  virtual void SetReuseScratchBuffers(bool reuse);
  vtkGetMacro(ReuseScratchBuffers, bool);
  vtkBooleanMacro(ReuseScratchBuffers, bool);
  void ReleaseScratchBuffers();
  ///@}

  ///@{
  /**
   * Keep each output point array's device buffer (the resolved and smoothed `Radiance`,
   * `RadianceDirection` and, with the first-collision split or analog scattering,
   * `MultipleScattering` and the lattice's source) as that array's device copy in the context's
   * vtkOpenCLDeviceArrays, so that the lattice and the view pass take them from the device instead
   * of uploading the arrays again (a light move at 128^3 sent 120 MiB back; Benchmarks.md). Off
   * by default: the copies hold device memory (12 bytes per voxel and array) for as long as the
   * output arrays live. vtkRefractaRenderPipeline turns it on (its DeviceHandOff).
   */
  vtkSetMacro(KeepDeviceCopies, bool);
  vtkGetMacro(KeepDeviceCopies, bool);
  vtkBooleanMacro(KeepDeviceCopies, bool);
  ///@}

  /**
   * Whether the last run had surfaces, and whether it reused the device copy of the surface set
   * (same set, not rebuilt since, same context) instead of uploading it.
   */
  vtkGetMacro(UsedSurfaces, bool);
  vtkGetMacro(LastRunReusedSurfaces, bool);

#ifndef __VTK_WRAP__
  /**
   * Called after each chunk (on the context's queue, nothing waited for): the fixed-point
   * deposits (six cl_long per voxel: the Radiance accumulator's RGB, then the direction sums'
   * xyz), the factors that turn them into S1 (power per unit volume) and direction sums, and the
   * number of photons still marching after this chunk (0 on the last call). Return false to abort
   * the run (an error).
   */
  using ChunkCallback = std::function<bool(
    cl_mem deposits, double radianceFactor, double directionFactor, int activePhotons)>;
  void SetChunkCallback(ChunkCallback callback)
  {
    this->Callback = std::move(callback);
  }
#endif

  /**
   * Build only the octree of `medium` into `octree` (same grid; unsigned char point arrays
   * `OctreeLevel`, the leaf level, and `OctreeStepLimited`, 1 where the secondary tolerance
   * applies). For inspection and tests. Returns false after reporting an error.
   */
  bool BuildOctree(vtkImageData* medium, vtkImageData* octree);

protected:
  vtkPhotonTracer();
  ~vtkPhotonTracer() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  vtkMTimeType GetMTime() override;

  vtkSmartPointer<vtkLightCollection> Lights;
  vtkSmartPointer<vtkOpenCLContext> Context;
  vtkSmartPointer<vtkRefractaSurfaceSet> Surfaces;
  vtkSmartPointer<vtkMatrix4x4> MediumToWorld;
  vtkSmartPointer<vtkImageData> EnvironmentMap;
  bool BackgroundIlluminates = false;
  double BackgroundColor[3] = { 0.0, 0.0, 0.0 };
  double EnvironmentUp[3] = { 0.0, 1.0, 0.0 };
  double EnvironmentRight[3] = { 1.0, 0.0, 0.0 };
  bool UsedEnvironment = false;
  int EnvironmentPhotons = 0;
  int NumberOfPhotons = 65536;
  unsigned int Seed = 1;
  double PrimaryTolerance = 0.005;
  double SecondaryTolerance = 0.02;
  double SecondaryStepLimit = 8.0;
  double MinimumStep = 1.0;
  double MaximumStep = 64.0;
  bool AdaptiveStepping = true;
  double FixedStep = 1.0;
  double ExtinctionStepLimit = 0.0;
  double RouletteThreshold = 0.001;
  int MaximumNumberOfSteps = 10000;
  int MaximumNumberOfInterfaceEvents = 64;
  int CausticSubdivision = 4;
  vtkIdType MaximumNumberOfCausticTexels = vtkIdType(1) << 22;
  int LastCausticSubdivision = 1;
  int MaximumRadianceLobes = 2;
  int LastNumberOfLobes = 1;
  int VolumeCausticSubdivision = 4;
  vtkIdType MaximumNumberOfVolumeCausticVoxels = vtkIdType(1) << 20;
  double VolumeCausticPiecesPerFineVoxel = 4.0;
  int LastVolumeCausticSubdivision = 1;
  vtkIdType LastNumberOfVolumeCausticBricks = 0;
  double MaximumTurn = 0.5;
  double StepTolerance = 0.02;
  bool Smoothing = true;
  double SmoothingBias = 0.01;
  bool UseProxyBounds = true;
  double LightRadius = 0.0;
  double DirectionalLightAngularRadius = 0.0;
  int StepsPerChunk = 0;
  int NumberOfChunks = 0;
  int PhotonBatchSize = 0;
  int NumberOfBatches = 0;
  bool LastRunAborted = false;
  bool LastRunReusedMedium = false;
  bool UsedSurfaces = false;
  bool LastRunReusedSurfaces = false;
  bool AnalogScattering = false;
  bool UsedAnalogScattering = false;
  bool SkipDirectSurfaceLight = false;
  bool LastSkippedDirectSurfaceLight = false;
  int ScatteringOrders = 0;
  int UsedScatteringOrders = 0;
#ifndef __VTK_WRAP__
  ChunkCallback Callback;
#endif

  double OctreeSeconds = 0;
  double GenerationSeconds = 0;
  double MarchingSeconds = 0;
  double SmoothingSeconds = 0;
  double PeakDeviceMemoryBytes = 0;
  double PlannedDeviceMemoryBytes = 0;
  double PlannedHostMemoryBytes = 0;
  bool UsedCurvedRays = false;
  bool UsedExtinction = false;
  bool UsedNodePlaneCuts = false;
  bool UsedDeposit = false;
  bool UsedOctree = false;
  bool ComputedGradient = false;

private:
  vtkPhotonTracer(const vtkPhotonTracer&) = delete;
  void operator=(const vtkPhotonTracer&) = delete;
  struct Internals;
  struct MediumCache;
  std::unique_ptr<MediumCache> Cache; // the medium kept from the last successful run
  struct SurfaceCache;
  std::unique_ptr<SurfaceCache> KeptSurfaces; // the surfaces' device arrays of the last run
  std::unique_ptr<vtkPhotonTracerDetail::ScratchPool> Scratch; // ReuseScratchBuffers
  std::unique_ptr<vtkPhotonTracerDetail::PhotonStreams> Streams; // the last run's photon order
  vtkSmartPointer<vtkRefractaGridCuts> Cuts; // where opaque surfaces cut the grid, kept
  bool ReuseScratchBuffers = false;
  bool KeepDeviceCopies = false;
  bool CoherentPhotonOrder = true;
  // The surface stage (vtkPhotonTracerSurfaces.cxx): build the set and the emission box; upload
  // (or take the kept) device arrays and the irradiance accumulator; set the kernels' surface
  // arguments from `index` on (advanced past them); read back the irradiance; keep the arrays
  // for the next run.
  bool PrepareSurfaces(Internals& run);
  // this->Cuts from the opaque triangles, placed by `localToWorld` (grid-local -> world); kept
  // while the set's build, the grid and the placement stay (a light move reuses them).
  void FindGridCuts(Internals& run, vtkMatrix4x4* localToWorld);
  bool UploadSurfaces(Internals& run);
  bool UploadGridCuts(
    Internals& run); // vtkRefractaGridCuts' bytes (a one-byte stand-in without cuts)
#ifndef __VTK_WRAP__
  bool SetSurfaceArguments(Internals& run, cl_kernel kernel, cl_uint& index);
#endif
  bool ResolveSurfaces(Internals& run);
  // Analog scattering (vtkPhotonTracerAnalog.cxx): the anisotropy and S_ms accumulator buffers
  // (placeholders when off), and S_ms (and the split's lattice source) resolved into run.Multiple
  // (run.LatticeSource, run.LatticeSourceDirection).
  bool UploadAnalogScattering(Internals& run);
  bool ResolveMultipleScattering(Internals& run);
#ifndef __VTK_WRAP__
  // Fixed-point deposits (3 per voxel from `offset` longs into `fixed`, voxel v's at offset +
  // stride v) into power per unit volume in `values` (near opaque surfaces per unit of the owned
  // volume, vtkRefractaGridCuts::GetVolumeScales, as every field), smoothed with Smoothing; with
  // `directions`, the direction sums (from `directionOffset` into `directionFixed`, the same
  // stride) smoothed the same way into unit mean directions, or with `unit` false into sums per
  // photon scale (each voxel's sum over its values' channel sum times the voxel's volume is then
  // the mean direction weighted by power, its length the flux over the fluence).
  bool ResolveDeposits(Internals& run, cl_mem fixed, size_t offset, cl_mem directionFixed,
    size_t directionOffset, size_t stride, vtkFloatArray* values, vtkFloatArray* directions,
    bool unit = true, bool keep = true);
  // The smoothing's three axis passes (radiance_smooth_axis) from `a` into `b` (`a` is scratch).
  bool SmoothAxes(Internals& run, cl_kernel filter, cl_mem a, cl_mem b);
#endif
  void WriteSurfaceOutput(Internals& run, vtkImageData* output);
  // The volume caustic (vtkPhotonTracerVolumeCaustic.cxx): whether this run builds one; its
  // kernel arguments from index `first` (subdivision 0: none, 16-byte buffers; 1: the pilot);
  // the pilot march that places the bricks (the accumulators are cleared after it); the fine
  // deposits resolved; the output.
  bool UsesVolumeCaustic(Internals& run);
#ifndef __VTK_WRAP__
  bool SetVolumeCausticArguments(
    Internals& run, cl_kernel kernel, cl_uint first, int subdivision);
  // `march(first, count)` launches the march kernel `kernel` over photons [first, first + count).
  bool PlaceVolumeCausticBricks(Internals& run,
    const std::function<bool(size_t, size_t)>& march, cl_kernel kernel, cl_uint first);
#endif
  bool ResolveVolumeCaustic(Internals& run);
  void WriteVolumeCausticOutput(Internals& run, vtkImageData* output);
  void PrintVolumeCaustic(ostream& os, vtkIndent indent);
  void KeepSurfaces(Internals& run);
  // The environment light (vtkPhotonTracerEnvironment.cxx): its radiance table, CDFs and emission
  // sphere (appended to run.Lights as one more source), and the generation launch for its photons.
  bool SetUpEnvironment(Internals& run);
  bool ReadEnvironmentRadiance(std::vector<double>& rgb, int size[2]);
  bool GenerateEnvironmentPhotons(
    Internals& run, size_t light, unsigned int offset, unsigned int r1, unsigned int r2);
  void PrintEnvironment(ostream& os, vtkIndent indent);
  bool TakeCachedMedium(Internals& run);
  void KeepMedium(Internals& run);
  // Reports max(progress, the last value reported) and returns false when AbortExecute is set.
  bool ReportProgress(Internals& run, double progress);
  // The stages of RequestData, in order; each returns false after reporting an error.
  bool SetUpLights(Internals& run);
  // Groups the lights into S1's lobes (MaximumRadianceLobes): run.Lobes and run.LightLobes.
  void AssignLobes(Internals& run);
  // With lobes: the deposits' first block (all of S1) as the sum of the lobes' blocks.
  bool SumLobeDeposits(Internals& run);
  void SharePhotons(Internals& run);
  bool InitializeDevice(Internals& run);
  bool PlanMemory(Internals& run);
  bool BuildOctreeStage(Internals& run);
  bool GeneratePhotons(Internals& run);
  bool MarchPhotons(Internals& run);
  bool ResolveRadiance(Internals& run);
  void WriteOutput(Internals& run, vtkImageData* output);
};

#endif
