/**
 * @class   vtkRefractaLightingVolume
 * @brief   The conventions of a Refracta lighting volume: array names, component counts, units.
 *
 * A lighting volume is a vtkImageData on the medium's grid (vtkRefractaGridFrame::SameGrid)
 * whose point data carries what the light passes computed; the view pass reads it.
 *
 * - `Radiance` (3 components): S1 = sigma_s phi1, power per unit volume scattered out of the
 *   unscattered beam (RGB, >= 0; vtkPhotonTracer).
 * - `RadianceDirection` (3): mean travel direction of that light, unit vector in the grid-local
 *   frame (zero where none).
 * - `MultipleScattering` (3): S_ms = sigma_s phi_ms, power per unit volume scattered out of the
 *   diffuse field (RGB, >= 0; vtkLatticeBoltzmannLighting, or the photons' analog scattering).
 * - `MultipleScatteringSource` (3, first-collision split only, vtkPhotonTracer::ScatteringOrders
 *   k): power per unit volume scattered by light scattered k times, the lattice's source.
 * - `MultipleScatteringSourceDirection` (3): mean travel direction of that light (unit, or zero).
 * - `MultipleScatteringDirection` (3): the mean travel direction of the multiply scattered light
 *   weighted by its power, i.e. its net flux over its fluence, F / phi_ms (length f in [0, 1]:
 *   0 isotropic, 1 collimated; zero where none), from the photons' deposits (every order, or the
 *   split's orders up to k) and from the lattice's distributions (the two merged by power with
 *   the split). The view pass shades S_ms with the phase function of anisotropy g f about it
 *   (light spread as a Henyey-Greenstein lobe of mean cosine f); without it, isotropic.
 *
 * - `RadianceLobe<k>` and `RadianceLobeDirection<k>` (3 each, k = 0 .. K - 1, K >= 2, optional;
 *   RadianceLobeName(k)): the same two fields for the lights of lobe k alone
 *   (vtkPhotonTracer and vtkLightRaySingleScattering::MaximumRadianceLobes); the lobes' S1 sum
 *   to `Radiance`. Where they are present the view pass shades each lobe with the phase function
 *   about its own direction, so that lights from different sides are not shaded along their
 *   mean; every other reader takes `Radiance` and `RadianceDirection` as before.
 *
 * The lattice's source is `Radiance` (S1), or `MultipleScatteringSource` where the photon pass
 * carried the first k orders itself (LatticeSourceName()); then the lattice's S_ms is added to
 * the photons' `MultipleScattering` (orders up to k).
 *
 * Surfaces (vtkRefractaSurfaceSet) are lit in the same passes. Their irradiance is not a point
 * array but a field-data array of the lighting volume, SurfaceIrradianceName(): a vtkFloatArray
 * with 6 components and one tuple per texel of the surface set's atlas (in the set's texel order),
 * the irradiance E on each side of the texel in power per unit area: RGB on the front (the side
 * the triangle's winding normal points to), then RGB on the back (>= 0; the flux that arrived on
 * that side divided by the texel's area). A side sees only its own light: a lamp inside a closed
 * box lights the inner faces, not the outer ones. Readers also take 3 components (one irradiance
 * for both sides, as a hand-made lighting volume may have; GetSurfaceSideValue()). Every stage
 * that copies a lighting volume passes it through.
 *
 * Only static methods are used; New() exists so that it can be wrapped and printed.
 */
#ifndef vtkRefractaLightingVolume_h
#define vtkRefractaLightingVolume_h

#include "RefractaCoreModule.h" // for export macro
#include "vtkObject.h"

#include <vector> // for ReadLatticeSource

class vtkDataArray;
class vtkDataSet;
class vtkImageData;
class vtkFloatArray;

