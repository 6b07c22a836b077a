#include "RefractaSceneSurfaces.h"

#include "RefractaSceneMedium.h"

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkPlaneSource.h"
#include "vtkPoints.h"
#include "vtkRefractaSurfaceMaterial.h"
#include "vtkRefractaSurfaceSet.h"
#include "vtkTriangle.h"
#include "vtkTriangleFilter.h"

#include <cmath>
#include <sstream>

namespace RefractaRender
{
namespace
{
std::array<double, 3> Colour(const json& object, const std::string& key, const std::string& path,
  const std::array<double, 3>& fallback)
{
  auto v = Vector(object, key, path, { fallback[0], fallback[1], fallback[2] }, 3, 0.0, 1.0);
  return { { v[0], v[1], v[2] } };
}

SurfaceMaterialDescription ReadSurfaceMaterial(const json& m, const std::string& p)
{
  CheckKeys(m, p, { "albedo", "checker" });
  SurfaceMaterialDescription material;
  material.Albedo = Colour(m, "albedo", p, material.Albedo);
  if (m.contains("checker"))
  {
    const json& c = m["checker"];
    const std::string cp = p + ".checker";
    CheckKeys(c, cp, { "squares", "color1", "color2" });
    material.Checker = true;
    auto squares = Vector(c, "squares", cp, { 8, 8 }, 2, 1, 4096);
    material.Squares = { { static_cast<int>(squares[0]), static_cast<int>(squares[1]) } };
    material.Color1 = Colour(c, "color1", cp, material.Color1);
    material.Color2 = Colour(c, "color2", cp, material.Color2);
  }
  return material;
}

vtkSmartPointer<vtkPolyData> ReadPlane(const json& plane, const std::string& p)
{
  CheckKeys(plane, p, { "center", "normal", "size" });
  auto c = Vector(plane, "center", p, { 0, 0, 0 }, 3, -1e30, 1e30);
  auto n = Vector(plane, "normal", p, { 0, 1, 0 }, 3, -1e30, 1e30);
  if (vtkMath::Norm(n.data()) <= 0.0)
  {
    Fail(p + ".normal", "must not be the zero vector");
  }
  auto size = Vector(plane, "size", p, { 1, 1 }, 2, 1e-30, 1e30);
  return MakePlane(c.data(), n.data(), size[0], size[1]);
}

// Triangles of `mesh` (polygons and strips; verts and lines are not surfaces), the scene path
// named in failures.
vtkSmartPointer<vtkPolyData> Triangulate(vtkPolyData* mesh)
{
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputData(mesh);
  triangles->PassVertsOff();
  triangles->PassLinesOff();
  triangles->Update();
  return triangles->GetOutput();
}

// Fails unless at least one triangle has a non-zero area (a file's points are checked finite by
// ReadMeshFile, the generated shapes' by their parameters' ranges).
void CheckMesh(vtkPolyData* mesh, const std::string& path, const std::string& what)
{
  vtkPoints* points = mesh->GetPoints();
  auto it = vtk::TakeSmartPointer(mesh->GetPolys()->NewIterator());
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
  {
    vtkIdList* ids = it->GetCurrentCell();
    double a[3], b[3], c[3];
    points->GetPoint(ids->GetId(0), a);
    points->GetPoint(ids->GetId(1), b);
    points->GetPoint(ids->GetId(2), c);
    if (vtkTriangle::TriangleArea(a, b, c) > 0.0)
    {
      return;
    }
  }
  Fail(path, what + " has no triangle of non-zero area (a degenerate mesh)");
}

SceneSurface ReadSurface(const json& entry, const std::string& path, const std::string& base)
{
  CheckKeys(entry, path, { "file", "plane", "box", "sphere", "material" });
  SceneSurface surface;
  surface.Path = path;
  for (const char* kind : { "file", "plane", "box", "sphere" })
  {
    if (entry.contains(kind))
    {
      if (!surface.Kind.empty())
      {
        Fail(path, "needs exactly one of 'file', 'plane', 'box' or 'sphere'");
      }
      surface.Kind = kind;
    }
  }
  if (surface.Kind.empty())
  {
    Fail(path, "needs exactly one of 'file', 'plane', 'box' or 'sphere'");
  }
  const std::string p = path + "." + surface.Kind;
  const json& description = entry[surface.Kind];
  vtkSmartPointer<vtkPolyData> mesh;
  std::string what = "the " + surface.Kind;
  if (surface.Kind == "file")
  {
    mesh = ReadMeshFile(description, p, base);
    what = "'" + Resolve(base, description.get<std::string>()) + "'";
  }
  else if (surface.Kind == "plane")
  {
    mesh = ReadPlane(description, p);
  }
  else if (surface.Kind == "box")
  {
    mesh = ReadBox(description, p);
  }
  else
  {
    mesh = ReadSphere(description, p);
  }
  surface.Mesh = Triangulate(mesh);
  CheckMesh(surface.Mesh, p, what);
  surface.Triangles = surface.Mesh->GetNumberOfPolys();
  surface.Material =
    ReadSurfaceMaterial(entry.value("material", json::object()), path + ".material");
  return surface;
}
}

std::vector<SceneSurface> ReadSurfaces(const json& scene, const std::string& base)
{
  std::vector<SceneSurface> surfaces;
  if (!scene.contains("surfaces"))
  {
    return surfaces;
  }
  const json& list = scene["surfaces"];
  if (!list.is_array())
  {
    Fail("scene.surfaces", "must be an array of surfaces");
  }
  long long triangles = 0;
  for (size_t i = 0; i < list.size(); ++i)
  {
    const std::string path = "scene.surfaces[" + std::to_string(i) + "]";
    surfaces.push_back(ReadSurface(list[i], path, base));
    triangles += surfaces.back().Triangles;
    if (triangles > MaximumSurfaceTriangles)
    {
      std::ostringstream os;
      os << "the surfaces up to this one hold " << triangles
         << " triangles, more than the limit of " << MaximumSurfaceTriangles
         << " per scene (decimate the mesh, e.g. vtkQuadricDecimation)";
      Fail(path, os.str());
    }
  }
  return surfaces;
}

vtkSmartPointer<vtkPolyData> MakePlane(
  const double center[3], const double normal[3], double width, double height)
{
  double n[3] = { normal[0], normal[1], normal[2] };
  vtkMath::Normalize(n);
  int least = 0;
  for (int a = 1; a < 3; ++a)
  {
    least = std::abs(n[a]) < std::abs(n[least]) ? a : least;
  }
  double u[3] = { 0, 0, 0 }, v[3];
  u[least] = 1.0;
  const double along = vtkMath::Dot(u, n);
  for (int a = 0; a < 3; ++a)
  {
    u[a] -= along * n[a];
  }
  vtkMath::Normalize(u);
  vtkMath::Cross(n, u, v);
  double origin[3], p1[3], p2[3];
  for (int a = 0; a < 3; ++a)
  {
    origin[a] = center[a] - 0.5 * width * u[a] - 0.5 * height * v[a];
    p1[a] = origin[a] + width * u[a];
    p2[a] = origin[a] + height * v[a];
  }
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(origin);
  plane->SetPoint1(p1);
  plane->SetPoint2(p2);
  plane->Update();
  return Triangulate(plane->GetOutput());
}

vtkSmartPointer<vtkRefractaSurfaceSet> MakeSurfaceSet(const std::vector<SceneSurface>& surfaces)
{
  if (surfaces.empty())
  {
    return nullptr;
  }
  auto set = vtkSmartPointer<vtkRefractaSurfaceSet>::New();
  for (const SceneSurface& s : surfaces)
  {
    vtkNew<vtkRefractaSurfaceMaterial> material;
    material->SetAlbedo(s.Material.Albedo.data());
    material->SetUseChecker(s.Material.Checker);
    material->SetCheckerSquares(s.Material.Squares[0], s.Material.Squares[1]);
    material->SetCheckerColor1(s.Material.Color1.data());
    material->SetCheckerColor2(s.Material.Color2.data());
    set->AddSurface(s.Mesh, material);
  }
  return set;
}

json SurfacesReport(const std::vector<SceneSurface>& surfaces, vtkRefractaSurfaceSet* set)
{
  json report;
  long long triangles = 0;
  json list = json::array();
  for (const SceneSurface& s : surfaces)
  {
    triangles += s.Triangles;
    list.push_back(
      { { "kind", s.Kind }, { "triangles", s.Triangles }, { "checker", s.Material.Checker } });
  }
  report["count"] = surfaces.size();
  report["triangles"] = triangles;
  report["list"] = list;
  if (set)
  {
    report["texels"] = set->GetNumberOfTexels();
    report["texel_size"] = set->GetEffectiveTexelSize();
    report["dropped_triangles"] = set->GetNumberOfDroppedTriangles();
    report["build_seconds"] = set->GetBuildSeconds();
    // The medium's exact interfaces, which the pipeline added to the scene's surfaces.
    report["interface_surfaces"] = set->GetNumberOfNonEmptyDielectricSurfaces();
    report["interface_triangles"] = set->GetNumberOfDielectricTriangles();
  }
  return report;
}
}
