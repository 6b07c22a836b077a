/**
 * Internal to RefractaReference (a private header: not wrapped, not installed). The medium of the
 * reference renderer in the grid-local frame, in double precision: the arrays (uniform ones kept
 * as a single tuple), trilinear sampling clamped to the edge voxels, grad n (the array or central
 * differences), the box, and the per block majorants and flat (straight-ray) blocks.
 */
#ifndef vtkReferenceMedium_h
#define vtkReferenceMedium_h

#include "vtkReferenceMath.h"

#include "vtkRefractaGridFrame.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

class vtkImageData;

namespace refracta
{
namespace reference
{
// The medium in the grid-local frame, double precision.
struct Medium
{
  int N[3] = { 1, 1, 1 };
  double S[3] = { 1, 1, 1 };
  Vec3 Lo = Vec3(0.0), Hi = Vec3(0.0);
  vtkSmartPointer<vtkRefractaGridFrame> Grid = vtkSmartPointer<vtkRefractaGridFrame>::New();
  std::vector<double> Index, Gradient, Sigma, Albedo, G, Emission;
  bool StraightRays = true;
  bool Grey = true;
  bool HasEmission = false;
  double NMax = 1;
  double MinSpacing = 1;
  double Diagonal = 1;
  // Blocks of BlockSize^3 interpolation cells where n is constant and grad n is 0 over the whole
  // trilinear footprint: curved rays cross them in one straight move instead of RK steps.
  static constexpr int BlockSize = 4;
  int NB[3] = { 1, 1, 1 };
  std::vector<unsigned char> Flat;
  std::vector<double> BlockMajorant; // 3 per block

  // When p lies in a flat block, the straight distance along unit d to leave it (the first and
  // last blocks extend to infinity, as the field is clamped beyond the edge voxels).
  bool FlatBlock(const Vec3& p, const Vec3& d, double& tLeave) const
  {
    if (Flat.empty())
    {
      return false;
    }
    int b[3];
    BlockOf(p, b);
    if (!Flat[b[0] + NB[0] * (b[1] + static_cast<size_t>(NB[1]) * b[2])])
    {
      return false;
    }
    tLeave = Inf;
    for (int a = 0; a < 3; ++a)
    {
      if (d[a] > 0 && b[a] < NB[a] - 1)
      {
        const double upper = std::min((b[a] + 1) * BlockSize, N[a] - 1) * S[a];
        tLeave = std::min(tLeave, (upper - p[a]) / d[a]);
      }
      else if (d[a] < 0 && b[a] > 0)
      {
        const double lower = b[a] * BlockSize * S[a];
        tLeave = std::min(tLeave, (lower - p[a]) / d[a]);
      }
    }
    tLeave = std::max(tLeave, 0.0);
    return true;
  }

  // Block b of point p (u clamped to the voxel range, as the fields are).
  void BlockOf(const Vec3& p, int b[3]) const
  {
    for (int a = 0; a < 3; ++a)
    {
      const double u = std::min(std::max(p[a] / S[a], 0.0), static_cast<double>(N[a] - 1));
      b[a] = std::min(static_cast<int>(u / BlockSize), NB[a] - 1);
    }
  }

  // Local majorant of sigma_t (channel ch) at p, valid within the Euclidean distance dSafe of p:
  // each block's majorant covers its trilinear footprint grown by one voxel on every side, and a
  // path of arc length d stays within distance d of its start.
  void LocalMajorant(const Vec3& p, int ch, double& m, double& dSafe) const
  {
    int b[3];
    BlockOf(p, b);
    m = BlockMajorant[3 * (b[0] + NB[0] * (b[1] + static_cast<size_t>(NB[1]) * b[2])) + ch];
    dSafe = Inf;
    for (int a = 0; a < 3; ++a)
    {
      if (b[a] > 0)
      {
        dSafe = std::min(dSafe, p[a] - (b[a] * BlockSize - 1) * S[a]);
      }
      if (b[a] < NB[a] - 1)
      {
        dSafe = std::min(dSafe, ((b[a] + 1) * BlockSize + 1) * S[a] - p[a]);
      }
    }
    dSafe = std::max(dSafe, 0.0);
  }

