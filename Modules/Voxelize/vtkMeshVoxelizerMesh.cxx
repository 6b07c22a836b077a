// Mesh validation and exact inside tests for vtkMeshVoxelizer. This is the only translation unit
// of Refracta that includes CGAL (compile time, and keeping CGAL out of public headers).
#include "vtkMeshVoxelizerMesh.h"

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkTriangleFilter.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/intersections.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

namespace refracta_voxelize
{
namespace
{
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point2 = Kernel::Point_2;
using Point3 = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point3>;
using SideOf = CGAL::Side_of_triangle_mesh<Mesh, Kernel>;
namespace PMP = CGAL::Polygon_mesh_processing;

std::string PointText(const double* p)
{
  std::ostringstream os;
  os << "(" << p[0] << ", " << p[1] << ", " << p[2] << ")";
  return os.str();
}
} // namespace

struct PreparedMesh::Internals
{
  Mesh Surface; // in the classifier's frame: world coordinates times Scale
  std::unique_ptr<SideOf> Side;
  // A power of two (so the scaling is exact) that brings every coordinate within +-1. CGAL's
  // classifier casts rays from the query point through point + a unit vector; beyond about 1e15
  // that sum rounds back to the point, every ray is degenerate and CGAL retries forever (a hang
  // found by FuzzMeshVoxelizer, corpus input huge_coordinates_classifier_hang).
  double Scale = 1.0;
};

namespace
{
// The power of two that brings the largest |coordinate| below 1 (1 when it already is), or 0
// when that would push a non-zero coordinate below the normal doubles (the scaling would then
// round it: the mesh spans too many orders of magnitude for an exact test).
double ClassifierScale(const std::vector<double>& points)
{
  double largest = 0.0, smallest = std::numeric_limits<double>::infinity();
  for (double x : points)
  {
    const double a = std::abs(x);
    largest = std::max(largest, a);
    if (a > 0.0)
    {
      smallest = std::min(smallest, a);
    }
  }
  if (largest <= 1.0)
  {
    return 1.0;
  }
  int exponent = 0;
  std::frexp(largest, &exponent);
  const double scale = std::ldexp(1.0, -exponent);
  return smallest * scale >= std::numeric_limits<double>::min() ? scale : 0.0;
}
}

PreparedMesh::PreparedMesh() = default;
PreparedMesh::~PreparedMesh() = default;

//------------------------------------------------------------------------------
bool PreparedMesh::Prepare(vtkPolyData* input, const std::string& name, bool checkSelfIntersections,
  std::vector<std::string>& errors, std::vector<std::string>& warnings)
{
  const std::string prefix = name + ": ";
  auto fail = [&](const std::string& what)
  {
    errors.push_back(prefix + what);
    return false;
  };
  this->Points.clear();
  this->Triangles.clear();
  this->Impl.reset();

  if (!input)
  {
    return fail("no mesh (null input); connect a closed triangle vtkPolyData");
  }
  const vtkIdType numPoints = input->GetNumberOfPoints();
  const vtkIdType numSurfaceCells = input->GetNumberOfPolys() + input->GetNumberOfStrips();
  if (numPoints == 0 || numSurfaceCells == 0)
  {
    std::ostringstream os;
    os << "empty mesh (" << numPoints << " points, " << numSurfaceCells
       << " polygons or strips); a closed surface of polygons is needed";
    return fail(os.str());
  }

  std::string badIds;
  if (!CheckPointIds(input, badIds))
  {
    return fail(badIds);
  }

  // NaN, infinite or huge coordinates make the geometric tests meaningless (products of three
  // coordinates overflow past 1e100): reject, naming the first.
  vtkIdType badPoints = 0, firstBad = -1;
  for (vtkIdType i = 0; i < numPoints; ++i)
  {
    double p[3];
    input->GetPoint(i, p);
    if (!(std::abs(p[0]) <= MaximumCoordinate && std::abs(p[1]) <= MaximumCoordinate &&
          std::abs(p[2]) <= MaximumCoordinate))
    {
      firstBad = badPoints++ == 0 ? i : firstBad;
    }
  }
  if (badPoints)
  {
    double p[3];
    input->GetPoint(firstBad, p);
    std::ostringstream os;
    const bool finite = std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
    os << badPoints << " points have " << (finite ? "too large" : "NaN or infinite")
       << " coordinates (first: point " << firstBad << " = " << PointText(p)
       << "); every coordinate must be finite and within +-" << MaximumCoordinate
       << " (scale the mesh)";
    return fail(os.str());
  }

  if (input->GetNumberOfLines() + input->GetNumberOfVerts() > 0)
  {
    std::ostringstream os;
    os << prefix << (input->GetNumberOfLines() + input->GetNumberOfVerts())
       << " line and vertex cells were ignored (only polygons bound a volume)";
    warnings.push_back(os.str());
  }

  // Triangulate polygons and strips when there are any that are not triangles.
  vtkIdType nonTriangles = 0, tooSmall = 0;
  {
    auto it = vtk::TakeSmartPointer(input->GetPolys()->NewIterator());
    for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
    {
      vtkIdType n;
      const vtkIdType* ids;
      it->GetCurrentCell(n, ids);
      nonTriangles += n > 3 ? 1 : 0;
      tooSmall += n < 3 ? 1 : 0;
    }
  }
  vtkSmartPointer<vtkPolyData> triangles = input;
  if (nonTriangles > 0 || input->GetNumberOfStrips() > 0)
  {
    vtkNew<vtkTriangleFilter> triangulate;
    triangulate->SetInputData(input);
    triangulate->PassLinesOff();
    triangulate->PassVertsOff();
    triangulate->Update();
    triangles = triangulate->GetOutput();
    std::ostringstream os;
    os << prefix << nonTriangles << " polygons with more than three vertices and "
       << input->GetNumberOfStrips() << " triangle strips were triangulated";
    warnings.push_back(os.str());
  }
  if (tooSmall > 0)
  {
    std::ostringstream os;
    os << prefix << tooSmall << " polygons with fewer than three vertices were ignored";
    warnings.push_back(os.str());
  }

  // Merge exactly coincident points: many sources (vtkCubeSource) duplicate points per face for
  // normals, which would otherwise make a closed surface look open. No tolerance: merging
  // near-coincident points could change the geometry.
  std::map<std::array<double, 3>, vtkIdType> unique;
  std::vector<vtkIdType> remap(triangles->GetNumberOfPoints());
  for (vtkIdType i = 0; i < triangles->GetNumberOfPoints(); ++i)
  {
    double p[3];
    triangles->GetPoint(i, p);
    const std::array<double, 3> key = { p[0] + 0.0, p[1] + 0.0, p[2] + 0.0 }; // -0 == +0
    auto inserted = unique.emplace(key, static_cast<vtkIdType>(this->Points.size() / 3));
    if (inserted.second)
    {
      this->Points.insert(this->Points.end(), key.begin(), key.end());
    }
    remap[i] = inserted.first->second;
  }
  vtkIdType collapsed = 0;
  {
    auto it = vtk::TakeSmartPointer(triangles->GetPolys()->NewIterator());
    for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
    {
      vtkIdType n;
      const vtkIdType* ids;
      it->GetCurrentCell(n, ids);
      if (n != 3)
      {
        continue;
      }
      const std::array<vtkIdType, 3> t = { remap[ids[0]], remap[ids[1]], remap[ids[2]] };
      if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0])
      {
        ++collapsed; // zero area and no effect on the surface's topology
        continue;
      }
      this->Triangles.push_back(t);
    }
  }
  if (collapsed)
  {
    std::ostringstream os;
    os << prefix << collapsed << " faces with a repeated vertex (zero area) were dropped";
    warnings.push_back(os.str());
  }
  if (this->Triangles.empty())
  {
    return fail("no triangle with three distinct vertices; a closed surface is needed");
  }
  const vtkIdType numTriangles = static_cast<vtkIdType>(this->Triangles.size());
  auto P = [this](vtkIdType v)
  { return Point3(this->Points[3 * v], this->Points[3 * v + 1], this->Points[3 * v + 2]); };

  // Degenerate faces: three distinct but collinear vertices (exact test).
  vtkIdType degenerate = 0, firstDegenerate = -1;
  for (vtkIdType t = 0; t < numTriangles; ++t)
  {
    const auto& f = this->Triangles[t];
    if (CGAL::collinear(P(f[0]), P(f[1]), P(f[2])))
    {
      firstDegenerate = degenerate++ == 0 ? t : firstDegenerate;
    }
  }
  if (degenerate)
  {
    const auto& f = this->Triangles[firstDegenerate];
    std::ostringstream os;
    os << degenerate << " degenerate faces (three collinear vertices, zero area; first: "
       << PointText(&this->Points[3 * f[0]]) << ", " << PointText(&this->Points[3 * f[1]]) << ", "
       << PointText(&this->Points[3 * f[2]])
       << "); repair the mesh (e.g. CGAL::Polygon_mesh_processing::remove_degenerate_faces)";
    return fail(os.str());
  }

  // Edge topology: every undirected edge of a closed 2-manifold has exactly two faces.
  struct HalfEdge
  {
    vtkIdType A, B, Face;
    bool Forward;
    bool operator<(const HalfEdge& o) const { return A < o.A || (A == o.A && B < o.B); }
  };
  std::vector<HalfEdge> edges;
  edges.reserve(3 * numTriangles);
  for (vtkIdType t = 0; t < numTriangles; ++t)
  {
    for (int e = 0; e < 3; ++e)
    {
      const vtkIdType a = this->Triangles[t][e], b = this->Triangles[t][(e + 1) % 3];
      edges.push_back({ std::min(a, b), std::max(a, b), t, a < b });
    }
  }
  std::sort(edges.begin(), edges.end());
  vtkIdType border = 0, nonManifold = 0;
  const HalfEdge* firstBorder = nullptr;
  // Neighbour lists: (other face, whether the pair disagrees in orientation).
  std::vector<std::vector<std::pair<vtkIdType, bool>>> neighbours(numTriangles);
  for (size_t i = 0; i < edges.size();)
  {
    size_t j = i;
    while (j < edges.size() && edges[j].A == edges[i].A && edges[j].B == edges[i].B)
    {
      ++j;
    }
    if (j - i == 1)
    {
      firstBorder = border++ == 0 ? &edges[i] : firstBorder;
    }
    else if (j - i > 2)
    {
      ++nonManifold;
    }
    else
    {
      // Consistent neighbours traverse their shared edge in opposite directions.
      const bool disagree = edges[i].Forward == edges[i + 1].Forward;
      neighbours[edges[i].Face].emplace_back(edges[i + 1].Face, disagree);
      neighbours[edges[i + 1].Face].emplace_back(edges[i].Face, disagree);
    }
    i = j;
  }
  if (border)
  {
    std::ostringstream os;
    os << "the mesh is not closed: " << border << " boundary edges (first from "
       << PointText(&this->Points[3 * firstBorder->A]) << " to "
       << PointText(&this->Points[3 * firstBorder->B])
       << "); a closed (watertight) surface is needed: fill the holes (e.g. vtkFillHolesFilter) "
          "or merge duplicated points (vtkCleanPolyData)";
    fail(os.str());
  }
  if (nonManifold)
  {
    std::ostringstream os;
    os << "the mesh is not a 2-manifold: " << nonManifold
       << " edges are shared by more than two faces; each edge must bound exactly two faces";
    fail(os.str());
  }
  if (border || nonManifold)
  {
    return false;
  }

  // Orientation: propagate over each connected component; flip the minority so that the fix
  // touches as few faces as possible. A conflict means the surface is not orientable.
  std::vector<signed char> flip(numTriangles, -1);
  vtkIdType flipped = 0;
  for (vtkIdType seed = 0; seed < numTriangles; ++seed)
  {
    if (flip[seed] >= 0)
    {
      continue;
    }
    std::vector<vtkIdType> component{ seed }, stack{ seed };
    flip[seed] = 0;
    while (!stack.empty())
    {
      const vtkIdType f = stack.back();
      stack.pop_back();
      for (const auto& nb : neighbours[f])
      {
        const signed char want = static_cast<signed char>(flip[f] ^ (nb.second ? 1 : 0));
        if (flip[nb.first] < 0)
        {
          flip[nb.first] = want;
          component.push_back(nb.first);
          stack.push_back(nb.first);
        }
        else if (flip[nb.first] != want)
        {
          return fail("the surface is not orientable (like a Moebius strip or a Klein bottle): "
                      "its faces cannot be oriented consistently, so it bounds no volume");
        }
      }
    }
    vtkIdType count = 0;
    for (vtkIdType f : component)
    {
      count += flip[f];
    }
    const bool invert = 2 * count > static_cast<vtkIdType>(component.size());
    for (vtkIdType f : component)
    {
      if ((flip[f] != 0) != invert)
      {
        std::swap(this->Triangles[f][1], this->Triangles[f][2]);
        ++flipped;
      }
    }
  }
  if (flipped)
  {
    std::ostringstream os;
    os << prefix << flipped
       << " faces were oriented against their neighbours and were flipped to match them";
    warnings.push_back(os.str());
  }

  // Bounds and enclosed volume (divergence theorem about the bounds' centre, for precision).
  for (int a = 0; a < 3; ++a)
  {
    this->Bounds[2 * a] = this->Bounds[2 * a + 1] = this->Points[a];
  }
  for (size_t v = 0; v < this->Points.size() / 3; ++v)
  {
    for (int a = 0; a < 3; ++a)
    {
      this->Bounds[2 * a] = std::min(this->Bounds[2 * a], this->Points[3 * v + a]);
      this->Bounds[2 * a + 1] = std::max(this->Bounds[2 * a + 1], this->Points[3 * v + a]);
    }
  }
  const double c[3] = { 0.5 * (this->Bounds[0] + this->Bounds[1]),
    0.5 * (this->Bounds[2] + this->Bounds[3]), 0.5 * (this->Bounds[4] + this->Bounds[5]) };
  double volume = 0.0;
  for (const auto& f : this->Triangles)
  {
    double q[3][3];
    for (int k = 0; k < 3; ++k)
    {
      for (int a = 0; a < 3; ++a)
      {
        q[k][a] = this->Points[3 * f[k] + a] - c[a];
      }
    }
    volume += (q[0][0] * (q[1][1] * q[2][2] - q[1][2] * q[2][1]) -
                q[0][1] * (q[1][0] * q[2][2] - q[1][2] * q[2][0]) +
                q[0][2] * (q[1][0] * q[2][1] - q[1][1] * q[2][0])) /
      6.0;
  }
  if (!(std::abs(volume) > 0.0))
  {
    return fail("the surface encloses no volume");
  }
  if (volume < 0.0)
  {
    for (auto& f : this->Triangles)
    {
      std::swap(f[1], f[2]);
    }
    volume = -volume;
    warnings.push_back(prefix +
      "the mesh was inside out (normals pointing inwards, negative volume); all faces were "
      "flipped");
  }
  this->Volume = volume;

  // CGAL surface: vertex-manifoldness, self-intersections, and the robust point classifier.
  const double scale = ClassifierScale(this->Points);
  if (scale == 0.0)
  {
    return fail("the coordinates span more than 308 orders of magnitude (a non-zero "
                "|coordinate| below 2.2e-308 times the largest): the inside test scales the "
                "mesh into +-1 exactly and would round the smallest; snap tiny coordinates to 0");
  }
  std::vector<Point3> cgalPoints;
  cgalPoints.reserve(this->Points.size() / 3);
  for (size_t v = 0; v < this->Points.size() / 3; ++v)
  {
    const double* x = &this->Points[3 * v];
    cgalPoints.emplace_back(x[0] * scale, x[1] * scale, x[2] * scale);
  }
  std::vector<std::array<std::size_t, 3>> polygons;
  polygons.reserve(this->Triangles.size());
  for (const auto& f : this->Triangles)
  {
    polygons.push_back({ static_cast<std::size_t>(f[0]), static_cast<std::size_t>(f[1]),
      static_cast<std::size_t>(f[2]) });
  }
  if (!PMP::is_polygon_soup_a_polygon_mesh(polygons))
  {
    return fail("the mesh is not a 2-manifold at some vertex (surfaces touching at a single "
                "point); separate them so every vertex has a single fan of faces");
  }
  this->Impl.reset(new Internals);
  this->Impl->Scale = scale;
  PMP::polygon_soup_to_polygon_mesh(cgalPoints, polygons, this->Impl->Surface);
  if (checkSelfIntersections && PMP::does_self_intersect(this->Impl->Surface))
  {
    this->Impl.reset();
    return fail("the surface intersects itself (or two of its parts intersect), so inside and "
                "outside are ambiguous; repair it (e.g. "
                "CGAL::Polygon_mesh_processing::autorefine) or split it into separate inputs");
  }
  this->Impl->Side.reset(new SideOf(this->Impl->Surface));
