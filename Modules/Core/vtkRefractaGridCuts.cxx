#include "vtkRefractaGridCuts.h"

#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkRefractaBVH.h"
#include "vtkRefractaSurfaceSet.h"
#include "vtkSMPTools.h"

#include "refracta_surfaces.cl" // the triangle info layout, shared with the kernels

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <new>
#include <utility>
#include <vector>

vtkStandardNewMacro(vtkRefractaGridCuts);

namespace
{
// Whether the segment from p along axis a, `length` long, meets triangle v (a touch included; a
// segment in the triangle's plane does not cut it).
bool SegmentMeetsTriangle(const double p[3], int a, double length, const double v[3][3])
{
  double e1[3], e2[3], d[3] = { 0, 0, 0 }, w[3];
  d[a] = length;
  for (int c = 0; c < 3; ++c)
  {
    e1[c] = v[1][c] - v[0][c];
    e2[c] = v[2][c] - v[0][c];
    w[c] = p[c] - v[0][c];
  }
  double h[3], q[3];
  vtkMath::Cross(d, e2, h);
  const double det = vtkMath::Dot(e1, h);
  const double scale = vtkMath::Norm(e1) * vtkMath::Norm(e2) * length;
  if (!(std::fabs(det) > 1e-12 * scale))
  {
    return false; // parallel
  }
  const double tolerance = 1e-9;
  // A touch within the float rounding of the set's vertices (stored relative to the BVH's frame
  // origin in float) counts: a wall through voxel centres cuts the links on both sides of them.
  const double touch = 1e-5;
  const double u = vtkMath::Dot(w, h) / det;
  vtkMath::Cross(w, e1, q);
  const double s = vtkMath::Dot(d, q) / det;
  const double t = vtkMath::Dot(e2, q) / det;
  return u >= -tolerance && s >= -tolerance && u + s <= 1 + tolerance && t >= -touch &&
    t <= 1 + touch;
}

// Triangle v's plane in voxel coordinates u = local / spacing: n . u + d = 0, n unit (the voxels
// near the triangle are within |n_x| + |n_y| + |n_z| of it). False for a degenerate triangle.
bool PlaneInVoxels(const double v[3][3], const double spacing[3], float plane[4])
{
  double e1[3], e2[3], n[3];
  for (int c = 0; c < 3; ++c)
  {
    e1[c] = v[1][c] - v[0][c];
    e2[c] = v[2][c] - v[0][c];
  }
  vtkMath::Cross(e1, e2, n);
  // n . x = n . v0 with x = spacing * u: (n * spacing) . u = n . v0.
  const double offset = vtkMath::Dot(n, v[0]);
  for (int c = 0; c < 3; ++c)
  {
    n[c] *= spacing[c];
  }
  const double norm = vtkMath::Norm(n);
  if (!(norm > 0.0))
  {
    return false;
  }
  for (int c = 0; c < 3; ++c)
  {
    plane[c] = static_cast<float>(n[c] / norm);
  }
  plane[3] = static_cast<float>(-offset / norm);
  return true;
}

// The voxels whose box an opaque triangle may cross, each with those triangles (the rows of the
// sorted (voxel, triangle) pairs from First[slot] on), and the deposits' rule on them
// (photon_sided_voxel's, in double): a segment within a few boxes can only meet the triangles
// noted for them.
class BoxTriangleIndex
{
public:
  BoxTriangleIndex(std::vector<std::pair<vtkIdType, vtkIdType>>& pairs,
    const std::vector<double>& opaque, const int dims[3], const double spacing[3])
    : Pairs(pairs)
    , Opaque(opaque)
    , Dims(dims)
    , Spacing(spacing)
  {
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
    for (size_t k = 0; k < pairs.size(); ++k)
    {
      if (k == 0 || pairs[k].first != pairs[k - 1].first)
      {
        this->Crossed.push_back(pairs[k].first);
        this->First.push_back(static_cast<vtkIdType>(k));
      }
    }
    this->First.push_back(static_cast<vtkIdType>(pairs.size()));
    // Each triangle's plane n . x + d = 0 (n unnormalised): a segment with both ends clearly on
    // one side cannot meet it, which spares most of the exact tests.
    this->Planes.resize(opaque.size() / 9 * 4);
    for (size_t t = 0; t < this->Planes.size() / 4; ++t)
    {
      const double* v = opaque.data() + 9 * t;
      const double e1[3] = { v[3] - v[0], v[4] - v[1], v[5] - v[2] };
      const double e2[3] = { v[6] - v[0], v[7] - v[1], v[8] - v[2] };
      double* q = this->Planes.data() + 4 * t;
      vtkMath::Cross(e1, e2, q);
      q[3] = -vtkMath::Dot(q, v);
    }
  }