  void BuildBlockMajorants();

  void BuildFlatBlocks();

  // World <-> grid-local, through vtkRefractaGridFrame (origin, extent and direction matrix).
  Vec3 ToLocalPoint(const double p[3]) const;
  Vec3 ToLocalVector(const double v[3]) const;
  Vec3 ToWorldVector(const Vec3& v) const;
  Vec3 ToWorldPoint(const Vec3& v) const;

  bool Inside(const Vec3& p, double eps) const
  {
    return p.x >= Lo.x - eps && p.x <= Hi.x + eps && p.y >= Lo.y - eps && p.y <= Hi.y + eps &&
      p.z >= Lo.z - eps && p.z <= Hi.z + eps;
  }

  // Ray-box slab intersection; returns false on a miss.
  bool Intersect(const Vec3& o, const Vec3& d, double& t0, double& t1) const
  {
    t0 = 0;
    t1 = Inf;
    for (int i = 0; i < 3; ++i)
    {
      if (d[i] == 0)
      {
        if (o[i] < Lo[i] || o[i] > Hi[i])
        {
          return false;
        }
        continue;
      }
      const double inv = 1.0 / d[i];
      double a = (Lo[i] - o[i]) * inv, b = (Hi[i] - o[i]) * inv;
      if (a > b)
      {
        std::swap(a, b);
      }
      t0 = std::max(t0, a);
      t1 = std::min(t1, b);
    }
    return t1 >= t0;
  }

  // Trilinear stencil: 8 voxel indices and weights, clamped to the edge voxels.
  struct Stencil
  {
    int64_t Idx[8];
    double W[8];
  };
  void MakeStencil(const Vec3& p, Stencil& st) const
  {
    int i0[3], i1[3];
    double t[3];
    for (int a = 0; a < 3; ++a)
    {
      double u = p[a] / S[a];
      u = std::min(std::max(u, 0.0), static_cast<double>(N[a] - 1));
      int i = static_cast<int>(std::floor(u));
      i = std::min(i, std::max(N[a] - 2, 0));
      i0[a] = i;
      i1[a] = std::min(i + 1, N[a] - 1);
      t[a] = std::min(std::max(u - i, 0.0), 1.0);
    }
    int c = 0;
    for (int kz = 0; kz < 2; ++kz)
    {
      for (int ky = 0; ky < 2; ++ky)
      {
        for (int kx = 0; kx < 2; ++kx, ++c)
        {
          const int64_t ix = kx ? i1[0] : i0[0];
          const int64_t iy = ky ? i1[1] : i0[1];
          const int64_t iz = kz ? i1[2] : i0[2];
          st.Idx[c] = ix + N[0] * (iy + static_cast<int64_t>(N[1]) * iz);
          st.W[c] = (kx ? t[0] : 1 - t[0]) * (ky ? t[1] : 1 - t[1]) * (kz ? t[2] : 1 - t[2]);
        }
      }
    }
  }
  // Arrays that are missing or uniform are stored as a single tuple (see Load).
  double Sample1(const std::vector<double>& a, const Stencil& st) const
  {
    if (a.size() == 1)
    {
      return a[0];
    }
    double r = 0;
    for (int c = 0; c < 8; ++c)
    {
      r += st.W[c] * a[st.Idx[c]];
    }
    return r;
  }
  Vec3 Sample3(const std::vector<double>& a, const Stencil& st) const
  {
    if (a.size() == 3)
    {
      return ToVec3(a.data());
    }
    Vec3 r(0.0);
    for (int c = 0; c < 8; ++c)
    {
      const double* p = &a[3 * st.Idx[c]];
      r.x += st.W[c] * p[0];
      r.y += st.W[c] * p[1];
      r.z += st.W[c] * p[2];
    }
    return r;
  }
  void IndexAndGradient(const Vec3& p, double& n, Vec3& g) const
  {
    Stencil st;
    MakeStencil(p, st);
    n = Sample1(Index, st);
    g = Sample3(Gradient, st);
  }

  // Copies the arrays (defaults where missing) and derives the flags. `medium` was validated.
  void Load(vtkImageData* medium);
};
} // namespace reference
} // namespace refracta

#endif