#ifndef CGAL_HAS_THREADS
  // Without CGAL's thread support the lazy AABB-tree build is not locked: build it now, while
  // single-threaded (a query inside the bounding box triggers it).
  this->Classify(c);
#endif
  return true;
}

//------------------------------------------------------------------------------
bool PreparedMesh::CheckPointIds(vtkPolyData* input, std::string& why)
{
  const vtkIdType numPoints = input->GetNumberOfPoints();
  const std::pair<const char*, vtkCellArray*> kinds[] = { { "polygon", input->GetPolys() },
    { "triangle strip", input->GetStrips() }, { "line", input->GetLines() },
    { "vertex", input->GetVerts() } };
  for (const auto& kind : kinds)
  {
    if (!kind.second)
    {
      continue;
    }
    vtkIdType cell = 0;
    auto it = vtk::TakeSmartPointer(kind.second->NewIterator());
    for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell(), ++cell)
    {
      vtkIdType n;
      const vtkIdType* ids;
      it->GetCurrentCell(n, ids);
      for (vtkIdType v = 0; v < n; ++v)
      {
        if (ids[v] < 0 || ids[v] >= numPoints)
        {
          std::ostringstream os;
          os << kind.first << " cell " << cell << " refers to point id " << ids[v]
             << " but the mesh has " << numPoints << " points (valid ids: 0 to " << numPoints - 1
             << "); every cell must use existing points";
          why = os.str();
          return false;
        }
      }
    }
  }
  return true;
}

