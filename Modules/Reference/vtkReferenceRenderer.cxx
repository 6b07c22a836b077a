#include "vtkReferenceRenderer.h"

#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMath.h"
#include "vtkMatrix3x3.h"
#include "vtkMediumValidator.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkRefractaEnvironmentMap.h"
#include "vtkRefractaGridFrame.h"
#include "vtkRefractaMedium.h"
#include "vtkSMPTools.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkReferenceRenderer);

namespace
{
constexpr double Pi = 3.14159265358979323846;
constexpr double Inf = std::numeric_limits<double>::infinity();

// ---------------------------------------------------------------------------------------------
// Small double vector.
struct V3
{
  double x = 0, y = 0, z = 0;
  V3() = default;
  V3(double a, double b, double c)
    : x(a)
    , y(b)
    , z(c)
  {
  }
  explicit V3(const double* p)
    : x(p[0])
    , y(p[1])
    , z(p[2])
  {
  }
  double operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  double& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
};
inline V3 operator+(const V3& a, const V3& b)
{
  return { a.x + b.x, a.y + b.y, a.z + b.z };
}
inline V3 operator-(const V3& a, const V3& b)
{
  return { a.x - b.x, a.y - b.y, a.z - b.z };
}
inline V3 operator*(double s, const V3& a)
{
  return { s * a.x, s * a.y, s * a.z };
}
inline V3 operator*(const V3& a, const V3& b)
{
  return { a.x * b.x, a.y * b.y, a.z * b.z };
}
inline V3 operator-(const V3& a)
{
  return { -a.x, -a.y, -a.z };
}
inline V3& operator+=(V3& a, const V3& b)
{
  a.x += b.x;
  a.y += b.y;
  a.z += b.z;
  return a;
}
inline double Dot(const V3& a, const V3& b)
{
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline V3 Cross(const V3& a, const V3& b)
{
  return { a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x };
}
inline double Norm(const V3& a)
{
  return std::sqrt(Dot(a, a));
}
inline V3 Normalized(const V3& a)
{
  const double l = Norm(a);
  return l > 0 ? (1.0 / l) * a : V3(0, 0, 1);
}
inline double MaxComp(const V3& a)
{
  return std::max(a.x, std::max(a.y, a.z));
}

// Orthonormal basis around a unit vector (Duff et al. 2017, branchless).
inline void Basis(const V3& n, V3& t, V3& b)
{
  const double s = std::copysign(1.0, n.z);
  const double a = -1.0 / (s + n.z);
  const double c = n.x * n.y * a;
  t = V3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
  b = V3(c, s + n.y * n.y * a, -n.y);
}

// 1 - cos of the angle between unit vectors, without cancellation near 0: |a - b|^2 / 2.
inline double OneMinusCos(const V3& a, const V3& b)
{
  const V3 d = a - b;
  return 0.5 * Dot(d, d);
}

double HGPhase(double g, double oneMinusCos)
{
  // (1 + g^2 - 2 g c) written as a sum of non-negative terms (see refracta_common.cl).
  const double omc = std::min(std::max(oneMinusCos, 0.0), 2.0);
  const double denom =
    g >= 0 ? (1 - g) * (1 - g) + 2 * g * omc : (1 + g) * (1 + g) - 2 * g * (2.0 - omc);
  const double d = std::max(denom, 1e-300);
  return (1 - g) * (1 + g) / (4 * Pi * d * std::sqrt(d));
}

V3 SampleHG(double g, const V3& in, double u1, double u2)
{
  double cosT, sinT;
  if (std::abs(g) < 1e-5)
  {
    cosT = 1 - 2 * u1;
    sinT = std::sqrt(std::max(0.0, 1 - cosT * cosT));
  }
  else
  {
    // Inverse CDF: 1 - cos = (s^2 - (1-g)^2) / (2g) with s = (1 - g^2) / (1 - g + 2 g u1); the
    // factored form (s - 1 + g)(s + 1 - g) keeps precision when the distribution is sharply
    // peaked.
    const double s = (1 - g * g) / (1 - g + 2 * g * u1);
    double omc = (s - 1 + g) * (s + 1 - g) / (2 * g);
    omc = std::min(std::max(omc, 0.0), 2.0);
    cosT = 1 - omc;
    sinT = std::sqrt(std::max(0.0, omc * (2 - omc)));
  }
  const double phi = 2 * Pi * u2;
  V3 t, b;
  Basis(in, t, b);
  return Normalized((sinT * std::cos(phi)) * t + (sinT * std::sin(phi)) * b + cosT * in);
}

// Uniform direction in the cone of half-angle theta_max around `axis`; omcMax = 1 - cos(theta_max).
V3 SampleCone(const V3& axis, double omcMax, double u1, double u2)
{
  const double omc = u1 * omcMax;
  const double cosT = 1 - omc;
  const double sinT = std::sqrt(std::max(0.0, omc * (2 - omc)));
  const double phi = 2 * Pi * u2;
  V3 t, b;
  Basis(axis, t, b);
  return Normalized((sinT * std::cos(phi)) * t + (sinT * std::sin(phi)) * b + cosT * axis);
}

// ---------------------------------------------------------------------------------------------
// Random numbers: SplitMix64 per pixel stream (each pixel's stream seeded from the seed and the
// pixel index through the same mixer), 53-bit uniform doubles in [0, 1).
inline uint64_t Mix64(uint64_t z)
{
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}
struct Rng
{
  uint64_t State;
  Rng(uint64_t seed, uint64_t stream)
    : State(Mix64(Mix64(seed + 0x9e3779b97f4a7c15ULL) ^ (stream * 0xd1b54a32d192ed03ULL)))
  {
  }
  double Uniform()
  {
    this->State += 0x9e3779b97f4a7c15ULL;
    return static_cast<double>(Mix64(this->State) >> 11) * (1.0 / 9007199254740992.0);
  }
};

// ---------------------------------------------------------------------------------------------
// The medium in the grid-local frame, double precision.
struct Medium
{
  int N[3] = { 1, 1, 1 };
  double S[3] = { 1, 1, 1 };
  V3 Lo, Hi;
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
  bool FlatBlock(const V3& p, const V3& d, double& tLeave) const
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
  void BlockOf(const V3& p, int b[3]) const
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
  void LocalMajorant(const V3& p, int ch, double& m, double& dSafe) const
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

  void BuildBlockMajorants()
  {
    BlockMajorant.assign(3 * static_cast<size_t>(NB[0]) * NB[1] * NB[2], 0.0);
    auto at = [this](const std::vector<double>& v, int64_t id)
    { return &v[v.size() == 3 ? 0 : 3 * id]; };
    for (int bz = 0; bz < NB[2]; ++bz)
    {
      for (int by = 0; by < NB[1]; ++by)
      {
        for (int bx = 0; bx < NB[0]; ++bx)
        {
          const int b[3] = { bx, by, bz };
          int lo[3], hi[3];
          for (int a = 0; a < 3; ++a)
          {
            // Points within one voxel of the block region [bB, (b+1)B] interpolate voxels
            // bB - 1 .. (b+1)B + 2.
            lo[a] = std::max(b[a] * BlockSize - 1, 0);
            hi[a] = std::min((b[a] + 1) * BlockSize + 2, N[a] - 1);
          }
          double m[3] = { 0, 0, 0 };
          bool emission = false;
          for (int k = lo[2]; k <= hi[2]; ++k)
          {
            for (int j = lo[1]; j <= hi[1]; ++j)
            {
              for (int i = lo[0]; i <= hi[0]; ++i)
              {
                const int64_t id = i + N[0] * (j + static_cast<int64_t>(N[1]) * k);
                const double* sg = at(Sigma, id);
                const double* e = at(Emission, id);
                for (int c = 0; c < 3; ++c)
                {
                  m[c] = std::max(m[c], sg[c]);
                  emission = emission || e[c] > 0;
                }
              }
            }
          }
          if (emission)
          {
            // Emission is estimated at tentative collisions: at least 4 per smallest spacing.
            for (int c = 0; c < 3; ++c)
            {
              m[c] = std::max(m[c], 4.0 / MinSpacing);
            }
          }
          if (Grey)
          {
            m[0] = m[1] = m[2] = std::max(m[0], std::max(m[1], m[2]));
          }
          double* out = &BlockMajorant[3 * (bx + NB[0] * (by + static_cast<size_t>(NB[1]) * bz))];
          out[0] = m[0];
          out[1] = m[1];
          out[2] = m[2];
        }
      }
    }
  }

  void BuildFlatBlocks()
  {
    Flat.clear();
    if (StraightRays || (Index.size() == 1 && Gradient.size() == 3))
    {
      return; // everything straight, or a uniform non-zero gradient: nothing flat to skip
    }
    Flat.assign(static_cast<size_t>(NB[0]) * NB[1] * NB[2], 0);
    auto nAt = [this](int64_t id) { return Index.size() == 1 ? Index[0] : Index[id]; };
    auto gAt = [this](int64_t id) { return &Gradient[Gradient.size() == 3 ? 0 : 3 * id]; };
    for (int bz = 0; bz < NB[2]; ++bz)
    {
      for (int by = 0; by < NB[1]; ++by)
      {
        for (int bx = 0; bx < NB[0]; ++bx)
        {
          const int b[3] = { bx, by, bz };
          int lo[3], hi[3];
          for (int a = 0; a < 3; ++a)
          {
            lo[a] = b[a] * BlockSize;
            hi[a] = std::min((b[a] + 1) * BlockSize, N[a] - 1);
          }
          const double n0 = nAt(lo[0] + N[0] * (lo[1] + static_cast<int64_t>(N[1]) * lo[2]));
          bool flat = true;
          for (int k = lo[2]; k <= hi[2] && flat; ++k)
          {
            for (int j = lo[1]; j <= hi[1] && flat; ++j)
            {
              for (int i = lo[0]; i <= hi[0] && flat; ++i)
              {
                const int64_t id = i + N[0] * (j + static_cast<int64_t>(N[1]) * k);
                const double* g = gAt(id);
                flat = nAt(id) == n0 && g[0] == 0 && g[1] == 0 && g[2] == 0;
              }
            }
          }
          Flat[bx + NB[0] * (by + static_cast<size_t>(NB[1]) * bz)] = flat ? 1 : 0;
        }
      }
    }
  }

  // World <-> grid-local, through vtkRefractaGridFrame (origin, extent and direction matrix).
  V3 ToLocalPoint(const double p[3]) const
  {
    double r[3];
    Grid->WorldToLocalPoint(p, r);
    return V3(r);
  }
  V3 ToLocalVector(const double v[3]) const
  {
    double r[3];
    Grid->WorldToLocalVector(v, r);
    return V3(r);
  }
  V3 ToWorldVector(const V3& v) const
  {
    const double in[3] = { v.x, v.y, v.z };
    double r[3];
    Grid->LocalToWorldVector(in, r);
    return V3(r);
  }
  V3 ToWorldPoint(const V3& v) const
  {
    const double in[3] = { v.x, v.y, v.z };
    double r[3];
    Grid->LocalToWorldPoint(in, r);
    return V3(r);
  }

  bool Inside(const V3& p, double eps) const
  {
    return p.x >= Lo.x - eps && p.x <= Hi.x + eps && p.y >= Lo.y - eps && p.y <= Hi.y + eps &&
      p.z >= Lo.z - eps && p.z <= Hi.z + eps;
  }

  // Ray-box slab intersection; returns false on a miss.
  bool Intersect(const V3& o, const V3& d, double& t0, double& t1) const
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
  void MakeStencil(const V3& p, Stencil& st) const
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
  V3 Sample3(const std::vector<double>& a, const Stencil& st) const
  {
    if (a.size() == 3)
    {
      return V3(a.data());
    }
    V3 r;
    for (int c = 0; c < 8; ++c)
    {
      const double* p = &a[3 * st.Idx[c]];
      r.x += st.W[c] * p[0];
      r.y += st.W[c] * p[1];
      r.z += st.W[c] * p[2];
    }
    return r;
  }
  void IndexAndGradient(const V3& p, double& n, V3& g) const
  {
    Stencil st;
    MakeStencil(p, st);
    n = Sample1(Index, st);
    g = Sample3(Gradient, st);
  }

  // Copies the arrays (defaults where missing) and derives the flags. `medium` was validated.
  void Load(vtkImageData* medium)
  {
    int dims[3];
    medium->GetDimensions(dims);
    medium->GetSpacing(S);
    Grid->SetImage(medium);
    for (int a = 0; a < 3; ++a)
    {
      N[a] = dims[a];
      Lo[a] = -0.5 * S[a];
      Hi[a] = (N[a] - 0.5) * S[a];
    }
    MinSpacing = std::min(S[0], std::min(S[1], S[2]));
    Diagonal = Norm(Hi - Lo);
    const int64_t n = static_cast<int64_t>(N[0]) * N[1] * N[2];
    vtkPointData* pd = medium->GetPointData();
    // A missing array, or one whose tuples are all equal, is kept as a single tuple: memory
    // (8 bytes per component per voxel otherwise) and a faster lookup.
    auto shrinkIfUniform = [n](std::vector<double>& out, int nc)
    {
      for (int64_t i = 1; i < n; ++i)
      {
        for (int c = 0; c < nc; ++c)
        {
          if (out[i * nc + c] != out[c])
          {
            return;
          }
        }
      }
      out.resize(nc);
      out.shrink_to_fit();
    };
    auto load = [&](int id, std::vector<double>& out) -> bool
    {
      const int nc = vtkRefractaMedium::GetNumberOfComponents(id);
      vtkDataArray* arr = pd->GetArray(vtkRefractaMedium::GetArrayName(id));
      if (!arr)
      {
        out.assign(nc, vtkRefractaMedium::GetDefaultValue(id));
        return false;
      }
      out.resize(static_cast<size_t>(n * nc));
      for (int64_t i = 0; i < n; ++i)
      {
        for (int c = 0; c < nc; ++c)
        {
          out[i * nc + c] = arr->GetComponent(i, c);
        }
      }
      shrinkIfUniform(out, nc);
      return true;
    };
    load(vtkRefractaMedium::REFRACTIVE_INDEX, Index);
    const bool hasGradient = load(vtkRefractaMedium::REFRACTIVE_INDEX_GRADIENT, Gradient);
    load(vtkRefractaMedium::EXTINCTION, Sigma);
    load(vtkRefractaMedium::ALBEDO, Albedo);
    load(vtkRefractaMedium::ANISOTROPY, G);
    load(vtkRefractaMedium::EMISSION, Emission);

    if (!hasGradient && Index.size() == 1)
    {
      Gradient.assign(3, 0.0);
    }
    else if (!hasGradient)
    {
      // Per-voxel central differences of n (one-sided at the edge voxels, 0 along an axis with a
      // single voxel), interpolated trilinearly afterwards like any other array.
      Gradient.assign(static_cast<size_t>(3 * n), 0.0);
      for (int k = 0; k < N[2]; ++k)
      {
        for (int j = 0; j < N[1]; ++j)
        {
          for (int i = 0; i < N[0]; ++i)
          {
            const int ijk[3] = { i, j, k };
            const int64_t id = i + N[0] * (j + static_cast<int64_t>(N[1]) * k);
            for (int a = 0; a < 3; ++a)
            {
              if (N[a] < 2)
              {
                continue;
              }
              int lo[3] = { i, j, k }, hi[3] = { i, j, k };
              lo[a] = std::max(ijk[a] - 1, 0);
              hi[a] = std::min(ijk[a] + 1, N[a] - 1);
              const int64_t il = lo[0] + N[0] * (lo[1] + static_cast<int64_t>(N[1]) * lo[2]);
              const int64_t ih = hi[0] + N[0] * (hi[1] + static_cast<int64_t>(N[1]) * hi[2]);
              Gradient[3 * id + a] = (Index[ih] - Index[il]) / ((hi[a] - lo[a]) * S[a]);
            }
          }
        }
      }
      shrinkIfUniform(Gradient, 3);
    }
    auto at = [](const std::vector<double>& v, int nc, int64_t i)
    { return &v[v.size() == static_cast<size_t>(nc) ? 0 : i * nc]; };
    const int64_t nIndex = static_cast<int64_t>(Index.size());
    const int64_t nGrad = static_cast<int64_t>(Gradient.size()) / 3;
    StraightRays = true;
    NMax = 1;
    for (int64_t i = 0; i < nIndex; ++i)
    {
      NMax = std::max(NMax, Index[i]);
      StraightRays = StraightRays && Index[i] == Index[0];
    }
    for (int64_t i = 0; i < nGrad; ++i)
    {
      const double* g = at(Gradient, 3, i);
      StraightRays = StraightRays && g[0] == 0 && g[1] == 0 && g[2] == 0;
    }
    Grey = true;
    HasEmission = false;
    for (int64_t i = 0; i < n; ++i)
    {
      const double* s = at(Sigma, 3, i);
      const double* a = at(Albedo, 3, i);
      const double* e = at(Emission, 3, i);
      if (s[0] != s[1] || s[0] != s[2] || a[0] != a[1] || a[0] != a[2])
      {
        Grey = false;
      }
      for (int c = 0; c < 3; ++c)
      {
        HasEmission = HasEmission || e[c] > 0;
      }
    }
    for (int a = 0; a < 3; ++a)
    {
      NB[a] = std::max(1, (N[a] - 1 + BlockSize - 1) / BlockSize);
    }
    BuildFlatBlocks();
    BuildBlockMajorants();
  }
};

// ---------------------------------------------------------------------------------------------
// A light in the grid-local frame, with its finite extent.
struct Light
{
  bool Directional = true;
  V3 Colour;           // E (directional) or I (point / spot) per channel
  V3 Towards;          // directional: unit direction from the scene towards the light
  double OmcDelta = 0; // directional: 1 - cos(delta)
  double Radiance = 0; // directional: 1 / (pi sin^2 delta) ; sphere: 1 / (pi r^2)
  V3 Centre;           // point / spot
  double Radius = 0;
  bool Spot = false;
  V3 Axis; // spot axis (unit, from the light towards its focal point)
  double CosCone = -1;
  double Exponent = 0;

  // Radiance (per unit colour) leaving the sphere in the unit direction `w` (travel direction of
  // the emitted light).
  double SphereFactor(const V3& w) const
  {
    if (!Spot)
    {
      return Radiance;
    }
    const double c = Dot(w, Axis);
    if (c < CosCone || c <= 0)
    {
      return 0;
    }
    return Radiance * std::pow(c, Exponent);
  }

  // Solid-angle pdf of the uniform cone that this light subtends from x, evaluated at w; fills the
  // cone for sampling when asked.
  bool Cone(const V3& x, V3& axis, double& omcMax) const
  {
    if (Directional)
    {
      axis = Towards;
      omcMax = OmcDelta;
      return true;
    }
    const V3 d = Centre - x;
    const double dist2 = Dot(d, d);
    if (dist2 <= Radius * Radius)
    {
      // Inside the sphere: the whole sphere of directions (pdf positive, no contribution).
      axis = V3(0, 0, 1);
      omcMax = 2;
      return false;
    }
    axis = (1.0 / std::sqrt(dist2)) * d;
    const double sin2 = Radius * Radius / dist2;
    const double cosMax = std::sqrt(std::max(0.0, 1 - sin2));
    omcMax = sin2 / (1 + cosMax);
    return true;
  }
  double ConePdf(const V3& x, const V3& w) const
  {
    V3 axis;
    double omcMax;
    Cone(x, axis, omcMax);
    if (OneMinusCos(w, axis) > omcMax)
    {
      return 0;
    }
    return 1.0 / (2 * Pi * omcMax);
  }
  // Distance along the segment o + t d (unit d), t in [0, tMax], to the outer surface of the
  // sphere, or Inf.
  double HitSphere(const V3& o, const V3& d, double tMax) const
  {
    const V3 oc = o - Centre;
    const double b = Dot(oc, d);
    const double c = Dot(oc, oc) - Radius * Radius;
    if (c <= 0)
    {
      return Inf; // starts inside: the outer surface cannot be hit from inside
    }
    const double disc = b * b - c;
    if (disc < 0)
    {
      return Inf;
    }
    const double t = -b - std::sqrt(disc);
    return (t >= 0 && t <= tMax) ? t : Inf;
  }
};

// ---------------------------------------------------------------------------------------------
// Tracing along a (possibly curved) ray inside the box.
struct RayState
{
  V3 X;         // position, grid-local
  V3 V;         // n dx/ds, |V| = n (curved rays); unused for straight rays
  V3 Dir;       // unit travel direction
  double H = 0; // integrator step proposal
};

enum class Event
{
  Reached,  // moved the requested arc length, still inside the box
  Exited,   // left the box; X on the boundary, Dir the exit direction
  HitLight, // reached a light sphere inside the box (HitIndex)
  Stuck     // integrator step limit reached (path dropped)
};

struct Tracer
{
  const Medium* M = nullptr;
  double Tol = 1e-7;
  double MaxStep = 1;
  const std::vector<Light>* Lights = nullptr; // spheres to test, or nullptr
  int64_t StepBudget = 1000000;               // steps per Advance call: bounds trapped (TIR) rays

  double StraightExit(const V3& x, const V3& d) const
  {
    double t0, t1;
    if (!M->Intersect(x, d, t0, t1))
    {
      return 0;
    }
    return std::max(t1, 0.0);
  }

  void CheckSpheres(const V3& o, const V3& d, double len, double& tHit, int& which) const
  {
    if (!Lights)
    {
      return;
    }
    for (size_t i = 0; i < Lights->size(); ++i)
    {
      const Light& l = (*Lights)[i];
      if (l.Directional)
      {
        continue;
      }
      const double t = l.HitSphere(o, d, len);
      if (t < tHit)
      {
        tHit = t;
        which = static_cast<int>(i);
      }
    }
  }

  // Start a curved ray at x (inside or on the box) with unit direction d.
  void Start(RayState& r, const V3& x, const V3& d) const
  {
    r.X = x;
    r.Dir = d;
    if (!M->StraightRays)
    {
      double n;
      V3 g;
      M->IndexAndGradient(x, n, g);
      r.V = n * d;
    }
    r.H = MaxStep * M->MinSpacing;
  }

  // Dormand-Prince RK5(4) step of the ray equation in arc length; returns the error norm.
  double RKStep(const V3& x, const V3& v, double h, V3& xn, V3& vn) const
  {
    static const double a21 = 1.0 / 5, a31 = 3.0 / 40, a32 = 9.0 / 40, a41 = 44.0 / 45,
                        a42 = -56.0 / 15, a43 = 32.0 / 9, a51 = 19372.0 / 6561,
                        a52 = -25360.0 / 2187, a53 = 64448.0 / 6561, a54 = -212.0 / 729,
                        a61 = 9017.0 / 3168, a62 = -355.0 / 33, a63 = 46732.0 / 5247,
                        a64 = 49.0 / 176, a65 = -5103.0 / 18656, b1 = 35.0 / 384, b3 = 500.0 / 1113,
                        b4 = 125.0 / 192, b5 = -2187.0 / 6784, b6 = 11.0 / 84,
                        e1 = 35.0 / 384 - 5179.0 / 57600, e3 = 500.0 / 1113 - 7571.0 / 16695,
                        e4 = 125.0 / 192 - 393.0 / 640, e5 = -2187.0 / 6784 + 92097.0 / 339200,
                        e6 = 11.0 / 84 - 187.0 / 2100, e7 = -1.0 / 40;
    auto f = [this](const V3& px, const V3& pv, V3& dx, V3& dv)
    {
      double n;
      M->IndexAndGradient(px, n, dv);
      dx = (1.0 / n) * pv;
    };
    V3 kx[7], kv[7];
    f(x, v, kx[0], kv[0]);
    f(x + h * (a21 * kx[0]), v + h * (a21 * kv[0]), kx[1], kv[1]);
    f(x + h * (a31 * kx[0] + a32 * kx[1]), v + h * (a31 * kv[0] + a32 * kv[1]), kx[2], kv[2]);
    f(x + h * (a41 * kx[0] + a42 * kx[1] + a43 * kx[2]),
      v + h * (a41 * kv[0] + a42 * kv[1] + a43 * kv[2]), kx[3], kv[3]);
    f(x + h * (a51 * kx[0] + a52 * kx[1] + a53 * kx[2] + a54 * kx[3]),
      v + h * (a51 * kv[0] + a52 * kv[1] + a53 * kv[2] + a54 * kv[3]), kx[4], kv[4]);
    f(x + h * (a61 * kx[0] + a62 * kx[1] + a63 * kx[2] + a64 * kx[3] + a65 * kx[4]),
      v + h * (a61 * kv[0] + a62 * kv[1] + a63 * kv[2] + a64 * kv[3] + a65 * kv[4]), kx[5], kv[5]);
    xn = x + h * (b1 * kx[0] + b3 * kx[2] + b4 * kx[3] + b5 * kx[4] + b6 * kx[5]);
    vn = v + h * (b1 * kv[0] + b3 * kv[2] + b4 * kv[3] + b5 * kv[4] + b6 * kv[5]);
    f(xn, vn, kx[6], kv[6]);
    const V3 ex = h * (e1 * kx[0] + e3 * kx[2] + e4 * kx[3] + e5 * kx[4] + e6 * kx[5] + e7 * kx[6]);
    const V3 ev = h * (e1 * kv[0] + e3 * kv[2] + e4 * kv[3] + e5 * kv[4] + e6 * kv[5] + e7 * kv[6]);
    const double sx = Tol * M->MinSpacing, sv = Tol * M->NMax;
    return std::max(std::max(std::abs(ex.x), std::max(std::abs(ex.y), std::abs(ex.z))) / sx,
      std::max(std::abs(ev.x), std::max(std::abs(ev.y), std::abs(ev.z))) / sv);
  }

  // Move along the ray by arc length `dist` (may be Inf) inside the box. `moved` returns the arc
  // length travelled, `hit` the light sphere index for HitLight, `steps` accumulates accepted
  // steps.
  Event Advance(RayState& r, double dist, double& moved, int& hit, int64_t& steps) const
  {
    moved = 0;
    hit = -1;
    if (M->StraightRays)
    {
      const double tExit = StraightExit(r.X, r.Dir);
      const double len = std::min(dist, tExit);
      double tHit = Inf;
      CheckSpheres(r.X, r.Dir, len, tHit, hit);
      ++steps;
      if (tHit < Inf)
      {
        r.X = r.X + tHit * r.Dir;
        moved = tHit;
        return Event::HitLight;
      }
      r.X = r.X + len * r.Dir;
      moved = len;
      return dist < tExit ? Event::Reached : Event::Exited;
    }
    const double hMin = 1e-4 * M->MinSpacing; // also the tolerance for the exit point
    const double hMax = MaxStep * M->MinSpacing;
    int64_t budget = StepBudget;
    while (moved < dist)
    {
      if (--budget < 0)
      {
        return Event::Stuck;
      }
      const double tExit = StraightExit(r.X, r.Dir);
      double tBlock;
      if (M->FlatBlock(r.X, r.Dir, tBlock))
      {
        // n constant and grad n = 0 here: the ray is exactly straight until it leaves the block
        // (overshooting by hMin / 2 so that it does not stall on the block face, where grad n
        // is still exactly 0).
        const double len = std::min(dist - moved, std::min(tExit, tBlock + 0.5 * hMin));
        ++steps;
        if (Lights)
        {
          double tHit = Inf;
          CheckSpheres(r.X, r.Dir, len, tHit, hit);
          if (tHit < Inf)
          {
            r.X = r.X + tHit * r.Dir;
            moved += tHit;
            return Event::HitLight;
          }
        }
        r.X = r.X + len * r.Dir;
        moved += len;
        if (len >= tExit)
        {
          return Event::Exited;
        }
        continue;
      }
      double h = std::min(std::min(r.H, hMax), dist - moved);
      h = std::min(h, std::max(tExit, hMin));
      h = std::max(h, std::min(hMin, dist - moved));
      V3 xn, vn;
      const double err = RKStep(r.X, r.V, h, xn, vn);
      if (err > 1 && h > hMin)
      {
        r.H = std::max(hMin, h * std::max(0.2, 0.9 * std::pow(err, -0.2)));
        continue;
      }
      const bool outside = !M->Inside(xn, 0);
      if (outside && !M->Inside(xn, hMin) && h > hMin)
      {
        // Overshot the box by more than the exit tolerance: shorter step towards the boundary.
        r.H = std::max(hMin, 0.5 * h);
        continue;
      }
      // Accept.
      ++steps;
      const V3 chord = xn - r.X;
      const double clen = Norm(chord);
      if (Lights && clen > 0)
      {
        double tHit = Inf;
        CheckSpheres(r.X, (1.0 / clen) * chord, clen, tHit, hit);
        if (tHit < Inf)
        {
          const double frac = tHit / clen;
          r.X = r.X + frac * chord;
          r.Dir = (1.0 / clen) * chord;
          moved += frac * h;
          return Event::HitLight;
        }
      }
      double n;
      V3 g;
      M->IndexAndGradient(xn, n, g);
      const double vl = Norm(vn);
      r.V = vl > 0 ? (n / vl) * vn : n * r.Dir;
      r.X = xn;
      r.Dir = (1.0 / n) * r.V;
      moved += h;
      if (err <= 1)
      {
        r.H = std::min(hMax, h * std::min(5.0, 0.9 * std::pow(std::max(err, 1e-10), -0.2)));
      }
      if (outside)
      {
        return Event::Exited;
      }
    }
    return Event::Reached;
  }
};

// Delta/ratio tracking step with piecewise-constant (per block) majorants: moves the ray until
// the majorant optical length `tau` is used up (Reached: a tentative collision, its majorant in
// `m`) or the ray leaves the box or hits a light.
Event AdvanceOptical(const Tracer& tr, RayState& r, double tau, int ch, int& hit, double& m)
{
  int64_t steps = 0;
  for (int64_t guard = 0; guard < 10000000; ++guard)
  {
    double dSafe, moved;
    tr.M->LocalMajorant(r.X, ch, m, dSafe);
    if (m > 0 && m * dSafe >= tau)
    {
      return tr.Advance(r, tau / m, moved, hit, steps);
    }
    const Event ev = tr.Advance(r, dSafe, moved, hit, steps);
    if (ev != Event::Reached)
    {
      return ev;
    }
    tau -= m * moved;
  }
  return Event::Stuck;
}

// ---------------------------------------------------------------------------------------------
// Everything a path needs.
struct Scene
{
  Medium M;
  std::vector<Light> Lights;
  V3 Background;
  // Environment map (linear RGB, row major, bottom row first).
  std::vector<double> Env;
  int EnvW = 0, EnvH = 0;
  double EnvUp[3] = { 0, 1, 0 }, EnvRight[3] = { 1, 0, 0 }; // world
  int MaxDepth = -1;
  int RouletteDepth = 8;
  int MaxVertices = 100000;
  Tracer T;      // view rays (no light spheres)
  Tracer TLight; // scattered rays (light spheres tested)

  V3 BackgroundRadiance(const V3& dLocal) const
  {
    if (Env.empty())
    {
      return Background;
    }
    const V3 d = M.ToWorldVector(dLocal);
    const double dw[3] = { d.x, d.y, d.z };
    double uv[2], rgb[3];
    vtkRefractaEnvironmentMap::DirectionToTexture(dw, EnvUp, EnvRight, uv);
    vtkRefractaEnvironmentMap::Sample(Env.data(), EnvW, EnvH, uv[0], uv[1], rgb);
    return V3(rgb);
  }

  // Radiance arriving from lights along a ray that left the box at x with direction d
  // (straight from here on): the first light sphere in the way, else every directional disc
  // containing d.
  V3 EscapedLightRadiance(const V3& x, const V3& d) const
  {
    double tHit = Inf;
    int which = -1;
    for (size_t i = 0; i < Lights.size(); ++i)
    {
      if (!Lights[i].Directional)
      {
        const double t = Lights[i].HitSphere(x, d, Inf);
        if (t < tHit)
        {
          tHit = t;
          which = static_cast<int>(i);
        }
      }
    }
    if (which >= 0)
    {
      const Light& l = Lights[which];
      return (l.SphereFactor(-d)) * l.Colour;
    }
    V3 r;
    for (const Light& l : Lights)
    {
      if (l.Directional && OneMinusCos(d, l.Towards) <= l.OmcDelta)
      {
        r += l.Radiance * l.Colour;
      }
    }
    return r;
  }

  // Light arriving at x (inside the box) along the curved ray leaving x in direction w, times the
  // transmittance to the light, estimated by ratio tracking (the tentative-collision weights
  // (1 - sigma_t / majorant) multiply; Russian roulette once the weight is small). Only the
  // channel `ch` matters for the transmittance (all three when grey).
  V3 Connect(const V3& x, const V3& w, int ch, Rng& rng, bool& truncated) const
  {
    double weight = 1;
    RayState ray;
    TLight.Start(ray, x, w);
    for (;;)
    {
      double majorant;
      int hit;
      const Event ev = AdvanceOptical(TLight, ray, -std::log(1 - rng.Uniform()), ch, hit, majorant);
      if (ev == Event::Stuck)
      {
        truncated = true;
        return V3();
      }
      if (ev == Event::HitLight)
      {
        const Light& l = Lights[hit];
        return (weight * l.SphereFactor(-ray.Dir)) * l.Colour;
      }
      if (ev == Event::Exited)
      {
        return weight * EscapedLightRadiance(ray.X, ray.Dir);
      }
      Medium::Stencil st;
      M.MakeStencil(ray.X, st);
      const double sigma = M.Sample3(M.Sigma, st)[ch];
      weight *= std::max(0.0, 1 - sigma / majorant);
      if (weight < 0.1)
      {
        if (weight <= 0 || rng.Uniform() >= 0.5)
        {
          return V3();
        }
        weight *= 2;
      }
    }
  }

  // One path from a view ray. channel < 0: grey medium, RGB carried together; else only that
  // channel is estimated (returned in that component). `truncated` is set when the path hit a
  // safety limit.
  //
  // At every scattering vertex the light that reaches the vertex without a further collision is
  // estimated by one connection ray whose direction is drawn from the one-sample MIS mixture
  // 0.5 HG + 0.5 (cone of a uniformly chosen light), weighted HG / mixture, its transmittance by
  // ratio tracking; the path itself continues in an HG direction and only its later collisions
  // contribute (light it reaches unscattered was already counted by the connection).
  V3 Trace(V3 origin, V3 dir, int channel, Rng& rng, bool& truncated) const
  {
    V3 result;
    const int ch = channel < 0 ? 0 : channel;
    const V3 mask = channel < 0 ? V3(1, 1, 1) : V3(channel == 0, channel == 1, channel == 2);
    double t0, t1;
    if (!M.Inside(origin, 0))
    {
      if (!M.Intersect(origin, dir, t0, t1))
      {
        return mask * BackgroundRadiance(dir);
      }
      origin = origin + t0 * dir;
    }
    const bool lightsPresent = !Lights.empty();
    const double nLights = static_cast<double>(Lights.size());
    double beta = 1;
    int depth = 0;
    RayState ray;
    T.Start(ray, origin, dir);
    for (;;)
    {
      double majorant;
      int hit;
      // The path's own rays never test light spheres: lights are not seen by view rays, and
      // scattered light reaching a light unscattered is the connections' business.
      const Event ev = AdvanceOptical(T, ray, -std::log(1 - rng.Uniform()), ch, hit, majorant);
      if (ev == Event::Stuck)
      {
        truncated = true;
        return result;
      }
      if (ev == Event::Exited)
      {
        if (depth == 0)
        {
          result += beta * (mask * BackgroundRadiance(ray.Dir));
        }
        return result;
      }
      // Tentative collision.
      Medium::Stencil st;
      M.MakeStencil(ray.X, st);
      const V3 sigma = M.Sample3(M.Sigma, st);
      if (depth == 0 && M.HasEmission)
      {
        // Emission is physical radiance per length; the camera (in n = 1) sees the basic
        // radiance L / n^2, which is what the paths carry.
        const double n = M.Sample1(M.Index, st);
        result += (beta / (majorant * n * n)) * (mask * M.Sample3(M.Emission, st));
      }
      if (rng.Uniform() * majorant >= sigma[ch])
      {
        continue; // null collision
      }
      // Real collision: the scattered part carries on with weight albedo.
      const double albedo = M.Sample3(M.Albedo, st)[ch];
      if (!lightsPresent || albedo <= 0 || (MaxDepth >= 0 && depth + 1 > MaxDepth))
      {
        return result;
      }
      if (depth + 1 > MaxVertices)
      {
        truncated = true;
        return result;
      }
      beta *= albedo;
      if (depth >= RouletteDepth)
      {
        const double q = std::min(1.0, beta);
        if (rng.Uniform() >= q)
        {
          return result;
        }
        beta /= q;
      }
      ++depth;
      const double g = M.Sample1(M.G, st);
      // Light reaching this vertex: one-sample MIS connection.
      {
        V3 w;
        if (rng.Uniform() < 0.5)
        {
          w = SampleHG(g, ray.Dir, rng.Uniform(), rng.Uniform());
        }
        else
        {
          const size_t j =
            std::min(Lights.size() - 1, static_cast<size_t>(rng.Uniform() * nLights));
          V3 axis;
          double omc;
          Lights[j].Cone(ray.X, axis, omc);
          w = SampleCone(axis, omc, rng.Uniform(), rng.Uniform());
        }
        const double p = HGPhase(g, OneMinusCos(ray.Dir, w));
        double lightPdf = 0;
        for (const Light& l : Lights)
        {
          lightPdf += l.ConePdf(ray.X, w);
        }
        const double q = 0.5 * p + 0.5 * lightPdf / nLights;
        if (q > 0 && p > 0)
        {
          const V3 li = Connect(ray.X, w, ch, rng, truncated);
          result += (beta * p / q) * (mask * li);
        }
      }
      if (MaxDepth >= 0 && depth + 1 > MaxDepth)
      {
        return result;
      }
      // Continue the path in an HG direction (weight HG / HG = 1).
      T.Start(ray, ray.X, SampleHG(g, ray.Dir, rng.Uniform(), rng.Uniform()));
    }
  }
};

// True when a switched-on light of the collection is positional (point or spot).
bool HasPositionalLight(vtkLightCollection* lights)
{
  if (!lights)
  {
    return false;
  }
  vtkCollectionSimpleIterator it;
  lights->InitTraversal(it);
  while (vtkLight* l = lights->GetNextLight(it))
  {
    if (l->GetSwitch() && l->GetPositional())
    {
      return true;
    }
  }
  return false;
}

// Converts the renderer's lights to the grid-local frame. Returns an error message for a light
// whose direction is undefined or whose intensity is invalid (empty when all are usable).
std::string BuildLights(const Medium& m, vtkLightCollection* lights, vtkCamera* camera,
  double deltaDeg, double radius, std::vector<Light>& out)
{
  out.clear();
  if (!lights)
  {
    return std::string();
  }
  lights->InitTraversal();
  int index = -1;
  while (vtkLight* vl = lights->GetNextItem())
  {
    ++index;
    if (!vl->GetSwitch())
    {
      continue;
    }
    double pos[3], foc[3];
    if (vl->LightTypeIsHeadlight() && camera)
    {
      camera->GetPosition(pos);
      camera->GetFocalPoint(foc);
    }
    else
    {
      vl->GetTransformedPosition(pos);
      vl->GetTransformedFocalPoint(foc);
    }
    const bool needsDirection = !vl->GetPositional() || vl->GetConeAngle() < 90;
    const double sep[3] = { pos[0] - foc[0], pos[1] - foc[1], pos[2] - foc[2] };
    if (needsDirection && !(vtkMath::Norm(sep) > 0))
    {
      std::ostringstream msg;
      msg << "Light " << index << " is " << (vl->GetPositional() ? "a spot" : "a directional")
          << " light whose position equals its focal point, so its direction is undefined; give "
             "it a position different from its focal point.";
      return msg.str();
    }
    if (!std::isfinite(vl->GetIntensity()) || vl->GetIntensity() < 0)
    {
      std::ostringstream msg;
      msg << "Light " << index << " has intensity " << vl->GetIntensity()
          << "; it must be finite and >= 0.";
      return msg.str();
    }
    double col[3];
    vl->GetDiffuseColor(col);
    Light l;
    l.Colour = vl->GetIntensity() * V3(col);
    const V3 p = m.ToLocalPoint(pos), f = m.ToLocalPoint(foc);
    if (!vl->GetPositional())
    {
      l.Directional = true;
      l.Towards = Normalized(p - f);
      const double delta = vtkMath::RadiansFromDegrees(deltaDeg);
      const double s = std::sin(delta);
      l.OmcDelta = 2 * std::sin(0.5 * delta) * std::sin(0.5 * delta);
      l.Radiance = 1.0 / (Pi * s * s);
    }
    else
    {
      l.Directional = false;
      l.Centre = p;
      l.Radius = radius;
      l.Radiance = 1.0 / (Pi * radius * radius);
      if (vl->GetConeAngle() < 90)
      {
        l.Spot = true;
        l.Axis = Normalized(f - p);
        l.CosCone = std::cos(vtkMath::RadiansFromDegrees(vl->GetConeAngle()));
        l.Exponent = vl->GetExponent();
      }
    }
    out.push_back(l);
  }
  return std::string();
}

inline unsigned char ToneMap(double v, double exposure)
{
  double c = std::min(std::max(exposure * v, 0.0), 1.0);
  if (!(c == c))
  {
    c = 0;
  }
  c = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
  return static_cast<unsigned char>(std::lround(255.0 * c));
}
} // namespace

//------------------------------------------------------------------------------
vtkReferenceRenderer::vtkReferenceRenderer()
{
  this->SetNumberOfInputPorts(1);
  this->SetNumberOfOutputPorts(1);
  this->Lights = vtkSmartPointer<vtkLightCollection>::New();
}

vtkReferenceRenderer::~vtkReferenceRenderer() = default;

void vtkReferenceRenderer::SetCamera(vtkCamera* camera)
{
  if (this->Camera != camera)
  {
    this->Camera = camera;
    this->Modified();
  }
}
vtkCamera* vtkReferenceRenderer::GetCamera()
{
  return this->Camera;
}

void vtkReferenceRenderer::AddLight(vtkLight* light)
{
  if (light)
  {
    this->Lights->AddItem(light);
    this->Modified();
  }
}
void vtkReferenceRenderer::RemoveAllLights()
{
  this->Lights->RemoveAllItems();
  this->Modified();
}
void vtkReferenceRenderer::SetLights(vtkLightCollection* lights)
{
  this->Lights->RemoveAllItems();
  if (lights)
  {
    lights->InitTraversal();
    while (vtkLight* l = lights->GetNextItem())
    {
      this->Lights->AddItem(l);
    }
  }
  this->Modified();
}
vtkLightCollection* vtkReferenceRenderer::GetLights()
{
  return this->Lights;
}

void vtkReferenceRenderer::SetImageSize(int width, int height)
{
  width = std::min(std::max(width, 1), 16384);
  height = std::min(std::max(height, 1), 16384);
  if (width != this->ImageSize[0] || height != this->ImageSize[1])
  {
    this->ImageSize[0] = width;
    this->ImageSize[1] = height;
    this->Modified();
  }
}

void vtkReferenceRenderer::SetEnvironmentMap(vtkImageData* image)
{
  if (this->EnvironmentMap != image)
  {
    this->EnvironmentMap = image;
    this->Modified();
  }
}
vtkImageData* vtkReferenceRenderer::GetEnvironmentMap()
{
  return this->EnvironmentMap;
}

vtkMTimeType vtkReferenceRenderer::GetMTime()
{
  vtkMTimeType t = this->Superclass::GetMTime();
  if (this->Camera)
  {
    t = std::max(t, this->Camera->GetMTime());
  }
  if (this->EnvironmentMap)
  {
    t = std::max(t, this->EnvironmentMap->GetMTime());
  }
  this->Lights->InitTraversal();
  while (vtkLight* l = this->Lights->GetNextItem())
  {
    t = std::max(t, l->GetMTime());
  }
  return t;
}

//------------------------------------------------------------------------------
double vtkReferenceRenderer::HenyeyGreensteinPhase(double g, double cosTheta)
{
  const double c = std::min(std::max(cosTheta, -1.0), 1.0);
  return HGPhase(g, 1 - c);
}

void vtkReferenceRenderer::SampleHenyeyGreenstein(
  double g, const double in[3], double u1, double u2, double out[3])
{
  const V3 w = SampleHG(g, Normalized(V3(in)), u1, u2);
  out[0] = w.x;
  out[1] = w.y;
  out[2] = w.z;
}

int vtkReferenceRenderer::TraceRay(vtkImageData* medium, const double origin[3],
  const double direction[3], double arcLength, double endPoint[3], double endDirection[3])
{
  vtkNew<vtkMediumValidator> validator;
  if (!validator->Validate(medium))
  {
    vtkErrorMacro("TraceRay: the medium is not valid: " << validator->GetErrorMessage());
    return -1;
  }
  Medium m;
  m.Load(medium);
  Tracer tr;
  tr.M = &m;
  tr.Tol = this->IntegratorTolerance;
  tr.MaxStep = this->MaximumStep;
  V3 x = m.ToLocalPoint(origin);
  V3 d = Normalized(m.ToLocalVector(direction));
  double remaining = arcLength;
  int64_t steps = 0;
  double t0, t1;
  if (!m.Inside(x, 0) && m.Intersect(x, d, t0, t1) && t0 < remaining)
  {
    x = x + t0 * d;
    remaining -= t0;
  }
  if (m.Inside(x, 0) && remaining > 0)
  {
    RayState r;
    tr.Start(r, x, d);
    double moved;
    int hit;
    tr.Advance(r, remaining, moved, hit, steps);
    remaining -= moved;
    x = r.X;
    d = r.Dir;
  }
  if (remaining > 0)
  {
    x = x + remaining * d;
  }
  const V3 pw = m.ToWorldPoint(x), dw = Normalized(m.ToWorldVector(d));
  for (int i = 0; i < 3; ++i)
  {
    endPoint[i] = pw[i];
    endDirection[i] = dw[i];
  }
  return static_cast<int>(steps);
}

//------------------------------------------------------------------------------
int vtkReferenceRenderer::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port == 0)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
    return 1;
  }
  return 0;
}

