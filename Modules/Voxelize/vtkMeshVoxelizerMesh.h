/**
 * Private helpers of vtkMeshVoxelizer: mesh validation and the exact inside tests. All of CGAL
 * lives behind this header (in vtkMeshVoxelizerMesh.cxx), so the rest of the module compiles
 * without it.
 */
#ifndef vtkMeshVoxelizerMesh_h
#define vtkMeshVoxelizerMesh_h

#include "vtkType.h"

#include <array>
#include <memory>
#include <string>
#include <vector>

class vtkPolyData;

namespace refracta_voxelize
{

/// A proper crossing of a grid line (parallel to x) with a triangle: x of the hit and triangle.
struct Crossing
{
  double X;
  vtkIdType Triangle;
  bool operator<(const Crossing& o) const { return this->X < o.X; }
};

/**
 * A validated, closed, consistently oriented triangle mesh ready for inside tests.
 */
class PreparedMesh
{
public:
  PreparedMesh();
  ~PreparedMesh();
  PreparedMesh(const PreparedMesh&) = delete;
  PreparedMesh& operator=(const PreparedMesh&) = delete;

  /**
   * Validate and prepare `input` (the mesh called `name` in messages). Returns false when the
   * mesh cannot be voxelized; `errors` then says why. `warnings` lists what was repaired
   * (triangulated polygons, dropped collapsed faces, fixed orientation). Never throws.
   */
  bool Prepare(vtkPolyData* input, const std::string& name, bool checkSelfIntersections,
    std::vector<std::string>& errors, std::vector<std::string>& warnings);

  /**
   * True when every cell of `input` (polygons, strips, lines, vertices) refers to existing
   * points; otherwise `why` names the first bad cell, its id and the valid range. VTK's bounds
   * and triangulation trust the ids, so check them before either runs.
   */
  static bool CheckPointIds(vtkPolyData* input, std::string& why);

  /**
   * Largest coordinate magnitude accepted (1e100): the inside test and the volume multiply three
   * coordinate differences, which must stay finite.
   */
  static constexpr double MaximumCoordinate = 1e100;

  /// Vertex coordinates (x, y, z per vertex) after merging exactly coincident points.
  std::vector<double> Points;
  /// Triangles (vertex ids), consistently oriented with outward normals.
  std::vector<std::array<vtkIdType, 3>> Triangles;
  /// Enclosed volume (world units cubed), > 0.
  double Volume = 0.0;
  /// Axis-aligned bounds (xmin, xmax, ymin, ymax, zmin, zmax).
  double Bounds[6] = { 0, -1, 0, -1, 0, -1 };

  /**
   * Proper crossings of the line {(t, y, z)} with the triangles `candidates`, appended to `out`
   * unsorted. Returns false when the line passes exactly through an edge or a vertex of a
   * triangle's projection onto the yz-plane, or lies in a triangle parallel to x (exact
   * predicates): parity along that line is then ambiguous and the caller must use Classify().
   */
  bool LineCrossings(const vtkIdType* candidates, size_t count, double y, double z,
    std::vector<Crossing>& out) const;

  /**
   * Exact side of point p relative to triangle `tri` along x: -1 when p lies before the plane of
   * the triangle (smaller x), +1 after, 0 exactly on it. For a triangle the line through p
   * crosses properly.
   */
  int SideAlongX(vtkIdType tri, const double p[3]) const;

  /**
   * Robust point classification (CGAL Side_of_triangle_mesh): 1 inside, 0.5 exactly on the
   * surface, 0 outside. Thread-safe.
   */
  double Classify(const double p[3]) const;

  /**
   * True when triangle `tri` intersects the closed box (xmin, xmax, ymin, ymax, zmin, zmax)
   * (exact predicates).
   */
  bool TriangleTouchesBox(vtkIdType tri, const double box[6]) const;

  /// Triangle bounds (xmin, xmax, ymin, ymax, zmin, zmax).
  void GetTriangleBounds(vtkIdType tri, double b[6]) const;

private:
  struct Internals;
  std::unique_ptr<Internals> Impl;
};

} // namespace refracta_voxelize

#endif