//------------------------------------------------------------------------------
void PreparedMesh::GetTriangleBounds(vtkIdType tri, double b[6]) const
{
  const auto& f = this->Triangles[tri];
  for (int a = 0; a < 3; ++a)
  {
    const double v0 = this->Points[3 * f[0] + a], v1 = this->Points[3 * f[1] + a],
                 v2 = this->Points[3 * f[2] + a];
    b[2 * a] = std::min(v0, std::min(v1, v2));
    b[2 * a + 1] = std::max(v0, std::max(v1, v2));
  }
}

//------------------------------------------------------------------------------
bool PreparedMesh::LineCrossings(
  const vtkIdType* candidates, size_t count, double y, double z, std::vector<Crossing>& out) const
{
  const Point2 q(y, z);
  const double* pts = this->Points.data();
  for (size_t n = 0; n < count; ++n)
  {
    const vtkIdType t = candidates[n];
    const auto& f = this->Triangles[t];
    const double* A = pts + 3 * f[0];
    const double* B = pts + 3 * f[1];
    const double* C = pts + 3 * f[2];
    // Quick rejection by the projected bounding box (exact comparisons of doubles).
    if ((y < A[1] && y < B[1] && y < C[1]) || (y > A[1] && y > B[1] && y > C[1]) ||
      (z < A[2] && z < B[2] && z < C[2]) || (z > A[2] && z > B[2] && z > C[2]))
    {
      continue;
    }
    const Point2 a(A[1], A[2]), b(B[1], B[2]), c(C[1], C[2]);
    const CGAL::Orientation oabc = CGAL::orientation(a, b, c);
    const CGAL::Orientation o1 = CGAL::orientation(a, b, q);
    const CGAL::Orientation o2 = CGAL::orientation(b, c, q);
    const CGAL::Orientation o3 = CGAL::orientation(c, a, q);
    if (oabc == CGAL::COLLINEAR)
    {
      // The triangle is parallel to x: the line lies in its plane iff q is on its projection
      // (a segment, q within its bounding box, checked above).
      if (o1 == CGAL::COLLINEAR && o2 == CGAL::COLLINEAR && o3 == CGAL::COLLINEAR)
      {
        return false;
      }
      continue;
    }
    const CGAL::Orientation opposite = -oabc;
    if (o1 == opposite || o2 == opposite || o3 == opposite)
    {
      continue; // strictly outside the projected triangle
    }
    if (o1 == CGAL::COLLINEAR || o2 == CGAL::COLLINEAR || o3 == CGAL::COLLINEAR)
    {
      return false; // through an edge or a vertex: parity is ambiguous
    }
    // Barycentric interpolation of x (the crossing is proper; only its position is rounded).
    auto area = [](const double* u, const double* v, double py, double pz)
    { return (v[1] - u[1]) * (pz - u[2]) - (v[2] - u[2]) * (py - u[1]); };
    const double wa = area(B, C, y, z), wb = area(C, A, y, z), wc = area(A, B, y, z);
    const double sum = wa + wb + wc;
    out.push_back({ (wa * A[0] + wb * B[0] + wc * C[0]) / sum, t });
  }
  return true;
}