  size_t GetNumberOfBoxes() const { return this->Crossed.size(); }
  vtkIdType GetVoxel(size_t slot) const { return this->Crossed[slot]; }

  // The voxel the point at `offset` from the centre of the box in `slot` (voxel units) deposits
  // into: its own when no triangle separates it from its centre, else the nearest of the 26
  // around whose centre none separates from it (ties in index order), else its own.
  vtkIdType Owner(const double offset[3], size_t slot) const
  {
    const vtkIdType own = this->Crossed[slot];
    const int* dims = this->Dims;
    const int cell[3] = { static_cast<int>(own % dims[0]),
      static_cast<int>((own / dims[0]) % dims[1]),
      static_cast<int>(own / (vtkIdType(dims[0]) * dims[1])) };
    const double p[3] = { cell[0] + offset[0], cell[1] + offset[1], cell[2] + offset[2] };
    if (!this->Separated(p, cell, slot, cell))
    {
      return own;
    }
    int tried = 1 << 13;
    for (int round = 0; round < 26; ++round)
    {
      int pick = -1;
      double nearest = std::numeric_limits<double>::infinity();
      for (int k = 0; k < 27; ++k)
      {
        const int to[3] = { cell[0] + k % 3 - 1, cell[1] + (k / 3) % 3 - 1, cell[2] + k / 9 - 1 };
        bool inGrid = true;
        double d = 0;
        for (int c = 0; c < 3; ++c)
        {
          inGrid = inGrid && to[c] >= 0 && to[c] < dims[c];
          d += (to[c] - p[c]) * (to[c] - p[c]);
        }
        if (!((tried >> k) & 1) && inGrid && d < nearest)
        {
          nearest = d;
          pick = k;
        }
      }
      if (pick < 0)
      {
        break;
      }
      tried |= 1 << pick;
      const int to[3] = { cell[0] + pick % 3 - 1, cell[1] + (pick / 3) % 3 - 1,
        cell[2] + pick / 9 - 1 };
      if (!this->Separated(p, cell, slot, to))
      {
        return this->Index(to[0], to[1], to[2]);
      }
    }
    return own;
  }

private:
  vtkIdType Index(int i, int j, int k) const
  {
    return i + vtkIdType(this->Dims[0]) * (j + vtkIdType(this->Dims[1]) * k);
  }

  // Whether a triangle noted for the box in `slot` meets the segment origin + t direction, t in
  // (0, 1.001] (a touch within 0.1% beyond its end counts, as refracta_opaque_between asks it).
  bool Meets(size_t slot, const double origin[3], const double direction[3]) const
  {
    for (vtkIdType r = this->First[slot]; r < this->First[slot + 1]; ++r)
    {
      const vtkIdType triangle = this->Pairs[r].second;
      const double* q = this->Planes.data() + 4 * triangle;
      const double s0 = vtkMath::Dot(q, origin) + q[3];
      const double along = vtkMath::Dot(q, direction);
      const double s1 = s0 + 1.001 * along;
      const double tolerance = 1e-9 * (std::fabs(q[3]) + std::fabs(s0) + std::fabs(along));
      if ((s0 > tolerance && s1 > tolerance) || (s0 < -tolerance && s1 < -tolerance))
      {
        continue;
      }
      const double* t = this->Opaque.data() + 9 * triangle;
      double hit[3];
      if (vtkRefractaBVH::IntersectTriangle(origin, direction, t, t + 3, t + 6, 1.001, hit))
      {
        return true;
      }
    }
    return false;
  }

