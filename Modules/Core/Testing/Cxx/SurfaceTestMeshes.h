// Meshes shared by the surface tests: a closed box and a random triangle soup.
#ifndef SurfaceTestMeshes_h
#define SurfaceTestMeshes_h

#include "vtkCellArray.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <cmath>
#include <random>
#include <vector>

namespace surface_test
{
// Triangles of a polydata's polys (9 doubles each).
inline std::vector<double> Triangles(vtkPolyData* mesh)
{
  std::vector<double> out;
  vtkCellArray* polys = mesh->GetPolys();
  vtkIdType n;
  const vtkIdType* ids;
  for (polys->InitTraversal(); polys->GetNextCell(n, ids);)
  {
    for (vtkIdType k = 1; k + 1 < n; ++k)
    {
      for (vtkIdType id : { ids[0], ids[k], ids[k + 1] })
      {
        double p[3];
        mesh->GetPoint(id, p);
        out.insert(out.end(), p, p + 3);
      }
    }
  }
  return out;
}

// The closed axis-aligned box [lo, hi] as 12 triangles over 8 shared points.
inline vtkSmartPointer<vtkPolyData> ClosedBox(const double lo[3], const double hi[3])
{
  vtkNew<vtkPoints> points;
  for (int c = 0; c < 8; ++c)
  {
    points->InsertNextPoint(
      (c & 1) ? hi[0] : lo[0], (c & 2) ? hi[1] : lo[1], (c & 4) ? hi[2] : lo[2]);
  }
  const vtkIdType quads[6][4] = { { 0, 2, 3, 1 }, { 4, 5, 7, 6 }, { 0, 1, 5, 4 }, { 2, 6, 7, 3 },
    { 0, 4, 6, 2 }, { 1, 3, 7, 5 } };
  vtkNew<vtkCellArray> polys;
  for (const auto& q : quads)
  {
    const vtkIdType t1[3] = { q[0], q[1], q[2] };
    const vtkIdType t2[3] = { q[0], q[2], q[3] };
    polys->InsertNextCell(3, t1);
    polys->InsertNextCell(3, t2);
  }
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->SetPoints(points);
  mesh->SetPolys(polys);
  return mesh;
}

// Whether the ray from `origin` to `target` passes through the inside of a closed mesh at the
// target rather than grazing its silhouette there: every triangle that contains the target (as a
// vertex or on an edge) faces the origin strictly, or every one faces away strictly. `tri` holds
// 9 values per triangle (float or double), the target is a vertex or an edge midpoint of them.
template <typename T>
bool CrossesAt(
  const std::vector<T>& tri, size_t stride, const double target[3], const double origin[3])
{
  int front = 0, back = 0;
  const double d[3] = { target[0] - origin[0], target[1] - origin[1], target[2] - origin[2] };
  for (size_t t = 0; t + 9 <= tri.size(); t += stride)
  {
    double v[3][3];
    for (int k = 0; k < 3; ++k)
    {
      for (int a = 0; a < 3; ++a)
      {
        v[k][a] = tri[t + (stride == 12 ? 4 : 3) * k + a];
      }
    }
    bool contains = false;
    for (int k = 0; k < 3 && !contains; ++k)
    {
      const double* p = v[k];
      const double* q = v[(k + 1) % 3];
      bool vertex = true, mid = true;
      for (int a = 0; a < 3; ++a)
      {
        vertex = vertex && p[a] == target[a];
        mid = mid && static_cast<T>(0.5 * (p[a] + q[a])) == static_cast<T>(target[a]);
      }
      contains = vertex || mid;
    }
    if (!contains)
    {
      continue;
    }
    const double e1[3] = { v[1][0] - v[0][0], v[1][1] - v[0][1], v[1][2] - v[0][2] };
    const double e2[3] = { v[2][0] - v[0][0], v[2][1] - v[0][1], v[2][2] - v[0][2] };
    const double n[3] = { e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
      e1[0] * e2[1] - e1[1] * e2[0] };
    const double c = (n[0] * d[0] + n[1] * d[1] + n[2] * d[2]) /
      std::sqrt(
        (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) * (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
    front += c < -1e-3 ? 1 : 0;
    back += c > 1e-3 ? 1 : 0;
    if (std::fabs(c) <= 1e-3)
    {
      return false;
    }
  }
  return (front > 0) != (back > 0);
}

// `count` random triangles of size up to `size` in the cube [-1, 1]^3 shifted by `offset`.
inline std::vector<double> RandomSoup(int count, double size, const double offset[3], unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> centre(-1.0, 1.0);
  std::uniform_real_distribution<double> jitter(-size, size);
  std::vector<double> out;
  for (int t = 0; t < count; ++t)
  {
    const double c[3] = { centre(rng), centre(rng), centre(rng) };
    for (int k = 0; k < 3; ++k)
    {
      for (int a = 0; a < 3; ++a)
      {
        out.push_back(offset[a] + c[a] + jitter(rng));
      }
    }
  }
  return out;
}
}

#endif