int vtkReferenceRenderer::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  const int extent[6] = { 0, this->ImageSize[0] - 1, 0, this->ImageSize[1] - 1, 0, 0 };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  const double spacing[3] = { 1, 1, 1 }, origin[3] = { 0, 0, 0 };
  outInfo->Set(vtkDataObject::SPACING(), spacing, 3);
  outInfo->Set(vtkDataObject::ORIGIN(), origin, 3);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, VTK_UNSIGNED_CHAR, 3);
  return 1;
}

int vtkReferenceRenderer::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  // The whole medium is needed whatever part of the image is requested.
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  if (inInfo && inInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(),
      inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()), 6);
  }
  return 1;
}

int vtkReferenceRenderer::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  const auto start = std::chrono::steady_clock::now();
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  vtkImageData* medium = vtkImageData::GetData(inputVector[0], 0);
  if (!output)
  {
    vtkErrorMacro("No output image.");
    return 0;
  }
  output->Initialize();

  vtkNew<vtkMediumValidator> validator;
  if (!medium || !validator->Validate(medium))
  {
    vtkErrorMacro("Input 0 is not a valid Refracta medium (a vtkImageData with the point arrays of "
                  "vtkRefractaMedium): "
      << (medium ? validator->GetErrorMessage() : "no input"));
    return 0;
  }
  if (!this->Camera)
  {
    vtkErrorMacro("No camera: call SetCamera(vtkCamera*) before rendering.");
    return 0;
  }
  for (int c = 0; c < 3; ++c)
  {
    if (!std::isfinite(this->BackgroundColor[c]) || this->BackgroundColor[c] < 0)
    {
      vtkErrorMacro("BackgroundColor component " << c << " is " << this->BackgroundColor[c]
                                                 << "; it must be finite and >= 0.");
      return 0;
    }
  }

  Scene scene;
  scene.M.Load(medium);
  const Medium& m = scene.M;

  // Environment map.
  if (this->EnvironmentMap)
  {
    vtkImageData* env = this->EnvironmentMap;
    int dims[3];
    env->GetDimensions(dims);
    vtkDataArray* s = env->GetPointData()->GetScalars();
    if (dims[0] < 1 || dims[1] < 1 || dims[2] != 1 || !s ||
      (s->GetNumberOfComponents() != 3 && s->GetNumberOfComponents() != 4) ||
      s->GetNumberOfTuples() != static_cast<vtkIdType>(dims[0]) * dims[1])
    {
      vtkErrorMacro("EnvironmentMap must be a 2D vtkImageData (W x H x 1) with point scalars of 3 "
                    "or 4 components (RGB or RGBA); got dimensions "
        << dims[0] << " x " << dims[1] << " x " << dims[2] << " and "
        << (s ? s->GetNumberOfComponents() : 0) << "-component scalars.");
      return 0;
    }
    const double scale = s->GetDataType() == VTK_UNSIGNED_CHAR ? 1.0 / 255.0 : 1.0;
    scene.EnvW = dims[0];
    scene.EnvH = dims[1];
    std::copy(this->EnvironmentUp, this->EnvironmentUp + 3, scene.EnvUp);
    std::copy(this->EnvironmentRight, this->EnvironmentRight + 3, scene.EnvRight);
    scene.Env.resize(3 * static_cast<size_t>(dims[0]) * dims[1]);
    for (vtkIdType i = 0; i < s->GetNumberOfTuples(); ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        const double v = s->GetComponent(i, c) * scale;
        if (!std::isfinite(v) || v < 0)
        {
          vtkErrorMacro("EnvironmentMap pixel " << i << " component " << c << " is " << v
                                                << "; radiance must be finite and >= 0.");
          return 0;
        }
        scene.Env[3 * i + c] = v;
      }
    }
  }
  scene.Background = V3(this->BackgroundColor);
  // LightRadius = 0 is a delta light, as in every pass. This estimator reaches a point or spot
  // light only by tracing a (possibly curved) ray that hits its sphere, which a point cannot be:
  // it needs an explicit radius, and says so rather than choosing one.
  const double radius = this->LightRadius;
  if (!(radius > 0) && HasPositionalLight(this->Lights))
  {
    vtkErrorMacro("LightRadius is 0 (a delta point or spot light), but the reference renderer "
                  "connects paths to point and spot lights by hitting their sphere and cannot "
                  "estimate a delta light; set LightRadius > 0 (world units; e.g. "
      << 0.01 * m.Diagonal << ", 1% of this medium's diagonal).");
    return 0;
  }
  const std::string lightError = BuildLights(
    m, this->Lights, this->Camera, this->DirectionalLightAngularRadius, radius, scene.Lights);
  if (!lightError.empty())
  {
    vtkErrorMacro(<< lightError);
    return 0;
  }
  scene.MaxDepth = this->MaximumScatteringDepth;
  scene.RouletteDepth = this->RouletteDepth;
  scene.MaxVertices = this->MaximumPathVertices;
  scene.T.M = &scene.M;
  scene.T.Tol = this->IntegratorTolerance;
  scene.T.MaxStep = this->MaximumStep;
  scene.TLight = scene.T;
  scene.TLight.Lights = &scene.Lights;

  // Camera in the grid-local frame.
  vtkCamera* cam = this->Camera;
  double pos[3], foc[3], up[3];
  cam->GetPosition(pos);
  cam->GetFocalPoint(foc);
  cam->GetViewUp(up);
  const V3 eye = m.ToLocalPoint(pos);
  const V3 fwd = Normalized(m.ToLocalPoint(foc) - eye);
  V3 vup = m.ToLocalVector(up);
  vup = vup - Dot(vup, fwd) * fwd;
  if (Norm(vup) < 1e-12)
  {
    vtkErrorMacro("The camera's view up is parallel to its direction of projection.");
    return 0;
  }
  vup = Normalized(vup);
  const V3 right = Cross(fwd, vup);
  const int W = this->ImageSize[0], H = this->ImageSize[1];
  const double aspect = static_cast<double>(W) / H;
  const bool parallel = cam->GetParallelProjection() != 0;
  const double halfH = parallel ? cam->GetParallelScale()
                                : std::tan(vtkMath::RadiansFromDegrees(cam->GetViewAngle()) / 2);

  const int spp = this->SamplesPerPixel;
  const bool grey = m.Grey;
  const bool jitter = this->PixelJitter;
  const uint64_t seed = this->Seed;
  const int64_t numPixels = static_cast<int64_t>(W) * H;
  std::vector<double> mean(3 * numPixels), stderrs(3 * numPixels);
  std::atomic<int64_t> truncated(0), nonFinite(0);

  auto renderPixels = [&](vtkIdType begin, vtkIdType end)
  {
    int64_t localTrunc = 0, localNonFinite = 0;
    for (vtkIdType p = begin; p < end; ++p)
    {
      const int i = static_cast<int>(p % W), j = static_cast<int>(p / W);
      Rng rng(seed, static_cast<uint64_t>(p));
      double sum[3] = { 0, 0, 0 }, sum2[3] = { 0, 0, 0 };
      for (int s = 0; s < spp; ++s)
      {
        const double jx = jitter ? rng.Uniform() : 0.5, jy = jitter ? rng.Uniform() : 0.5;
        const double sx = (2 * (i + jx) / W - 1) * aspect * halfH;
        const double sy = (2 * (j + jy) / H - 1) * halfH;
        V3 o, d;
        if (parallel)
        {
          o = eye + sx * right + sy * vup;
          d = fwd;
        }
        else
        {
          o = eye;
          d = Normalized(fwd + sx * right + sy * vup);
        }
        V3 val;
        bool trunc = false;
        if (grey)
        {
          val = scene.Trace(o, d, -1, rng, trunc);
        }
        else
        {
          for (int c = 0; c < 3; ++c)
          {
            val += scene.Trace(o, d, c, rng, trunc);
          }
        }
        localTrunc += trunc ? 1 : 0;
        if (!std::isfinite(val.x) || !std::isfinite(val.y) || !std::isfinite(val.z))
        {
          // Never expected; counted and reported (field data NonFiniteSamples) rather than
          // spreading a NaN through the image.
          ++localNonFinite;
          val = V3();
        }
        for (int c = 0; c < 3; ++c)
        {
          sum[c] += val[c];
          sum2[c] += val[c] * val[c];
        }
      }
      for (int c = 0; c < 3; ++c)
      {
        const double mu = sum[c] / spp;
        mean[3 * p + c] = mu;
        if (spp > 1)
        {
          const double var = std::max(0.0, (sum2[c] - spp * mu * mu) / (spp - 1));
          stderrs[3 * p + c] = std::sqrt(var / spp);
        }
        else
        {
          stderrs[3 * p + c] = -1;
        }
      }
    }
    truncated += localTrunc;
    nonFinite += localNonFinite;
  };

  // Rows in blocks so that progress can be reported (and aborts honoured) between parallel runs.
  const int blocks = std::min(H, 20);
  for (int b = 0; b < blocks && !this->GetAbortExecute(); ++b)
  {
    const int64_t r0 = static_cast<int64_t>(H) * b / blocks;
    const int64_t r1 = static_cast<int64_t>(H) * (b + 1) / blocks;
    vtkSMPTools::For(r0 * W, r1 * W, 1, renderPixels);
    this->UpdateProgress(static_cast<double>(b + 1) / blocks);
  }

  // Output.
  output->SetExtent(0, W - 1, 0, H - 1, 0, 0);
  output->SetSpacing(1, 1, 1);
  output->SetOrigin(0, 0, 0);
  vtkNew<vtkFloatArray> hdr;
  hdr->SetName("HDR");
  hdr->SetNumberOfComponents(4);
  hdr->SetNumberOfTuples(numPixels);
  vtkNew<vtkFloatArray> se;
  se->SetName("StandardError");
  se->SetNumberOfComponents(3);
  se->SetNumberOfTuples(numPixels);
  vtkNew<vtkUnsignedCharArray> rgb;
  rgb->SetName("RGB");
  rgb->SetNumberOfComponents(3);
  rgb->SetNumberOfTuples(numPixels);
  for (int64_t p = 0; p < numPixels; ++p)
  {
    for (int c = 0; c < 3; ++c)
    {
      hdr->SetTypedComponent(p, c, static_cast<float>(mean[3 * p + c]));
      se->SetTypedComponent(p, c, static_cast<float>(stderrs[3 * p + c]));
      rgb->SetTypedComponent(p, c, ToneMap(mean[3 * p + c], this->Exposure));
    }
    hdr->SetTypedComponent(p, 3, 1.0f);
  }
  output->GetPointData()->AddArray(hdr);
  output->GetPointData()->AddArray(se);
  output->GetPointData()->SetScalars(rgb);

  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  auto addField = [output](const char* name, double value, bool integer)
  {
    if (integer)
    {
      vtkNew<vtkIntArray> a;
      a->SetName(name);
      a->InsertNextValue(static_cast<int>(value));
      output->GetFieldData()->AddArray(a);
    }
    else
    {
      vtkNew<vtkDoubleArray> a;
      a->SetName(name);
      a->InsertNextValue(value);
      output->GetFieldData()->AddArray(a);
    }
  };
  addField("SamplesPerPixel", spp, true);
  addField("RenderSeconds", seconds, false);
  addField("Seed", static_cast<double>(this->Seed), false);
  addField("TruncatedPaths", static_cast<double>(truncated.load()), false);
  addField("NonFiniteSamples", static_cast<double>(nonFinite.load()), false);
  addField("LightRadius", radius, false);
  return 1;
}