  // Whether an opaque triangle separates voxel coordinates p (in the box of voxel cell, crossed
  // slot `cellSlot`) from voxel to's centre: the segment lies in the boxes of the voxels between.
  bool Separated(const double p[3], const int cell[3], size_t cellSlot, const int to[3]) const
  {
    double origin[3], direction[3];
    int lo[3], hi[3];
    for (int c = 0; c < 3; ++c)
    {
      origin[c] = p[c] * this->Spacing[c];
      direction[c] = (to[c] - p[c]) * this->Spacing[c];
      lo[c] = std::min(cell[c], to[c]);
      hi[c] = std::max(cell[c], to[c]);
    }
    for (int k = lo[2]; k <= hi[2]; ++k)
    {
      for (int j = lo[1]; j <= hi[1]; ++j)
      {
        for (int i = lo[0]; i <= hi[0]; ++i)
        {
          if (i == cell[0] && j == cell[1] && k == cell[2])
          {
            if (this->Meets(cellSlot, origin, direction))
            {
              return true;
            }
            continue;
          }
          const vtkIdType v = this->Index(i, j, k);
          const auto at = std::lower_bound(this->Crossed.begin(), this->Crossed.end(), v);
          if (at != this->Crossed.end() && *at == v &&
            this->Meets(static_cast<size_t>(at - this->Crossed.begin()), origin, direction))
          {
            return true;
          }
        }
      }
    }
    return false;
  }

  const std::vector<std::pair<vtkIdType, vtkIdType>>& Pairs;
  const std::vector<double>& Opaque;
  const int* Dims;
  const double* Spacing;
  std::vector<vtkIdType> Crossed, First;
  std::vector<double> Planes;
};
}

//------------------------------------------------------------------------------
vtkRefractaGridCuts::vtkRefractaGridCuts() = default;
vtkRefractaGridCuts::~vtkRefractaGridCuts() = default;

//------------------------------------------------------------------------------
bool vtkRefractaGridCuts::Update(vtkRefractaSurfaceSet* set, const int dims[3],
  const double spacing[3], vtkMatrix4x4* localToWorld)
{
  // At most 2^40 points: the voxel count must not overflow the index arithmetic.
  const bool gridValid = dims[0] >= 1 && dims[1] >= 1 && dims[2] >= 1 &&
    static_cast<double>(dims[0]) * dims[1] * dims[2] <= 1099511627776.0 &&
    std::all_of(spacing, spacing + 3, [](double h) { return std::isfinite(h) && h > 0.0; });
  if (!gridValid)
  {
    vtkErrorMacro("Cannot find the cuts of a grid of "
      << dims[0] << " x " << dims[1] << " x " << dims[2] << " points with spacing " << spacing[0]
      << ", " << spacing[1] << ", " << spacing[2]
      << ": dimensions must be >= 1 (at most 2^40 points) and spacings finite and > 0.");
    this->Clear();
    return false;
  }
  if (set && !set->Build())
  {
    vtkErrorMacro("Cannot find the cuts: the surface set could not be built.");
    this->Clear();
    return false;
  }
  double placement[16];
  vtkNew<vtkMatrix4x4> identity;
  vtkMatrix4x4::DeepCopy(placement, localToWorld ? localToWorld : identity.Get());
  const int builds = set ? set->GetNumberOfBuilds() : -1;
  if (this->NumberOfSearches > 0 && this->Set == set && this->Builds == builds &&
    std::equal(dims, dims + 3, this->Dims) && std::equal(spacing, spacing + 3, this->Spacing) &&
    std::equal(placement, placement + 16, this->LocalToWorld))
  {
    return false;
  }
  this->Set = set;
  this->Builds = builds;
  std::copy(dims, dims + 3, this->Dims);
  std::copy(spacing, spacing + 3, this->Spacing);
  std::copy(placement, placement + 16, this->LocalToWorld);
  this->Links.clear();
  this->Opaque.clear();
  this->BoxTriangles.clear();
  this->ScaledVoxels.clear();
  this->VolumeScales.clear();
  this->VolumesCounted = false;
  ++this->NumberOfSearches;
  if (set && set->GetBVH()->GetNumberOfTriangles() > 0)
  {
    vtkNew<vtkMatrix4x4> matrix;
    matrix->DeepCopy(placement);
    try
    {
      this->Search(set, matrix);
    }
    catch (const std::bad_alloc&)
    {
      vtkErrorMacro("Cannot allocate the cuts of the grid of "
        << dims[0] << " x " << dims[1] << " x " << dims[2] << " points (one byte per point).");
      this->Clear();
      return false;
    }
  }
  this->Modified();
  return true;
}

