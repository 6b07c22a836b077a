/**
 * @class   vtkRefractaGridCuts
 * @brief   Where the opaque surfaces of a vtkRefractaSurfaceSet cut a medium's grid.
 *
 * The light fields of the passes (`Radiance`, `MultipleScattering`, ...) are values at the voxel
 * centres of the medium's grid; an opaque surface inside the grid separates voxels whose light
 * must not mix. This class finds, for the Lambertian triangles of a built set placed relative to
 * the grid:
 *
 * - the **cut links**: per voxel, bit a (a = 0, 1, 2) is set where the segment from its centre to
 *   the next voxel centre along axis a meets a triangle (a touch counts, so a wall through a centre
 *   cuts both of its links across it);
 * - each **cut voxel's plane**: a voxel within one voxel per axis of a triangle (the reach of its
 *   cell's deposits and of the trilinear lookups that read it; conservatively, the triangle's
 *   plane within |n_x| + |n_y| + |n_z| voxels of the centre and its bounds within one voxel) gets
 *   the plane of the nearest such triangle, in voxel coordinates u (grid-local
 *   / spacing, voxel (i, j, k) at u = (i, j, k)) as (n, d) with n a unit vector in u and
 *   n . u + d the signed distance in voxels. A point lies **across** the voxel's surface when it is
 *   on the other side of that plane from the voxel's centre (IsAcross; a centre on the plane
 *   belongs to its front).
 *
 * Three passes read them: the photon deposits' 3 x 3 x 3 smoothing exchanges nothing over a cut
 * link; a photon's piece whose midpoint is across its voxel's surface deposits into the
 * neighbour on its own side; the view pass's trilinear lookups of light leave out the corners
 * across their surface from the sample. The plane is the triangle's own, extended: near the edge
 * of a surface it may separate points that the surface does not (within a voxel of the edge).
 * Dielectric (glass) triangles cut nothing: light passes through them.
 *
 * The search runs on the host in double precision over the voxels around each triangle's bounds
 * and is kept while the set's build, the grid and the placement stay the same (a light or camera
 * move does not search again).
 */
#ifndef vtkRefractaGridCuts_h
#define vtkRefractaGridCuts_h

#include "RefractaCoreModule.h" // for export macro
#include "vtkObject.h"
#include "vtkSmartPointer.h" // for the kept set

#include <vector> // for the cuts

class vtkMatrix4x4;
class vtkRefractaSurfaceSet;

class REFRACTACORE_EXPORT vtkRefractaGridCuts : public vtkObject
{
public:
  static vtkRefractaGridCuts* New();
  vtkTypeMacro(vtkRefractaGridCuts, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Finds the cuts of the Lambertian triangles of `set` (built: vtkRefractaSurfaceSet::Build())
   * in the grid of `dims` points with `spacing` (world units per voxel, > 0), whose grid-local
   * frame (vtkRefractaGridFrame) `localToWorld` places in the surfaces' world (nullptr: the
   * identity). Builds the set first (vtkRefractaSurfaceSet::Build() is cached). Keeps the last
   * result when the set, its build, the grid and the placement are those of the last call.
   * nullptr or an empty set: no cuts. Returns true when it searched again; false also after an
   * error (dimensions < 1, a spacing not finite and > 0, a set that cannot be built, memory),
   * which leaves no cuts.
   */
  bool Update(vtkRefractaSurfaceSet* set, const int dims[3], const double spacing[3],
    vtkMatrix4x4* localToWorld);

  /**
   * Whether any link is cut (false until Update()).
   */
  bool HasCuts() const { return !this->Links.empty(); }

  /**
   * Per voxel (index x + nx (y + ny z)), bit a set where its link along +axis a is cut; empty
   * when none is.
   */
  const std::vector<unsigned char>& GetLinks() const { return this->Links; }

  /**
   * Per voxel, the index of its plane in GetPlanes() (4 floats each), or -1 for a voxel at no
   * cut link; empty when no link is cut.
   */
  const std::vector<int>& GetVoxelPlanes() const { return this->VoxelPlanes; }

  /**
   * The planes (n_x, n_y, n_z, d) in voxel coordinates, n unit: one per triangle that is some
   * voxel's nearest cut.
   */
  const std::vector<float>& GetPlanes() const { return this->Planes; }

  /**
   * Whether voxel coordinates `u` lie across the surface of voxel (i, j, k) from its centre
   * (false for a voxel without a plane). A point on the plane counts on its front (n . u + d >=
   * 0): a voxel whose centre lies on a surface belongs to the side its normal faces. In float, as
   * the kernels' twin refracta_across_cut (Kernels/refracta_common.cl) computes it.
   */
  bool IsAcross(int i, int j, int k, const double u[3]) const;

  /**
   * How many searches Update() has run (a kept result is not a search).
   */
  vtkGetMacro(NumberOfSearches, int);

protected:
  vtkRefractaGridCuts();
  ~vtkRefractaGridCuts() override;

private:
  vtkRefractaGridCuts(const vtkRefractaGridCuts&) = delete;
  void operator=(const vtkRefractaGridCuts&) = delete;

  void Search(vtkRefractaSurfaceSet* set, vtkMatrix4x4* localToWorld);
  void Clear(); // no cuts, nothing kept

  // What the kept result was found for.
  vtkSmartPointer<vtkRefractaSurfaceSet> Set; // held: a new set cannot take its address
  int Builds = -1;
  int Dims[3] = { 0, 0, 0 };
  double Spacing[3] = { 0, 0, 0 };
  double LocalToWorld[16] = {};
  int NumberOfSearches = 0;

  std::vector<unsigned char> Links;
  std::vector<int> VoxelPlanes;
  std::vector<float> Planes;
};

#endif