//------------------------------------------------------------------------------
void vtkReferenceRenderer::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Camera: " << this->Camera.Get() << "\n";
  os << indent << "Lights: " << this->Lights->GetNumberOfItems() << "\n";
  os << indent << "ImageSize: " << this->ImageSize[0] << " x " << this->ImageSize[1] << "\n";
  os << indent << "BackgroundColor: " << this->BackgroundColor[0] << " " << this->BackgroundColor[1]
     << " " << this->BackgroundColor[2] << "\n";
  os << indent << "EnvironmentMap: " << this->EnvironmentMap.Get() << "\n";
  os << indent << "EnvironmentUp: (" << this->EnvironmentUp[0] << ", " << this->EnvironmentUp[1]
     << ", " << this->EnvironmentUp[2] << ")\n";
  os << indent << "EnvironmentRight: (" << this->EnvironmentRight[0] << ", "
     << this->EnvironmentRight[1] << ", " << this->EnvironmentRight[2] << ")\n";
  os << indent << "SamplesPerPixel: " << this->SamplesPerPixel << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "MaximumScatteringDepth: " << this->MaximumScatteringDepth << "\n";
  os << indent << "RouletteDepth: " << this->RouletteDepth << "\n";
  os << indent << "MaximumPathVertices: " << this->MaximumPathVertices << "\n";
  os << indent << "IntegratorTolerance: " << this->IntegratorTolerance << "\n";
  os << indent << "MaximumStep: " << this->MaximumStep << "\n";
  os << indent << "DirectionalLightAngularRadius: " << this->DirectionalLightAngularRadius << "\n";
  os << indent << "LightRadius: " << this->LightRadius << "\n";
  os << indent << "PixelJitter: " << this->PixelJitter << "\n";
  os << indent << "Exposure: " << this->Exposure << "\n";
}