//------------------------------------------------------------------------------
void vtkRefractaGridCuts::Clear()
{
  this->Set = nullptr;
  this->Builds = -1;
  this->Links.clear();
  this->Opaque.clear();
  this->BoxTriangles.clear();
  this->ScaledVoxels.clear();
  this->VolumeScales.clear();
  this->VolumesCounted = false;
  this->Modified();
}

//------------------------------------------------------------------------------
void vtkRefractaGridCuts::Search(vtkRefractaSurfaceSet* set, vtkMatrix4x4* localToWorld)
{
  vtkNew<vtkMatrix4x4> worldToLocal;
  vtkMatrix4x4::Invert(localToWorld, worldToLocal);
  vtkRefractaBVH* bvh = set->GetBVH();
  const std::vector<double>& triangles = bvh->GetTriangles();
  const std::vector<int>& info = set->GetTriangleInfo();
  const double* frameOrigin = bvh->GetFrameOrigin();
  // Triangle k's corners in grid-local coordinates (the BVH keeps them in the surface frame).
  auto toLocal = [&](vtkIdType k, double v[3][3])
  {
    for (int c = 0; c < 3; ++c)
    {
      double world[4] = { 0, 0, 0, 1 };
      for (int a = 0; a < 3; ++a)
      {
        world[a] = triangles[9 * k + 3 * c + a] + frameOrigin[a];
      }
      worldToLocal->MultiplyPoint(world, world);
      std::copy(world, world + 3, v[c]);
    }
  };
  const int* dims = this->Dims;
  const double* h = this->Spacing;
  for (vtkIdType k = 0; k < bvh->GetNumberOfTriangles(); ++k)
  {
    double v[3][3];
    float plane[4];
    toLocal(k, v);
    if (info[REFRACTA_TRIANGLE_INFO_INTS * k + REFRACTA_TRIANGLE_INFO_KIND] !=
        REFRACTA_SURFACE_LAMBERTIAN ||
      !PlaneInVoxels(v, h, plane))
    {
      continue; // glass lets light through (its two sides' fields belong together); degenerate
    }
    this->Opaque.insert(this->Opaque.end(), &v[0][0], &v[0][0] + 9);
    // The voxels within one voxel of the triangle's bounds (in voxel coordinates), and the
    // links from them.
    double low[3], high[3];
    int lo[3], hi[3];
    bool inside = true;
    for (int a = 0; a < 3 && inside; ++a)
    {
      low[a] = std::min({ v[0][a], v[1][a], v[2][a] }) / h[a];
      high[a] = std::max({ v[0][a], v[1][a], v[2][a] }) / h[a];
      lo[a] = static_cast<int>(std::max(std::floor(low[a]) - 1.0, 0.0));
      hi[a] = static_cast<int>(std::min(std::ceil(high[a]) + 1.0, dims[a] - 1.0));
      inside = low[a] < dims[a] && high[a] > -1.0 && lo[a] <= hi[a];
    }
    if (!inside)
    {
      continue;
    }
    if (this->Links.empty())
    {
      this->Links.assign(size_t(dims[0]) * dims[1] * dims[2], 0);
    }
    // The points within one voxel of a centre per axis (the cell's deposits: half a voxel; the
    // trilinear lookups that read the centre: one) lie within |n_x| + |n_y| + |n_z| of it
    // along the plane's normal.
    const double reach = std::fabs(plane[0]) + std::fabs(plane[1]) + std::fabs(plane[2]);
    // Only the voxels within `reach` of the plane can be near it or have a link it cuts (a link
    // along axis a spans |n_a| <= reach across the plane): along the plane's dominant axis d,
    // each column of the bounds holds at most 2 reach / |n_d| + 1 <= 7 of them. The band is
    // widened by 0.01 voxel for the plane's float rounding and the links' touch tolerance.
    const int d = static_cast<int>(std::max_element(plane, plane + 3,
                                     [](float x, float y) { return std::fabs(x) < std::fabs(y); }) -
      plane);
    const int e = (d + 1) % 3, f = (d + 2) % 3;
    const double band = reach + 0.01;
    int ijk[3];
    for (ijk[f] = lo[f]; ijk[f] <= hi[f]; ++ijk[f])
    {
      for (ijk[e] = lo[e]; ijk[e] <= hi[e]; ++ijk[e])
      {
        const double rest = plane[e] * ijk[e] + plane[f] * ijk[f] + plane[3];
        const double t0 = (-band - rest) / plane[d], t1 = (band - rest) / plane[d];
        const int first = std::max(lo[d], static_cast<int>(std::ceil(std::min(t0, t1))));
        const int last = std::min(hi[d], static_cast<int>(std::floor(std::max(t0, t1))));
        for (ijk[d] = first; ijk[d] <= last; ++ijk[d])
        {
          this->MarkVoxel(ijk, plane, reach, low, high, v);
          this->NoteBoxTriangle(ijk, plane, reach, low, high);
        }
      }
    }
  }
  if (std::none_of(this->Links.begin(), this->Links.end(), [](unsigned char b) { return b != 0; }))
  {
    this->Links.clear();
  }
}

