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
};

#endif