//------------------------------------------------------------------------------
int PreparedMesh::SideAlongX(vtkIdType tri, const double p[3]) const
{
  const auto& f = this->Triangles[tri];
  const double* pts = this->Points.data();
  const Point3 a(pts[3 * f[0]], pts[3 * f[0] + 1], pts[3 * f[0] + 2]);
  const Point3 b(pts[3 * f[1]], pts[3 * f[1] + 1], pts[3 * f[1] + 2]);
  const Point3 c(pts[3 * f[2]], pts[3 * f[2] + 1], pts[3 * f[2] + 2]);
  const CGAL::Orientation o = CGAL::orientation(a, b, c, Point3(p[0], p[1], p[2]));
  if (o == CGAL::COPLANAR)
  {
    return 0;
  }
  // A point on the same line surely before the plane: x below every vertex of the triangle.
  const double xFar =
    std::min(pts[3 * f[0]], std::min(pts[3 * f[1]], pts[3 * f[2]])) - 1.0 - std::abs(p[0]);
  const CGAL::Orientation before = CGAL::orientation(a, b, c, Point3(xFar, p[1], p[2]));
  return o == before ? -1 : 1;
}

//------------------------------------------------------------------------------
double PreparedMesh::Classify(const double p[3]) const
{
  const double s = this->Impl->Scale;
  switch ((*this->Impl->Side)(Point3(p[0] * s, p[1] * s, p[2] * s)))
  {
    case CGAL::ON_BOUNDED_SIDE:
      return 1.0;
    case CGAL::ON_BOUNDARY:
      return 0.5;
    default:
      return 0.0;
  }
}

//------------------------------------------------------------------------------
bool PreparedMesh::TriangleTouchesBox(vtkIdType tri, const double box[6]) const
{
  const auto& f = this->Triangles[tri];
  const double* pts = this->Points.data();
  const Kernel::Triangle_3 t(Point3(pts[3 * f[0]], pts[3 * f[0] + 1], pts[3 * f[0] + 2]),
    Point3(pts[3 * f[1]], pts[3 * f[1] + 1], pts[3 * f[1] + 2]),
    Point3(pts[3 * f[2]], pts[3 * f[2] + 1], pts[3 * f[2] + 2]));
  const CGAL::Bbox_3 b(box[0], box[2], box[4], box[1], box[3], box[5]);
  return CGAL::do_intersect(t, b);
}

} // namespace refracta_voxelize