//------------------------------------------------------------------------------
// Voxel ijk's bits for triangle v (plane in voxel coordinates, bounds low..high in voxels): near
// when within `reach` of the plane and one voxel of the bounds; a link along each axis when the
// segment to the next centre meets the triangle.
void vtkRefractaGridCuts::MarkVoxel(const int ijk[3], const float plane[4], double reach,
  const double low[3], const double high[3], const double v[3][3])
{
  const int* dims = this->Dims;
  const double* h = this->Spacing;
  unsigned char& bits = this->Links[ijk[0] + size_t(dims[0]) * (ijk[1] + size_t(dims[1]) * ijk[2])];
  bool near =
    std::fabs(plane[0] * ijk[0] + plane[1] * ijk[1] + plane[2] * ijk[2] + plane[3]) <= reach;
  for (int a = 0; a < 3; ++a)
  {
    near = near && ijk[a] >= low[a] - 1.0 && ijk[a] <= high[a] + 1.0;
  }
  bits |= near ? REFRACTA_CUT_NEAR : 0;
  const double p[3] = { ijk[0] * h[0], ijk[1] * h[1], ijk[2] * h[2] };
  for (int a = 0; a < 3; ++a)
  {
    if (ijk[a] + 1 < dims[a] && SegmentMeetsTriangle(p, a, h[a], v))
    {
      bits |= static_cast<unsigned char>(1 << a);
    }
  }
}

//------------------------------------------------------------------------------
// Whether the last triangle of Opaque may cross voxel ijk's box (a conservative test: within half
// the box's extent along the plane's normal and half a voxel of the triangle's bounds, each
// widened by 0.01 voxel for rounding); if so, the pair is noted for the owned volumes.
void vtkRefractaGridCuts::NoteBoxTriangle(
  const int ijk[3], const float plane[4], double reach, const double low[3], const double high[3])
{
  bool crosses = std::fabs(plane[0] * ijk[0] + plane[1] * ijk[1] + plane[2] * ijk[2] + plane[3]) <=
    0.5 * reach + 0.01;
  for (int a = 0; a < 3; ++a)
  {
    crosses = crosses && ijk[a] >= low[a] - 0.51 && ijk[a] <= high[a] + 0.51;
  }
  if (crosses)
  {
    const int* dims = this->Dims;
    this->BoxTriangles.emplace_back(
      ijk[0] + vtkIdType(dims[0]) * (ijk[1] + vtkIdType(dims[1]) * ijk[2]),
      static_cast<vtkIdType>(this->Opaque.size() / 9) - 1);
  }
}

//------------------------------------------------------------------------------
const std::vector<vtkIdType>& vtkRefractaGridCuts::GetScaledVoxels()
{
  this->CountOwnedVolumes();
  return this->ScaledVoxels;
}

