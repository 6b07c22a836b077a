// vtkRefractaSurfaceSet, part 3: what the triangles that share a mesh point share. The point
// adjacency (SharedPoints) serves the glass's smooth corner normals (DescribeInterfaces) and the
// Lambertian corners' irradiance (LinkCorners; Documentation/Physics.md, "Surfaces in the view
// pass").
#include "vtkRefractaSurfaceSet.h"

#include "vtkPolyData.h"
#include "vtkRefractaSurfaceSetInternals.h"

#include "refracta_surfaces.cl" // the flattened layout, shared with the kernels

#include <algorithm>

namespace
{
// The texel of a triangle of subdivision n at its corner c (0: (u, v) = (0, 0), 1: (1, 0),
// 2: (0, 1)): the upright texel of cell (0, 0), (n - 1, 0) or (0, n - 1) in TexelIndex's layout.
int CornerTexel(int corner, int n)
{
  return corner == 0 ? 0 : (corner == 1 ? 2 * (n - 1) : n * n - 1);
}
}

//------------------------------------------------------------------------------
void vtkRefractaSurfaceSetDetail::SharedPoints::Build(
  vtkRefractaSurfaceSet* set, const vtkRefractaBVH* bvh, const std::vector<SourceTriangle>& sources)
{
  const int surfaces = set->GetNumberOfSurfaces();
  const vtkIdType triangles = bvh->GetNumberOfTriangles();
  const std::vector<vtkIdType>& order = bvh->GetTriangleOrder();
  const std::vector<double>& tri = bvh->GetTriangles();
  this->Offsets.assign(surfaces, {});
  this->Triangles.assign(surfaces, {});
  for (int s = 0; s < surfaces; ++s)
  {
    this->Offsets[s].assign(size_t(set->GetSurface(s)->GetNumberOfPoints()) + 1, 0);
  }
  // Counting sort: count the triangles at each point, sum, then place them.
  for (vtkIdType k = 0; k < triangles; ++k)
  {
    const SourceTriangle& source = sources[order[k]];
    for (vtkIdType p : source.Points)
    {
      ++this->Offsets[source.Surface][p + 1];
    }
  }
  std::vector<std::vector<vtkIdType>> next(surfaces);
  for (int s = 0; s < surfaces; ++s)
  {
    std::vector<vtkIdType>& o = this->Offsets[s];
    for (size_t p = 1; p < o.size(); ++p)
    {
      o[p] += o[p - 1];
    }
    this->Triangles[s].resize(size_t(o.back()));
    next[s].assign(o.begin(), o.end() - 1);
  }
  this->Faces.resize(3 * size_t(triangles));
  this->Areas.resize(triangles);
  for (vtkIdType k = 0; k < triangles; ++k)
  {
    const SourceTriangle& source = sources[order[k]];
    for (vtkIdType p : source.Points)
    {
      this->Triangles[source.Surface][next[source.Surface][p]++] = k;
    }
    Cross(&tri[9 * k], &this->Faces[3 * k]);
    this->Areas[k] = DoubledArea(&tri[9 * k]);
    Normalize(&this->Faces[3 * k]);
  }
}

//------------------------------------------------------------------------------
void vtkRefractaSurfaceSet::LinkCorners()
{
  using namespace vtkRefractaSurfaceSetDetail;
  const vtkRefractaBVH* bvh = this->Impl->BVH;
  const vtkIdType triangles = bvh->GetNumberOfTriangles();
  const std::vector<vtkIdType>& order = bvh->GetTriangleOrder();
  const SharedPoints& shared = this->Impl->Shared;
  const auto info = [&](vtkIdType k, int field)
  { return this->TriangleInfo[REFRACTA_TRIANGLE_INFO_INTS * k + field]; };
  this->CornerOffsets.assign(1, 0);
  this->CornerOffsets.reserve(3 * size_t(triangles) + 1);
  this->CornerTexels.clear();
  for (vtkIdType k = 0; k < triangles; ++k)
  {
    const SourceTriangle& source = this->Impl->Sources[order[k]];
    const bool lambertian = info(k, REFRACTA_TRIANGLE_INFO_KIND) == REFRACTA_SURFACE_LAMBERTIAN;
    for (int corner = 0; corner < 3; ++corner)
    {
      // The corner texel of every triangle of this surface at this point (this one included)
      // whose face is within the smoothing angle: a cube's edges keep their sides apart. A
      // dielectric triangle's corners link nothing.
      const vtkIdType p = source.Points[corner];
      if (lambertian)
      {
        shared.ForSmoothNeighbours(source.Surface, p, k,
          [&](vtkIdType j)
          {
            const SourceTriangle& other = this->Impl->Sources[order[j]];
            const int c = other.Points[0] == p ? 0 : (other.Points[1] == p ? 1 : 2);
            this->CornerTexels.push_back(info(j, REFRACTA_TRIANGLE_INFO_TEXEL) +
              CornerTexel(c, info(j, REFRACTA_TRIANGLE_INFO_SUBDIVISION)));
          });
      }
      this->CornerOffsets.push_back(static_cast<vtkIdType>(this->CornerTexels.size()));
    }
  }
}

//------------------------------------------------------------------------------
void vtkRefractaSurfaceSet::ComputeCornerIrradiance(
  const float* irradiance, std::vector<float>& corners) const
{
  const vtkIdType count = static_cast<vtkIdType>(this->CornerOffsets.size()) - 1;
  corners.assign(3 * size_t(std::max<vtkIdType>(count, 0)), 0.0f);
  for (vtkIdType k = 0; k < count; ++k)
  {
    // Area-weighted: total flux over total area, the estimate of the smallest variance when
    // each texel's flux is a photon count.
    double sum[3] = { 0, 0, 0 }, area = 0;
    for (vtkIdType i = this->CornerOffsets[k]; i < this->CornerOffsets[k + 1]; ++i)
    {
      const int texel = this->CornerTexels[i];
      const double a = this->TexelAreas[texel];
      for (int ch = 0; ch < 3; ++ch)
      {
        sum[ch] += a * irradiance[3 * size_t(texel) + ch];
      }
      area += a;
    }
    for (int ch = 0; ch < 3 && area > 0; ++ch)
    {
      corners[3 * size_t(k) + ch] = static_cast<float>(sum[ch] / area);
    }
  }
}