class REFRACTACORE_EXPORT vtkRefractaLightingVolume : public vtkObject
{
public:
  static vtkRefractaLightingVolume* New();
  vtkTypeMacro(vtkRefractaLightingVolume, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Identifiers of the lighting-volume arrays, in the order of the table above.
   */
  enum ArrayId
  {
    RADIANCE = 0,
    RADIANCE_DIRECTION,
    MULTIPLE_SCATTERING,
    MULTIPLE_SCATTERING_SOURCE,
    MULTIPLE_SCATTERING_SOURCE_DIRECTION,
    MULTIPLE_SCATTERING_DIRECTION,
    NUMBER_OF_ARRAYS
  };

  ///@{
  /**
   * Array names as they appear in the point data.
   */
  static const char* RadianceName() { return "Radiance"; }
  static const char* RadianceDirectionName() { return "RadianceDirection"; }
  static const char* MultipleScatteringName() { return "MultipleScattering"; }
  static const char* MultipleScatteringSourceName() { return "MultipleScatteringSource"; }
  static const char* MultipleScatteringSourceDirectionName()
  {
    return "MultipleScatteringSourceDirection";
  }
  static const char* MultipleScatteringDirectionName() { return "MultipleScatteringDirection"; }
  ///@}

  /**
   * The most lobes S1 is kept in (see the class description).
   */
  enum
  {
    MAXIMUM_RADIANCE_LOBES = 4
  };

  ///@{
  /**
   * Names of lobe k's S1 and mean direction ("RadianceLobe0", "RadianceLobeDirection0", ...);
   * nullptr for k outside [0, MAXIMUM_RADIANCE_LOBES).
   */
  static const char* RadianceLobeName(int k);
  static const char* RadianceLobeDirectionName(int k);
  ///@}

  /**
   * The number of lobes `lighting` carries: K when it has both arrays of lobes 0 .. K - 1 and
   * K >= 2, else 0 (a single lobe is `Radiance` itself). The arrays' shapes are not checked.
   */
  static int GetNumberOfRadianceLobes(vtkDataSet* lighting);

  /**
   * Adds the single-scattering arrays of `from` (Radiance, RadianceDirection and the lobes, those
   * present) to the point data of `to`, sharing them: what a stage that computes S_ms on top of
   * S1 passes on.
   */
  static void PassSingleScattering(vtkDataSet* from, vtkDataSet* to);

  ///@{
  /**
   * The arrays of `lighting` a Lattice-Boltzmann solve takes as its source and source direction:
   * MultipleScatteringSource(Direction) where the photon pass handed the orders above k on (the
   * first-collision split), else Radiance(Direction). HasPhotonMultipleScattering() says whether
   * `lighting` already holds the photons' own S_ms (orders 1..k) that the lattice's is added to.
   */
  static const char* LatticeSourceName(vtkDataSet* lighting);
  static const char* LatticeSourceDirectionName(vtkDataSet* lighting);
  static bool HasPhotonMultipleScattering(vtkDataSet* lighting);
  ///@}

  /**
   * The lattice's source and source direction of `lighting` as floats (3 per voxel; zeros where
   * an array is missing): LatticeSourceName() and LatticeSourceDirectionName(), with, where the
   * source is Radiance and `lighting` has a volume caustic, each brick's mean S1 added back into
   * its voxel (and its light's direction into the voxel's power-weighted mean direction): the
   * lattice scatters all of S1 on, whatever resolution holds it.
   */
#ifndef __VTK_WRAP__
  static void ReadLatticeSource(
    vtkImageData* lighting, std::vector<float>& source, std::vector<float>& direction);
#endif

  /**
   * Adds the photons' `MultipleScattering` of `lighting` (when it has one with the shape of `ms`)
   * to `ms`, a lattice's S_ms of the same grid: the split's two parts of S_ms made one.
   */
  static void AddPhotonMultipleScattering(vtkDataSet* lighting, vtkFloatArray* ms);

  /**
   * Whether ReadLatticeSource() folds a volume caustic's bricks into the source: the source is
   * Radiance (no first-collision split) and `lighting` has a volume caustic of subdivision >= 2.
   * Otherwise the lattice's source is the point arrays as they are.
   */
  static bool LatticeSourceHasVolumeCaustic(vtkDataSet* lighting);

  /**
   * to += addend, value by value, when both have the same number of components and tuples (the
   * sum of the split's two parts of S_ms, in float as the lattice's device adds them).
   */
  static void AddValues(vtkDataArray* addend, vtkFloatArray* to);

  /**
   * Name of the field-data array with the surfaces' irradiance (see the class description).
   */
  static const char* SurfaceIrradianceName() { return "SurfaceIrradiance"; }

  /**
   * The two sides of a surface texel, in the order of the per-side arrays' components: FRONT_SIDE
   * faces where the triangle's winding normal points (counter-clockwise corners seen from there),
   * BACK_SIDE the other way. Light arriving along direction d meets the front when d . n < 0.
   */
  enum SurfaceSide
  {
    FRONT_SIDE = 0,
    BACK_SIDE = 1,
    NUMBER_OF_SURFACE_SIDES = 2
  };

  /**
   * Component `component` (< perSide) of `tuple` on `side` of a per-side surface array
   * (SurfaceIrradianceName() and its caustic arrays): the array holds perSide components per side,
   * the front's first (2 perSide in all), or perSide for one value shared by both sides. 0 for any
   * other shape or a tuple out of range.
   */
  static double GetSurfaceSideValue(
    vtkDataArray* array, vtkIdType tuple, int side, int component, int perSide);

  /**
   * Name of the field-data array with the surfaces' caustic irradiance (vtkPhotonTracer's
   * CausticSubdivision c > 1 and dielectric surfaces only): 6 components (front RGB, back RGB, as
   * SurfaceIrradianceName()) and c^2 tuples per texel
   * of the atlas, every triangle's texels cut again c x c (a triangle of subdivision n and first
   * texel t has the fine texels c^2 t onwards in the texel order of subdivision n c, each inside
   * one of its atlas texels, with 1 / c^2 of its area), the irradiance that caustic photons (an
   * LS+D path) brought, in power per unit area. SurfaceIrradianceName() still holds all the light
   * (caustic included), so a reader that ignores this array sees the surfaces as before; the
   * fine texels of an atlas texel sum (flux) to its caustic part. c follows from the tuple
   * counts.
   */
  static const char* SurfaceCausticIrradianceName() { return "SurfaceCausticIrradiance"; }

  /**
   * Name of the field-data array with the number of caustic photons that landed in each atlas
   * texel and side (2 components, front then back, integer, one tuple per texel of the atlas;
   * present with SurfaceCausticIrradianceName()). The view pass reads a texel side's caustic
   * light from its fine texels only where enough caustic photons landed there
   * (vtkRefractaViewPass::CausticPhotonsPerFineTexel), so that broad, dim refracted light stays as
   * smooth as the atlas.
   */
  static const char* SurfaceCausticPhotonsName() { return "SurfaceCausticPhotons"; }

  ///@{
  /**
   * The volume caustic (vtkPhotonTracer::VolumeCausticSubdivision c > 1; field-data arrays,
   * present together). Where light focused by dielectric interfaces crosses a voxel densely, the
   * voxel has a brick of c^3 fine voxels holding that light's S1 at c times the resolution:
   * - VolumeCausticBricksName(): integer, 1 component, one tuple per voxel of the grid (point
   *   order): the voxel's brick, or -1 (none);
   * - VolumeCausticRadianceName(): 3 components, c^3 tuples per brick: fine voxel (i, j, k) of
   *   brick b at b c^3 + (k c + j) c + i, covering voxel coordinates [x - 1/2 + i / c,
   *   x - 1/2 + (i + 1) / c) along x for the brick's voxel x (likewise y, z); S1 of the focused
   *   light, power per unit volume (RGB, >= 0);
   * - VolumeCausticRadianceDirectionName(): 3 components, the same tuples: mean travel direction
   *   of that light (unit, grid-local; zero where none).
   * `Radiance` then holds the rest of S1, so a voxel's Radiance plus the mean of its brick is
   * its whole S1 (before Radiance's smoothing). c follows from the tuple counts.
   */
  static const char* VolumeCausticBricksName() { return "VolumeCausticBricks"; }
  /**
   * The volume caustic's subdivision c of `lighting` (c >= 2), read from its arrays' shapes: a
   * bricks array of one component and one tuple per point whose largest entry is B - 1, and two
   * 3-component arrays of B c^3 tuples each. 1 when any is missing or the shapes disagree (no
   * volume caustic). The number of bricks B goes to `bricks` when given. Entries are not checked
   * one by one (vtkRefractaViewPass::SetLighting does that).
   */
  static int GetVolumeCausticSubdivision(vtkDataSet* lighting, vtkIdType* bricks = nullptr);
  static const char* VolumeCausticRadianceName() { return "VolumeCausticRadiance"; }
  static const char* VolumeCausticRadianceDirectionName()
  {
    return "VolumeCausticRadianceDirection";
  }
  ///@}

  /**
   * Name of the array with the given id, or nullptr for an id out of range.
   */
  static const char* GetArrayName(int id);

  /**
   * Id of the array with the given name, or -1 if the name is not a lighting-volume array.
   */
  static int GetArrayId(const char* name);

  /**
   * Number of components of the array (3), or 0 for an id out of range.
   */
  static int GetNumberOfComponents(int id);

protected:
  vtkRefractaLightingVolume() = default;
  ~vtkRefractaLightingVolume() override = default;

private:
  vtkRefractaLightingVolume(const vtkRefractaLightingVolume&) = delete;
  void operator=(const vtkRefractaLightingVolume&) = delete;
};

#endif
