/**
 * @class   vtkRefractaGridFrame
 * @brief   The one conversion between world coordinates and a vtkImageData's grid.
 *
 * VTK places the point with structured (absolute, extent-including) index ijk of an image at
 *
 *     world = Origin + D * (Spacing * ijk)
 *
 * (D the direction matrix, Spacing applied per axis). Refracta's passes store only the points of
 * the extent, so they work in two frames derived from it:
 *
 * - **index** coordinates: continuous, 0 at the first STORED point, i.e. index = ijk - extent min
 *   (dimensionless; index (i, j, k) is the point i + nx (j + ny k) of the point arrays);
 * - **grid-local** coordinates: grid axes, world units, origin at the first stored point centre:
 *   local = Spacing * index = D^-1 (world - Origin) - Spacing * extent min (D^-1 = D^T for the
 * rotations a medium must have; the inverse is used so that any direction matrix agrees with
 *   vtkImageData::TransformPhysicalPointToContinuousIndex). The passes march rays
 *   and photons in this frame; the medium box is [-Spacing / 2, (dims - 1/2) Spacing].
 *
 * Points use the full affine maps, vectors (directions, gradients) only their linear parts; a
 * world vector maps to grid-local by D^-1 (a rotation, lengths kept) and to index by
 * Spacing^-1 D^-1. All matrices are double 4x4, row major, acting on column vectors (x, y, z, 1).
 *
 * Every pass (view pass, reference renderer, photon tracer, scene analysis, lighting filters)
 * converts through this class; none combines origin, extent and direction on its own.
 */
#ifndef vtkRefractaGridFrame_h
#define vtkRefractaGridFrame_h

#include "RefractaCoreModule.h" // for export macro
#include "vtkObject.h"

#include <string> // for std::string

class vtkImageData;
class vtkMatrix4x4;

class REFRACTACORE_EXPORT vtkRefractaGridFrame : public vtkObject
{
public:
  static vtkRefractaGridFrame* New();
  vtkTypeMacro(vtkRefractaGridFrame, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Takes origin, spacing, extent and direction matrix of `image` (identity frame for nullptr).
   */
  void SetImage(vtkImageData* image);

  /**
   * The same from explicit values: origin (world units), spacing (world units, > 0), extent
   * (structured indices, min/max per axis) and direction matrix (row major, orthonormal).
   */
  void SetGrid(const double origin[3], const double spacing[3], const int extent[6],
    const double direction[9]);

  ///@{
  /**
   * The grid this frame was built from.
   */
  const double* GetOrigin() const { return this->Origin; }
  const double* GetSpacing() const { return this->Spacing; }
  const int* GetExtent() const { return this->Extent; }
  const double* GetDirection() const { return this->Direction; }
  ///@}

  /**
   * World position (world units) of the first stored point, index (0, 0, 0):
   * Origin + D (Spacing * extent min).
   */
  void GetFirstPoint(double world[3]) const;

  ///@{
  /**
   * The maps as 4x4 matrices (copied into `m`).
   * WorldToIndex: world point -> continuous index (0 at the first stored point).
   * WorldToLocal: world point -> grid-local (world units). The other two are their inverses.
   */
  void GetWorldToIndexMatrix(vtkMatrix4x4* m) const;
  void GetIndexToWorldMatrix(vtkMatrix4x4* m) const;
  void GetWorldToLocalMatrix(vtkMatrix4x4* m) const;
  void GetLocalToWorldMatrix(vtkMatrix4x4* m) const;
  const double* GetWorldToLocal() const { return this->WorldToLocal; }
  const double* GetLocalToWorld() const { return this->LocalToWorld; }
  ///@}

  ///@{
  /**
   * Points: world <-> grid-local (world units) and world <-> continuous index.
   */
  void WorldToLocalPoint(const double world[3], double local[3]) const
  {
    Apply(this->WorldToLocal, world, local, 1.0);
  }
  void LocalToWorldPoint(const double local[3], double world[3]) const
  {
    Apply(this->LocalToWorld, local, world, 1.0);
  }
  void WorldToIndexPoint(const double world[3], double index[3]) const
  {
    this->WorldToLocalPoint(world, index);
    for (int a = 0; a < 3; ++a)
    {
      index[a] /= this->Spacing[a];
    }
  }
  void IndexToWorldPoint(const double index[3], double world[3]) const
  {
    const double local[3] = { index[0] * this->Spacing[0], index[1] * this->Spacing[1],
      index[2] * this->Spacing[2] };
    this->LocalToWorldPoint(local, world);
  }
  ///@}

  ///@{
  /**
   * Vectors (directions, displacements, gradients of a scalar use the same rotation since D is
   * orthonormal): world <-> grid-local. Lengths are kept.
   */
  void WorldToLocalVector(const double world[3], double local[3]) const
  {
    Apply(this->WorldToLocal, world, local, 0.0);
  }
  void LocalToWorldVector(const double local[3], double world[3]) const
  {
    Apply(this->LocalToWorld, local, world, 0.0);
  }
  ///@}

  /**
   * True when `a` and `b` place the same number of points at the same world positions: equal
   * dimensions, spacing (relative `tolerance`), direction matrix (absolute `tolerance`) and
   * world position of the first stored point (within `tolerance` times the smallest spacing).
   * Origin and extent may differ as long as they compensate. False for a null image.
   */
  static bool SameGrid(vtkImageData* a, vtkImageData* b, double tolerance = 1e-6);

  /**
   * "dims 8x8x8, spacing (..), first point (..), direction (..)": for error messages.
   */
  static std::string DescribeGrid(vtkImageData* image);

protected:
  vtkRefractaGridFrame();
  ~vtkRefractaGridFrame() override = default;

  static void Apply(const double m[16], const double in[3], double out[3], double w)
  {
    for (int r = 0; r < 3; ++r)
    {
      out[r] = m[4 * r] * in[0] + m[4 * r + 1] * in[1] + m[4 * r + 2] * in[2] + w * m[4 * r + 3];
    }
  }

  double Origin[3] = { 0, 0, 0 };
  double Spacing[3] = { 1, 1, 1 };
  int Extent[6] = { 0, 0, 0, 0, 0, 0 };
  double Direction[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  double WorldToLocal[16];
  double LocalToWorld[16];

private:
  vtkRefractaGridFrame(const vtkRefractaGridFrame&) = delete;
  void operator=(const vtkRefractaGridFrame&) = delete;
};

#endif
