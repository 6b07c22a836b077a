/**
 * Internal to RefractaCore (a private header: not wrapped, not installed). What the two
 * implementation files of vtkRefractaSurfaceSet share: the build's scratch (its meshes, the BVH,
 * the world triangles and where they came from) and the triangle arithmetic the interface
 * description also needs (vtkRefractaSurfaceSetInterfaces.cxx).
 */
#ifndef vtkRefractaSurfaceSetInternals_h
#define vtkRefractaSurfaceSetInternals_h

#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkRefractaBVH.h"
#include "vtkRefractaSurfaceMaterial.h"
#include "vtkRefractaSurfaceSet.h"
#include "vtkSmartPointer.h"

#include <cmath>
#include <vector>

namespace vtkRefractaSurfaceSetDetail
{
// A smoothed corner normal is kept only within this angle of its face's normal (cos 30 degrees):
// a cube's edges stay sharp, a tessellated sphere is smooth.
constexpr double SmoothNormalCosine = 0.86602540378443865;

// Where a world triangle came from: its surface, cell and the mesh's point ids.
struct SourceTriangle
{
  int Surface;
  vtkIdType Cell;
  vtkIdType Points[3];
};

// (v1 - v0) x (v2 - v0) of the triangle v (9 doubles): the winding normal, |c| = doubled area.
inline void Cross(const double* v, double c[3])
{
  const double e1[3] = { v[3] - v[0], v[4] - v[1], v[5] - v[2] };
  const double e2[3] = { v[6] - v[0], v[7] - v[1], v[8] - v[2] };
  c[0] = e1[1] * e2[2] - e1[2] * e2[1];
  c[1] = e1[2] * e2[0] - e1[0] * e2[2];
  c[2] = e1[0] * e2[1] - e1[1] * e2[0];
}

inline double DoubledArea(const double* v)
{
  double c[3];
  Cross(v, c);
  return std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
}

// Scales c to unit length (left as it is when zero).
inline void Normalize(double c[3])
{
  const double l = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
  if (l > 0)
  {
    c[0] /= l;
    c[1] /= l;
    c[2] /= l;
  }
}

// What smoothing across the triangles that share a mesh point needs (the glass's corner normals,
// the Lambertian corners' irradiance): per surface, the triangles (BVH order) at each of its mesh
// points (CSR), and every triangle's unit face normal and doubled area (BVH order).
struct SharedPoints
{
  std::vector<std::vector<vtkIdType>> Offsets, Triangles;
  std::vector<double> Faces, Areas;

  void Build(vtkRefractaSurfaceSet* set, const vtkRefractaBVH* bvh,
    const std::vector<SourceTriangle>& sources);
  void Clear() { *this = SharedPoints(); }

  // Calls f(j) for each triangle j at mesh point p of surface s (triangle k among them) whose
  // face is within the smoothing angle of k's.
  template <class F>
  void ForSmoothNeighbours(int s, vtkIdType p, vtkIdType k, F f) const
  {
    const double* face = &this->Faces[3 * k];
    for (vtkIdType i = this->Offsets[s][p]; i < this->Offsets[s][p + 1]; ++i)
    {
      const vtkIdType j = this->Triangles[s][i];
      const double* g = &this->Faces[3 * j];
      if (g[0] * face[0] + g[1] * face[1] + g[2] * face[2] >= SmoothNormalCosine)
      {
        f(j);
      }
    }
  }
};
} // namespace vtkRefractaSurfaceSetDetail

//------------------------------------------------------------------------------
struct vtkRefractaSurfaceSet::Internals
{
  struct Entry
  {
    vtkSmartPointer<vtkPolyData> Mesh;
    vtkSmartPointer<vtkRefractaSurfaceMaterial> Material;
    vtkSmartPointer<vtkMatrix4x4> Matrix;
  };
  std::vector<Entry> Surfaces;
  vtkNew<vtkRefractaBVH> BVH;

  // Build scratch: world triangles (9 doubles each) and where they came from.
  std::vector<double> World;
  std::vector<vtkRefractaSurfaceSetDetail::SourceTriangle> Sources;
  vtkRefractaSurfaceSetDetail::SharedPoints Shared;
};

#endif
