#include "vtkReferenceSurfaces.h"

#include "vtkReferenceMedium.h"
#include "vtkRefractaBVH.h"
#include "vtkRefractaDielectric.h"
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
bool Surfaces::IsDielectric(const SurfaceHit& hit) const
{
  return Set->GetTriangleInfo()[REFRACTA_TRIANGLE_INFO_INTS * static_cast<size_t>(hit.Triangle) +
           REFRACTA_TRIANGLE_INFO_KIND] == REFRACTA_SURFACE_DIELECTRIC;
}

Vec3 Surfaces::ShadingNormal(const SurfaceHit& hit) const
{
  const float* c = &Set->GetTriangleNormals()[12 * static_cast<size_t>(hit.Triangle)];
  const double w[3] = { 1 - hit.U - hit.V, hit.U, hit.V };
  Vec3 nb(0.0);
  for (int k = 0; k < 3; ++k)
  {
    nb += w[k] * Vec3(c[4 * k], c[4 * k + 1], c[4 * k + 2]);
  }
  // Corner normals are world vectors; world -> grid-local is the transpose of the rotation.
  const double* R = Rotation;
  return Normalized(Vec3(R[0] * nb.x + R[3] * nb.y + R[6] * nb.z,
    R[1] * nb.x + R[4] * nb.y + R[7] * nb.z, R[2] * nb.x + R[5] * nb.y + R[8] * nb.z));
}

int Surfaces::StartBody(const Vec3& x, const Vec3& d) const
{
  SurfaceHit hit;
  if (this->Empty() || !this->Closest(x, d, Inf, hit) || !this->IsDielectric(hit) ||
    glm::dot(d, this->Normal(hit)) <= 0)
  {
    return -1;
  }
  return this->BodyAfter(hit, -d, -d, -1); // as if refracted into it from outside
}

int Surfaces::BodyAfter(const SurfaceHit& hit, const Vec3& dIn, const Vec3& dOut, int body) const
{
  const Vec3 ng = this->Normal(hit); // the winding normal: outwards
  const double in = glm::dot(dIn, ng), out = glm::dot(dOut, ng);
  if ((in < 0) != (out < 0))
  {
    return body; // reflected: on the same side
  }
  if (in >= 0)
  {
    return -1; // refracted out
  }
  const int surface =
    Set->GetTriangleInfo()[REFRACTA_TRIANGLE_INFO_INTS * static_cast<size_t>(hit.Triangle) +
      REFRACTA_TRIANGLE_INFO_SURFACE];
  return this->BodyMedium(surface)[3] > 0.5f ? surface : -1;
}

const float* Surfaces::BodyMedium(int b) const
{
  return &Set->GetSurfaceBodies()[REFRACTA_SURFACE_BODY_FLOATS * static_cast<size_t>(b)];
}

double Surfaces::BodyIndex(int b) const
{
  return Set->GetSurfaceInterfaces()[REFRACTA_SURFACE_INTERFACE_FLOATS * static_cast<size_t>(b)];
}

Vec3 Surfaces::Interface(const SurfaceHit& hit, const Vec3& d, double xi, Vec3& x) const
{
  const int surface =
    Set->GetTriangleInfo()[REFRACTA_TRIANGLE_INFO_INTS * static_cast<size_t>(hit.Triangle) +
      REFRACTA_TRIANGLE_INFO_SURFACE];
  const float* indices =
    &Set->GetSurfaceInterfaces()[REFRACTA_SURFACE_INTERFACE_FLOATS * static_cast<size_t>(surface)];
  const Vec3 ng = Normal(hit), ns = ShadingNormal(hit);
  const double dd[3] = { d.x, d.y, d.z }, g[3] = { ng.x, ng.y, ng.z }, s[3] = { ns.x, ns.y, ns.z };
  const vtkRefractaDielectric::Event e =
    vtkRefractaDielectric::Sample(dd, g, s, indices[0], indices[1], xi);
  const Vec3 out(e.Direction[0], e.Direction[1], e.Direction[2]);
  x = Leave(x, ng, out);
  return out;
}
} // namespace reference
} // namespace refracta