//------------------------------------------------------------------------------
const std::vector<float>& vtkRefractaGridCuts::GetVolumeScales()
{
  this->CountOwnedVolumes();
  return this->VolumeScales;
}

//------------------------------------------------------------------------------
void vtkRefractaGridCuts::CountOwnedVolumes()
{
  if (this->VolumesCounted || this->Links.empty())
  {
    return;
  }
  this->VolumesCounted = true;
  const BoxTriangleIndex boxes(this->BoxTriangles, this->Opaque, this->Dims, this->Spacing);
  // 64 points per box from the R3 sequence (Roberts 2018: frac(1/2 + k alpha), alpha_a =
  // phi3^-a, phi3 the plastic number): a grid of 4 x 4 x 4 puts only 4 distinct coordinates on
  // each axis, so an axis-aligned wall's share of a box was counted to a quarter; these 64 points
  // project to 64 distinct coordinates on every axis.
  constexpr int points = 64;
  constexpr double share = 1.0 / points;
  const double phi3 = 1.2207440846057596;
  const double alpha[3] = { 1.0 / phi3, 1.0 / (phi3 * phi3), 1.0 / (phi3 * phi3 * phi3) };
  double offsets[points][3];
  for (int k = 0; k < points; ++k)
  {
    for (int a = 0; a < 3; ++a)
    {
      const double u = 0.5 + (k + 1) * alpha[a];
      offsets[k][a] = u - std::floor(u) - 0.5;
    }
  }
  // Only the points of a box a triangle may cross can be separated from its centre. Per such box,
  // the voxels its points deposit into instead (in parallel: each slot is written by one thread),
  // then summed into the owned volumes (in boxes) that are not 1.
  std::vector<std::vector<vtkIdType>> moved(boxes.GetNumberOfBoxes());
  vtkSMPTools::For(0, static_cast<vtkIdType>(moved.size()),
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType slot = begin; slot < end; ++slot)
      {
        for (const auto& offset : offsets)
        {
          const vtkIdType to = boxes.Owner(offset, static_cast<size_t>(slot));
          if (to != boxes.GetVoxel(static_cast<size_t>(slot)))
          {
            moved[slot].push_back(to);
          }
        }
      }
    });
  std::map<vtkIdType, double> owned;
  for (size_t slot = 0; slot < moved.size(); ++slot)
  {
    for (const vtkIdType to : moved[slot])
    {
      owned.emplace(boxes.GetVoxel(slot), 1.0).first->second -= share;
      owned.emplace(to, 1.0).first->second += share;
    }
  }
  for (const auto& entry : owned)
  {
    if (std::fabs(entry.second - 1.0) > 0.5 * share)
    {
      this->ScaledVoxels.push_back(entry.first);
      this->VolumeScales.push_back(
        entry.second > 0.5 * share ? static_cast<float>(1.0 / entry.second) : 0.0f);
    }
  }
}

//------------------------------------------------------------------------------
bool vtkRefractaGridCuts::IsNear(int i, int j, int k) const
{
  if (this->Links.empty() || i < 0 || j < 0 || k < 0 || i >= this->Dims[0] || j >= this->Dims[1] ||
    k >= this->Dims[2])
  {
    return false;
  }
  return (this->Links[i + size_t(this->Dims[0]) * (j + size_t(this->Dims[1]) * k)] &
           REFRACTA_CUT_NEAR) != 0;
}

//------------------------------------------------------------------------------
void vtkRefractaGridCuts::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Dims: " << this->Dims[0] << " " << this->Dims[1] << " " << this->Dims[2] << "\n";
  os << indent << "Spacing: " << this->Spacing[0] << " " << this->Spacing[1] << " "
     << this->Spacing[2] << "\n";
  const auto near = std::count_if(this->Links.begin(), this->Links.end(),
    [](unsigned char b) { return (b & REFRACTA_CUT_NEAR) != 0; });
  os << indent << "NearVoxels: " << near << "\n";
  os << indent << "NumberOfSearches: " << this->NumberOfSearches << "\n";
}
