// vtkLightRaySingleScattering's voxel average on edge voxels (VoxelAverage): S1 as the mean of
// sigma_s phi over the voxel's box, the quantity the photon pass deposits and the lattice's
// per-voxel source needs, where the voxel's centre value would miss it (sharp density edges).
// Written to the RadianceVoxelMean array; Radiance keeps the centre values the view pass
// interpolates.
#include "vtkLightRaySingleScattering.h"
#include "vtkLightRaySingleScatteringInternals.h"

#include <algorithm>
#include <array>
#include <cmath>

using namespace vtkPhotonTracerDetail;

namespace
{
// Sub-points per edge voxel: the centres of the voxel's 8 octants, at +-1/4 voxel on each axis.
constexpr int SubPoints = 8;

size_t Index(const Medium& m, int i, int j, int k)
{
  return i + m.Dims[0] * (j + static_cast<size_t>(m.Dims[1]) * k);
}

int Clamp(int i, int n)
{
  return std::min(std::max(i, 0), n - 1);
}

// sigma_s (RGB) at the continuous voxel coordinate u (voxel centres at integers), trilinear and
// clamped to the edge voxels in the outer half voxel: the medium every pass samples.
std::array<double, 3> Trilinear(const Medium& m, const std::vector<float>& sc, const double u[3])
{
  int lo[3], hi[3];
  double f[3];
  for (int a = 0; a < 3; ++a)
  {
    const double x = std::min(std::max(u[a], 0.0), static_cast<double>(m.Dims[a] - 1));
    lo[a] = Clamp(static_cast<int>(std::floor(x)), m.Dims[a]);
    hi[a] = Clamp(lo[a] + 1, m.Dims[a]);
    f[a] = x - lo[a];
  }
  std::array<double, 3> out = { 0, 0, 0 };
  for (int corner = 0; corner < 8; ++corner)
  {
    const int b[3] = { corner & 1, (corner >> 1) & 1, (corner >> 2) & 1 };
    const double w = (b[0] ? f[0] : 1 - f[0]) * (b[1] ? f[1] : 1 - f[1]) * (b[2] ? f[2] : 1 - f[2]);
    const size_t v =
      Index(m, b[0] ? hi[0] : lo[0], b[1] ? hi[1] : lo[1], b[2] ? hi[2] : lo[2]);
    for (int c = 0; c < 3; ++c)
    {
      out[c] += w * sc[3 * v + c];
    }
  }
  return out;
}

// The exact mean of the trilinear sigma_s over voxel (i, j, k)'s box: per axis the hat functions
// of the neighbours i - 1, i, i + 1 integrate to 1/8, 3/4, 1/8 over [i - 1/2, i + 1/2] (indices
// clamped at the faces, where the field is clamped).
std::array<double, 3> BoxMean(const Medium& m, const std::vector<float>& sc, int i, int j, int k)
{
  static const double w[3] = { 0.125, 0.75, 0.125 };
  std::array<double, 3> out = { 0, 0, 0 };
  for (int c2 = -1; c2 <= 1; ++c2)
  {
    for (int b = -1; b <= 1; ++b)
    {
      for (int a = -1; a <= 1; ++a)
      {
        const double weight = w[a + 1] * w[b + 1] * w[c2 + 1];
        const size_t v = Index(
          m, Clamp(i + a, m.Dims[0]), Clamp(j + b, m.Dims[1]), Clamp(k + c2, m.Dims[2]));
        for (int c = 0; c < 3; ++c)
        {
          out[c] += weight * sc[3 * v + c];
        }
      }
    }
  }
  return out;
}
}

//------------------------------------------------------------------------------
// Edge voxels: where the box mean of sigma_s differs from the centre value by more than
// EdgeTolerance of the larger (any channel). The centre value sigma_s(x_c) phi(x_c) is then
// replaced by the midpoint rule over the 8 octants, (1/8) sum sigma_s(x_q) phi(x_q), which
// integrates the trilinear sigma_s exactly (it is multilinear within each octant) and phi to
// O(h^2).
std::vector<size_t> vtkLightRaySingleScattering::FindEdgeVoxels(Internals& run) const
{
  const Medium& m = run.M;
  std::vector<size_t> edges;
  for (int k = 0; k < m.Dims[2]; ++k)
  {
    for (int j = 0; j < m.Dims[1]; ++j)
    {
      for (int i = 0; i < m.Dims[0]; ++i)
      {
        const size_t v = Index(m, i, j, k);
        const std::array<double, 3> mean = BoxMean(m, run.Scattering, i, j, k);
        bool edge = false;
        for (int c = 0; c < 3 && !edge; ++c)
        {
          const double centre = run.Scattering[3 * v + c];
          const double larger = std::max(centre, mean[c]);
          edge = larger > 0 && std::fabs(mean[c] - centre) > this->EdgeTolerance * larger;
        }
        if (edge)
        {
          edges.push_back(v);
        }
      }
    }
  }
  return edges;
}

bool vtkLightRaySingleScattering::AverageEdgeVoxels(Internals& run)
{
  const auto start = Clock::now();
  this->NumberOfAveragedVoxels = 0;
  if (!this->VoxelAverage)
  {
    return true;
  }
  run.VoxelMean->DeepCopy(run.Radiance);
  const Medium& m = run.M;
  const std::vector<size_t> edges = this->FindEdgeVoxels(run);
  std::vector<float> points(4 * SubPoints * edges.size(), 0.0f);
  for (size_t e = 0; e < edges.size(); ++e)
  {
    const size_t v = edges[e];
    const int ijk[3] = { static_cast<int>(v % m.Dims[0]),
      static_cast<int>((v / m.Dims[0]) % m.Dims[1]),
      static_cast<int>(v / (static_cast<size_t>(m.Dims[0]) * m.Dims[1])) };
    for (int q = 0; q < SubPoints; ++q)
    {
      for (int a = 0; a < 3; ++a)
      {
        const double u = ijk[a] + (((q >> a) & 1) ? 0.25 : -0.25);
        points[4 * (SubPoints * e + q) + a] = static_cast<float>(u * m.Spacing[a]);
      }
    }
  }
  std::vector<float> phi, flux;
  if (!this->EvaluatePoints(run, points, nullptr, run.LightCount, phi, flux))
  {
    return false;
  }
  float* mean = run.VoxelMean->GetPointer(0);
  for (size_t e = 0; e < edges.size(); ++e)
  {
    double s1[3] = { 0, 0, 0 };
    for (int q = 0; q < SubPoints; ++q)
    {
      const size_t p = SubPoints * e + q;
      double u[3];
      for (int a = 0; a < 3; ++a)
      {
        u[a] = points[4 * p + a] / m.Spacing[a];
      }
      const std::array<double, 3> sc = Trilinear(m, run.Scattering, u);
      for (int c = 0; c < 3; ++c)
      {
        s1[c] += sc[c] * std::max(0.0f, phi[4 * p + c]) / SubPoints;
      }
    }
    for (int c = 0; c < 3; ++c)
    {
      mean[3 * edges[e] + c] = static_cast<float>(s1[c]);
    }
  }
  this->NumberOfAveragedVoxels = static_cast<long long>(edges.size());
  this->AveragingSeconds = Seconds(start);
  return true;
}
