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
 * - the voxels **near** a triangle (bit REFRACTA_CUT_NEAR, 8): a triangle passes within one voxel
 *   per axis of the centre (conservatively: its plane within |n_x| + |n_y| + |n_z| voxels, its
 *   bounds within one voxel), the reach of the cell's deposits and of the trilinear lookups that
 *   read the centre.
 *
 * The passes read them: the photon deposits' 3 x 3 x 3 smoothing exchanges nothing over a cut
 * link; near a triangle, a photon's piece that an opaque triangle separates from its voxel's
 * centre deposits into the nearest voxel around whose centre it sees, and the view pass's
 * trilinear lookups of light leave out the corners an opaque triangle separates from the sample
 * (both asked of the surfaces' BVH on the device, refracta_opaque_between). Dielectric (glass)
 * triangles cut nothing: light passes through them.
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

#include <utility> // for std::pair
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
   * Whether any link is cut or any voxel near an opaque triangle (false until Update()).
   */
  bool HasCuts() const { return !this->Links.empty(); }

  /**
   * Per voxel (index x + nx (y + ny z)), bit a set where its link along +axis a is cut and bit
   * REFRACTA_CUT_NEAR (Kernels/refracta_surfaces.cl, 8) where an opaque triangle passes within
   * one voxel per axis of its centre; empty when neither happens anywhere.
   */
  const std::vector<unsigned char>& GetLinks() const { return this->Links; }

  /**
   * Whether an opaque triangle passes within one voxel per axis of voxel (i, j, k)'s centre
   * (false outside the grid).
   */
  bool IsNear(int i, int j, int k) const;

  ///@{
  /**
   * The owned volumes of the sided deposits. A photon piece near an opaque triangle deposits into
   * its own voxel when no opaque triangle separates it from the voxel's centre, else into the
   * nearest of the 26 voxels around it whose centre none separates from it (the kernels' rule,
   * photon_sided_voxel). The voxels whose deposits so come from a volume other than their own box
   * (a wall through it or through a neighbour's) are listed with h^3 / V_owned, V_owned the
   * volume of the points that deposit into them (the factor that makes their deposits power per
   * unit volume again; 0 for a voxel that owns nothing, a centre on a wall). V_owned is counted
   * at 64 points per box a triangle crosses (the R3 low-discrepancy sequence; a point of any
   * other box sees its centre), in double against the triangles noted for the boxes a segment
   * passes, on the first call after a search (the view pass never asks), in parallel. Empty
   * without cuts.
   */
  const std::vector<vtkIdType>& GetScaledVoxels();
  const std::vector<float>& GetVolumeScales();
  ///@}

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
  void MarkVoxel(const int ijk[3], const float plane[4], double reach, const double low[3],
    const double high[3], const double v[3][3]);
  void NoteBoxTriangle(const int ijk[3], const float plane[4], double reach, const double low[3],
    const double high[3]);
  void Clear(); // no cuts, nothing kept
  // The owned volumes (GetScaledVoxels) of the triangles in Opaque.
  void CountOwnedVolumes();

  // What the kept result was found for.
  vtkSmartPointer<vtkRefractaSurfaceSet> Set; // held: a new set cannot take its address
  int Builds = -1;
  int Dims[3] = { 0, 0, 0 };
  double Spacing[3] = { 0, 0, 0 };
  double LocalToWorld[16] = {};
  int NumberOfSearches = 0;

  std::vector<unsigned char> Links;
  std::vector<double> Opaque; // the opaque triangles, grid-local (9 doubles each)
  // (voxel, triangle of Opaque) where the triangle may cross the voxel's box.
  std::vector<std::pair<vtkIdType, vtkIdType>> BoxTriangles;
  bool VolumesCounted = false;
  std::vector<vtkIdType> ScaledVoxels;
  std::vector<float> VolumeScales;
};

#endif
