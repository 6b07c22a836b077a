// The opaque surfaces of a refracta-render scene ("scene.surfaces"): triangle meshes from files
// (.ply, .stl, .obj, .vtp) or procedural planes, boxes and spheres, each with a Lambertian
// material (an albedo, optionally a checker over the surface's texture coordinates). Read and
// validated here into plain descriptions; MakeSurfaceSet turns them into the pipeline's
// vtkRefractaSurfaceSet.
#ifndef RefractaSceneSurfaces_h
#define RefractaSceneSurfaces_h

#include "RefractaSceneJson.h"

#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <array>
#include <string>
#include <vector>

class vtkRefractaSurfaceSet;

namespace RefractaRender
{
/// The most triangles all surfaces of a scene may hold together: 2^22 = 4,194,304 (the BVH and
/// its build then take some 0.5 GB and several seconds; a scene above it is refused, with the
/// count, rather than left to run out of memory).
constexpr long long MaximumSurfaceTriangles = 1LL << 22;

/// A surface's material as written in the scene (albedo RGB in [0, 1]; the checker alternates
/// Color1 and Color2 over Squares[0] x Squares[1] squares of the texture coordinates).
struct SurfaceMaterialDescription
{
  std::array<double, 3> Albedo = { { 0.8, 0.8, 0.8 } };
  bool Checker = false;
  std::array<int, 2> Squares = { { 8, 8 } };
  std::array<double, 3> Color1 = { { 0.8, 0.8, 0.8 } };
  std::array<double, 3> Color2 = { { 0.2, 0.2, 0.2 } };
};

/// One surface: its scene path ("scene.surfaces[2]"), kind ("file", "plane", "box", "sphere"),
/// triangulated world-space mesh and material.
struct SceneSurface
{
  std::string Path;
  std::string Kind;
  vtkSmartPointer<vtkPolyData> Mesh;
  long long Triangles = 0;
  SurfaceMaterialDescription Material;
};

/// Reads and validates "scene.surfaces" (files relative to `base`); empty where the key is
/// absent. Throws SceneError naming the key path for a bad entry: a missing or unreadable file,
/// a mesh with non-finite coordinates or without a triangle of non-zero area, a zero normal, a
/// non-positive size or radius, or more than MaximumSurfaceTriangles triangles in all. Open
/// meshes are accepted: surfaces are two-sided (a plane is open).
std::vector<SceneSurface> ReadSurfaces(const json& scene, const std::string& base);

/// The plane of {"center", "normal", "size": [w, h]}: a rectangle w along u and h along v, where
/// u is the world axis least aligned with the normal (x first on ties) made perpendicular to it
/// and v = normal x u (so u, v, normal are right-handed; a floor with normal +y has u = +x,
/// v = -z). Texture coordinates run 0..1 along u and v.
vtkSmartPointer<vtkPolyData> MakePlane(
  const double center[3], const double normal[3], double width, double height);

/// The pipeline's surface set for `surfaces` (meshes in world coordinates, no matrices); nullptr
/// when there are none.
vtkSmartPointer<vtkRefractaSurfaceSet> MakeSurfaceSet(const std::vector<SceneSurface>& surfaces);

/// The report's "surfaces": count, triangles, per surface its kind and triangles, and from the
/// built set (where there is one) its texels, texel size, dropped triangles and build seconds.
json SurfacesReport(const std::vector<SceneSurface>& surfaces, vtkRefractaSurfaceSet* set);
}

#endif
