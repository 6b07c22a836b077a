/**
 * @class   vtkRefractaBVH
 * @brief   Bounding-volume hierarchy over world triangles: binned SAH build on the host, a
 *          flattened node array for OpenCL, and double-precision host traversal.
 *
 * Build() takes triangles (9 doubles each, world coordinates) and builds a binary BVH top-down
 * with the surface-area heuristic evaluated over 16 bins of the centroids along the widest
 * centroid axis (Wald 2007, "On fast construction of SAH-based bounding volume hierarchies");
 * a node becomes a leaf when it holds at most 2 triangles, when no split beats the cost of the
 * leaf (traversal cost 1, intersection cost 1 per triangle) while it holds at most 8, or at depth
 * REFRACTA_BVH_MAX_DEPTH (60). When the centroids cannot be binned (all equal) the node is split
 * at the median of the triangle order, so the depth stays bounded on any input.
 *
 * The result is flattened depth-first (first child at k + 1) into the layout of
 * Kernels/refracta_surfaces.cl: two float4 per node, boxes in float rounded outwards. The
 * triangles are reordered so that every leaf holds a contiguous range; GetTriangleOrder() maps a
 * BVH position to the index given to Build(). All flattened coordinates are relative to
 * GetFrameOrigin() (the centre of the triangles' bounds), so float keeps its precision far from
 * the world origin; a pass adds that offset to its own frame in double.
 *
 * Host traversal (IntersectRay, Occluded) runs in double precision with the watertight
 * ray-triangle test of Woop, Benthin and Wald (2013): a ray aimed exactly at an edge or a vertex
 * shared by triangles of a closed mesh hits at least one of them. Triangles are two-sided.
 * The reference renderer uses it; the OpenCL passes use the same algorithm in float.
 */
#ifndef vtkRefractaBVH_h
#define vtkRefractaBVH_h

#include "RefractaCoreModule.h" // for export macro
#include "vtkObject.h"

#include <vector> // for the flattened arrays

class REFRACTACORE_EXPORT vtkRefractaBVH : public vtkObject
{
public:
  static vtkRefractaBVH* New();
  vtkTypeMacro(vtkRefractaBVH, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Builds the hierarchy over `numberOfTriangles` triangles, `vertices` holding 9 doubles per
   * triangle (x0 y0 z0 x1 ... z2, world units). Non-finite coordinates are the caller's to reject
   * (vtkRefractaSurfaceSet does). Zero triangles give an empty hierarchy (no node; rays miss).
   */
  void Build(const double* vertices, vtkIdType numberOfTriangles);

  /**
   * Closest hit of the ray origin + t direction (world units; direction need not be unit) with
   * t in (0, tMax): returns the triangle's BVH position (see GetTriangleOrder) and fills
   * hit = (t, u, v), u and v the barycentric weights of the triangle's second and third vertex;
   * returns -1 when nothing is hit.
   */
  vtkIdType IntersectRay(
    const double origin[3], const double direction[3], double tMax, double hit[3]) const;

  /**
   * Whether any triangle meets the ray origin + t direction with t in (0, tMax).
   */
  bool Occluded(const double origin[3], const double direction[3], double tMax) const;

  /**
   * The watertight test alone, in double, for triangle p0 p1 p2 and the ray: true and
   * hit = (t, u, v) for t in (0, tMax). Exposed for tests and brute-force checks.
   */
  static bool IntersectTriangle(const double origin[3], const double direction[3],
    const double p0[3], const double p1[3], const double p2[3], double tMax, double hit[3]);

  /**
   * Number of triangles and nodes, and the depth of the deepest leaf (root = 0).
   */
  vtkIdType GetNumberOfTriangles() const { return this->NumberOfTriangles; }
  vtkIdType GetNumberOfNodes() const { return static_cast<vtkIdType>(this->Nodes.size() / 8); }
  int GetDepth() const { return this->Depth; }

  /**
   * Seconds the last Build() took (wall clock).
   */
  double GetBuildSeconds() const { return this->BuildSeconds; }

  /**
   * World position that the flattened coordinates are relative to (the centre of the bounds).
   */
  const double* GetFrameOrigin() const { return this->FrameOrigin; }

  /**
   * World bounds (xmin, xmax, ymin, ymax, zmin, zmax) of the triangles; an empty box
   * (min > max) when there are none.
   */
  void GetBounds(double bounds[6]) const;

#ifndef __VTK_WRAP__
  /**
   * Flattened nodes: 8 floats per node (lo xyz, first/child as int bits, hi xyz, count as int
   * bits), the layout of Kernels/refracta_surfaces.cl.
   */
  const std::vector<float>& GetNodes() const
  {
    return this->Nodes;
  }

  /**
   * Triangles in BVH order, relative to the frame origin: 12 floats each (v0 xyz 0, v1 xyz 0,
   * v2 xyz 0), the device layout.
   */
  const std::vector<float>& GetFloatTriangles() const
  {
    return this->FloatTriangles;
  }

  /**
   * Triangles in BVH order, relative to the frame origin, 9 doubles each (host traversal).
   */
  const std::vector<double>& GetTriangles() const
  {
    return this->Triangles;
  }

  /**
   * Input index of the triangle at each BVH position.
   */
  const std::vector<vtkIdType>& GetTriangleOrder() const
  {
    return this->Order;
  }
#endif

protected:
  vtkRefractaBVH();
  ~vtkRefractaBVH() override;

  vtkIdType NumberOfTriangles = 0;
  int Depth = 0;
  double BuildSeconds = 0;
  double FrameOrigin[3] = { 0, 0, 0 };
  double Bounds[6] = { 1, -1, 1, -1, 1, -1 };
  std::vector<float> Nodes;
  std::vector<float> FloatTriangles;
  std::vector<double> Triangles;
  std::vector<vtkIdType> Order;

private:
  vtkRefractaBVH(const vtkRefractaBVH&) = delete;
  void operator=(const vtkRefractaBVH&) = delete;
  struct Builder;
};

#endif
