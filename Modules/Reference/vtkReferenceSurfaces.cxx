#include "vtkReferenceSurfaces.h"

#include "vtkReferenceMedium.h"
#include "vtkRefractaBVH.h"
#include "vtkRefractaSurfaceSet.h"

#include "refracta_surfaces.cl"

#include <algorithm>
#include <cmath>

namespace refracta
{
namespace reference
{
std::string Surfaces::Load(vtkRefractaSurfaceSet* set, const Medium& m)
{
  Set = set;
  BVH = nullptr;
  if (!set || set->GetNumberOfSurfaces() == 0)
  {
    return std::string();
  }
  if (!set->Build())
  {
    return "the surface set could not be built (more than 2^31 - 1 triangles or texels)";
  }
  if (set->GetNumberOfTriangles() == 0 || !set->GetBVH())
  {
    return std::string(); // every surface rejected or degenerate: the set reported why
  }
  BVH = set->GetBVH();
  // Grid-local -> world (the frame of the BVH's host traversal): a rotation and a translation.
  const double zero[3] = { 0, 0, 0 };
  double t[3];
  m.Grid->LocalToWorldPoint(zero, t);
  Translation = Vec3(t[0], t[1], t[2]);
  for (int a = 0; a < 3; ++a)
  {
    double e[3] = { 0, 0, 0 }, c[3];
    e[a] = 1;
    m.Grid->LocalToWorldVector(e, c);
    for (int r = 0; r < 3; ++r)
    {
      Rotation[3 * r + a] = c[r];
    }
  }
  double b[6];
  BVH->GetBounds(b);
  const double size = std::max(m.Diagonal,
    std::sqrt((b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) +
      (b[5] - b[4]) * (b[5] - b[4])));
  Offset = 1e-9 * size;
  return std::string();
}

Vec3 Surfaces::RotateToWorld(const Vec3& v) const
{
  const double* R = Rotation;
  return Vec3(R[0] * v.x + R[1] * v.y + R[2] * v.z, R[3] * v.x + R[4] * v.y + R[5] * v.z,
    R[6] * v.x + R[7] * v.y + R[8] * v.z);
}

Vec3 Surfaces::ToWorld(const Vec3& p) const
{
  return RotateToWorld(p) + Translation;
}

bool Surfaces::Closest(const Vec3& o, const Vec3& d, double tMax, SurfaceHit& hit) const
{
  if (!BVH || !(tMax > 0))
  {
    return false;
  }
  const Vec3 ob = ToWorld(o), db = RotateToWorld(d);
  const double origin[3] = { ob.x, ob.y, ob.z }, dir[3] = { db.x, db.y, db.z };
  double h[3];
  const vtkIdType tri = BVH->IntersectRay(origin, dir, tMax, h);
  if (tri < 0)
  {
    return false;
  }
  hit.T = h[0];
  hit.Triangle = tri;
  hit.U = h[1];
  hit.V = h[2];
  return true;
}

Vec3 Surfaces::Normal(const SurfaceHit& hit) const
{
  const double* p = &BVH->GetTriangles()[9 * static_cast<size_t>(hit.Triangle)];
  const Vec3 e1(p[3] - p[0], p[4] - p[1], p[5] - p[2]), e2(p[6] - p[0], p[7] - p[1], p[8] - p[2]);
  const Vec3 nb = glm::cross(e1, e2);
  // The BVH's stored triangles are relative to its frame origin (a translation: edges are world
  // vectors); world -> grid-local is the transpose of the rotation.
  const double* R = Rotation;
  return Normalized(Vec3(R[0] * nb.x + R[3] * nb.y + R[6] * nb.z,
    R[1] * nb.x + R[4] * nb.y + R[7] * nb.z, R[2] * nb.x + R[5] * nb.y + R[8] * nb.z));
}

Vec3 Surfaces::Albedo(const SurfaceHit& hit) const
{
  const int* info =
    &Set->GetTriangleInfo()[REFRACTA_TRIANGLE_INFO_INTS * static_cast<size_t>(hit.Triangle)];
  const int n = info[REFRACTA_TRIANGLE_INFO_SUBDIVISION];
  const size_t texel = static_cast<size_t>(info[REFRACTA_TRIANGLE_INFO_TEXEL]) +
    vtkRefractaSurfaceSet::TexelIndex(static_cast<float>(hit.U), static_cast<float>(hit.V), n);
  const float* a = &Set->GetTexelAlbedo()[3 * texel];
  return Vec3(a[0], a[1], a[2]);
}
} // namespace reference
} // namespace refracta
