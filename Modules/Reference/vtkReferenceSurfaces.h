/**
 * Internal to RefractaReference (a private header: not wrapped, not installed). The opaque
 * surfaces of the reference renderer: a built vtkRefractaSurfaceSet seen from the grid-local frame.
 * Rays are intersected with the set's host BVH (vtkRefractaBVH: double precision, the watertight
 * test of Woop, Benthin and Wald) after mapping them to world coordinates (the grid-local frame
 * differs from the world by a rotation and a translation, so distances along a ray are the same in
 * both). A hit's albedo is the set's baked per-texel albedo
 * at the texel of its barycentrics, looked up with the set's own texel function, so the reference
 * and the OpenCL passes see the same colour at the same point.
 */
#ifndef vtkReferenceSurfaces_h
#define vtkReferenceSurfaces_h

#include "vtkReferenceMath.h"

#include "vtkSmartPointer.h"
#include "vtkType.h" // for vtkIdType

#include <string>

class vtkRefractaSurfaceSet;
class vtkRefractaBVH;

namespace refracta
{
namespace reference
{
struct Medium;

// A ray-surface hit: distance along the (unit) ray, BVH position of the triangle, barycentric
// weights of its second and third vertex.
struct SurfaceHit
{
  double T = Inf;
  vtkIdType Triangle = -1;
  double U = 0, V = 0;
};

struct Surfaces
{
  vtkSmartPointer<vtkRefractaSurfaceSet> Set;
  const vtkRefractaBVH* BVH = nullptr;
  // World point = Rotation * local + Translation (row-major 3 x 3).
  double Rotation[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  Vec3 Translation = Vec3(0.0);
  // Distance (world units) a ray leaving a surface starts off it, along the normal on its side:
  // 1e-9 of the scene's size, far above double rounding of the hit point and far below any
  // feature the renderer resolves.
  double Offset = 0;

  // Builds the set (vtkRefractaSurfaceSet::Build) and takes its BVH. An empty set, or none,
  // leaves this empty. Returns an error message when the set cannot be built.
  std::string Load(vtkRefractaSurfaceSet* set, const Medium& m);

  bool Empty() const { return BVH == nullptr; }

  // Closest hit of the grid-local ray o + t d (d unit) with t in (0, tMax).
  bool Closest(const Vec3& o, const Vec3& d, double tMax, SurfaceHit& hit) const;

  // Unit geometric normal of the hit's triangle in the grid-local frame (either orientation:
  // surfaces are two-sided).
  Vec3 Normal(const SurfaceHit& hit) const;

  // RGB albedo of the texel holding the hit.
  Vec3 Albedo(const SurfaceHit& hit) const;

  // Whether the hit's triangle is a dielectric interface (glass) rather than an opaque surface.
  bool IsDielectric(const SurfaceHit& hit) const;

  // Unit shading normal of a hit (the triangle's corner normals interpolated at its
  // barycentrics, grid-local, on the side of the winding normal Normal() returns).
  Vec3 ShadingNormal(const SurfaceHit& hit) const;

  // A path arriving along unit d at a dielectric hit at x: one Fresnel choice
  // (vtkRefractaDielectric::Sample with xi, the same optics as the OpenCL passes, in double).
  // Returns the new unit direction; x is moved off the surface onto the side it leaves to.
  Vec3 Interface(const SurfaceHit& hit, const Vec3& d, double xi, Vec3& x) const;

  // Glass bodies (Documentation/Physics.md "Glass bodies"): the surface whose inside medium
  // (vtkRefractaSurfaceSet::GetSurfaceBodies) a path is in, or -1 (the grid).
  // The body a path at x along the unit d starts in: its first hit is a surface with an inside
  // medium met from inside (closed meshes: the innermost body around x), else -1.
  int StartBody(const Vec3& x, const Vec3& d) const;
  // The body after a path arriving along dIn in `body` left a dielectric hit along dOut:
  // refracted into a surface's inside: that surface (if it has a medium, else -1); refracted
  // out: -1; reflected: `body`.
  int BodyAfter(const SurfaceHit& hit, const Vec3& dIn, const Vec3& dOut, int body) const;
  // The medium of body b >= 0: REFRACTA_SURFACE_BODY_FLOATS floats (extinction RGB, 1, albedo
  // RGB, g, emission RGB, 0); and the refractive index inside it.
  const float* BodyMedium(int b) const;
  double BodyIndex(int b) const;

  // Where a ray leaving the surface point x in direction w starts: x moved by Offset along the
  // normal n, towards the side w points to.
  Vec3 Leave(const Vec3& x, const Vec3& n, const Vec3& w) const
  {
    return x + (glm::dot(n, w) >= 0 ? Offset : -Offset) * n;
  }

private:
  Vec3 ToWorld(const Vec3& local) const;
  Vec3 RotateToWorld(const Vec3& local) const;
};
} // namespace reference
} // namespace refracta

#endif
