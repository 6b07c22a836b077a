// Host-side geometry of vtkIlluminationNetwork: see vtkIlluminationNetworkInternals.h.
#include "vtkIlluminationNetworkInternals.h"

#include "vtkDataArray.h"
#include "vtkIlluminationNetwork.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkRefractaParticleMedium.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <random>

namespace vtkIlluminationNetworkGeometry
{
namespace
{
constexpr double Pi = 3.14159265358979323846;

double Component(vtkDataArray* array, vtkIdType i, int c, double fallback)
{
  return array ? array->GetComponent(i, c) : fallback;
}

// An orthonormal basis (u, v) of the plane perpendicular to the unit vector w.
void PlaneBasis(const double w[3], double u[3], double v[3])
{
  const double a[3] = { std::fabs(w[0]) < 0.9 ? 1.0 : 0.0, std::fabs(w[0]) < 0.9 ? 0.0 : 1.0, 0 };
  // u = normalize(a x w), v = w x u
  u[0] = a[1] * w[2] - a[2] * w[1];
  u[1] = a[2] * w[0] - a[0] * w[2];
  u[2] = a[0] * w[1] - a[1] * w[0];
  const double len = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  for (int k = 0; k < 3; ++k)
  {
    u[k] /= len;
  }
  v[0] = w[1] * u[2] - w[2] * u[1];
  v[1] = w[2] * u[0] - w[0] * u[2];
  v[2] = w[0] * u[1] - w[1] * u[0];
}

// One particle on a line: the line's key (pixel), its depth along the line and its index.
struct LineEntry
{
  std::int64_t Key;
  double Depth;
  int Particle;
  bool operator<(const LineEntry& o) const
  {
    return Key != o.Key ? Key < o.Key
                        : (Depth != o.Depth ? Depth < o.Depth : Particle < o.Particle);
  }
};

// Orthographic line bundle along unit direction w with square pixels of side `pixel`.
std::vector<LineEntry> OrthographicLines(const Particles& ps, const double w[3], double pixel)
{
  double u[3], v[3];
  PlaneBasis(w, u, v);
  const double r = ps.BoundingRadius;
  const std::int64_t m = static_cast<std::int64_t>(std::ceil(2.0 * r / pixel)) + 1;
  std::vector<LineEntry> lines(static_cast<size_t>(ps.N));
  for (vtkIdType p = 0; p < ps.N; ++p)
  {
    const double* x = &ps.Position[3 * p];
    const double d[3] = { x[0] - ps.Center[0], x[1] - ps.Center[1], x[2] - ps.Center[2] };
    const double s = d[0] * u[0] + d[1] * u[1] + d[2] * u[2];
    const double t = d[0] * v[0] + d[1] * v[1] + d[2] * v[2];
    const std::int64_t ix =
      std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((s + r) / pixel)), 0, m - 1);
    const std::int64_t iy =
      std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((t + r) / pixel)), 0, m - 1);
    lines[p] = { iy * m + ix, d[0] * w[0] + d[1] * w[1] + d[2] * w[2], static_cast<int>(p) };
  }
  std::sort(lines.begin(), lines.end());
  return lines;
}

// Perspective line bundle from a point: a cube map whose pixels have side `pixel` at the median
// distance of the particles; depth = distance from the point.
std::vector<LineEntry> CubeMapLines(const Particles& ps, const double o[3], double pixel)
{
  std::vector<double> distance(static_cast<size_t>(ps.N));
  for (vtkIdType p = 0; p < ps.N; ++p)
  {
    const double* x = &ps.Position[3 * p];
    distance[p] = std::sqrt((x[0] - o[0]) * (x[0] - o[0]) + (x[1] - o[1]) * (x[1] - o[1]) +
      (x[2] - o[2]) * (x[2] - o[2]));
  }
  std::vector<double> sorted = distance;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  const double median = std::max(sorted[sorted.size() / 2], pixel);
  const std::int64_t m = std::max<std::int64_t>(1, std::llround(std::ceil(2.0 * median / pixel)));
  std::vector<LineEntry> lines(static_cast<size_t>(ps.N));
  for (vtkIdType p = 0; p < ps.N; ++p)
  {
    const double* x = &ps.Position[3 * p];
    const double d[3] = { x[0] - o[0], x[1] - o[1], x[2] - o[2] };
    int axis = 0;
    for (int k = 1; k < 3; ++k)
    {
      axis = std::fabs(d[k]) > std::fabs(d[axis]) ? k : axis;
    }
    const double major = std::fabs(d[axis]);
    std::int64_t key = 0;
    if (major > 0)
    {
      const int face = 2 * axis + (d[axis] < 0 ? 1 : 0);
      const double s = d[(axis + 1) % 3] / major;
      const double t = d[(axis + 2) % 3] / major;
      const std::int64_t ix =
        std::clamp<std::int64_t>(static_cast<std::int64_t>((s + 1) * 0.5 * m), 0, m - 1);
      const std::int64_t iy =
        std::clamp<std::int64_t>(static_cast<std::int64_t>((t + 1) * 0.5 * m), 0, m - 1);
      key = (face * m + iy) * m + ix + 1; // key 0: a particle exactly at the light
    }
    lines[p] = { key, distance[p], static_cast<int>(p) };
  }
  std::sort(lines.begin(), lines.end());
  return lines;
}

// Transmittance (3N) of the particles in front of each particle along sorted lines.
std::vector<double> LineTransmittance(const Particles& ps, const std::vector<LineEntry>& lines)
{
  std::vector<double> t(3 * static_cast<size_t>(ps.N), 1.0);
  double running[3] = { 1, 1, 1 };
  for (size_t k = 0; k < lines.size(); ++k)
  {
    if (k == 0 || lines[k].Key != lines[k - 1].Key)
    {
      running[0] = running[1] = running[2] = 1.0;
    }
    const int p = lines[k].Particle;
    for (int c = 0; c < 3; ++c)
    {
      t[3 * p + c] = running[c];
      running[c] *= 1.0 - ps.Opacity[3 * p + c];
    }
  }
  return t;
}

double HenyeyGreenstein(double g, double cosine)
{
  const double denominator = 1.0 + g * g - 2.0 * g * cosine;
  return (1.0 - g * g) / (4.0 * Pi * denominator * std::sqrt(denominator));
}
}

//------------------------------------------------------------------------------
void ReadParticles(vtkPointSet* input, Particles& out)
{
  vtkPointData* pd = input->GetPointData();
  vtkDataArray* radius = pd->GetArray(vtkRefractaParticleMedium::RadiusName());
  vtkDataArray* extinction = pd->GetArray(vtkRefractaParticleMedium::ExtinctionName());
  vtkDataArray* albedo = pd->GetArray(vtkRefractaParticleMedium::AlbedoName());
  vtkDataArray* g = pd->GetArray(vtkRefractaParticleMedium::AnisotropyName());
  vtkDataArray* emission = pd->GetArray(vtkRefractaParticleMedium::EmissionName());
  const vtkIdType n = input->GetNumberOfPoints();
  out.N = n;
  out.Position.resize(3 * n);
  out.Radius.resize(n);
  out.Opacity.resize(3 * n);
  out.Albedo.resize(3 * n);
  out.Anisotropy.resize(n);
  out.Emission.resize(3 * n);
  double lo[3] = { HUGE_VAL, HUGE_VAL, HUGE_VAL }, hi[3] = { -HUGE_VAL, -HUGE_VAL, -HUGE_VAL };
  double radiusSum = 0, largestRadius = 0;
  for (vtkIdType p = 0; p < n; ++p)
  {
    input->GetPoint(p, &out.Position[3 * p]);
    const double r = radius->GetComponent(p, 0);
    out.Radius[p] = r;
    radiusSum += r;
    largestRadius = std::max(largestRadius, r);
    const double chord = vtkRefractaParticleMedium::MeanChord(r);
    for (int c = 0; c < 3; ++c)
    {
      lo[c] = std::min(lo[c], out.Position[3 * p + c]);
      hi[c] = std::max(hi[c], out.Position[3 * p + c]);
      out.Opacity[3 * p + c] =
        static_cast<float>(-std::expm1(-extinction->GetComponent(p, c) * chord));
      out.Albedo[3 * p + c] = static_cast<float>(Component(albedo, p, c, 0.0));
      out.Emission[3 * p + c] = static_cast<float>(Component(emission, p, c, 0.0) * chord);
    }
    out.Anisotropy[p] = static_cast<float>(Component(g, p, 0, 0.0));
  }
  double r2 = 0;
  for (int c = 0; c < 3; ++c)
  {
    out.Center[c] = 0.5 * (lo[c] + hi[c]);
  }
  for (vtkIdType p = 0; p < n; ++p)
  {
    double d2 = 0;
    for (int c = 0; c < 3; ++c)
    {
      d2 += (out.Position[3 * p + c] - out.Center[c]) * (out.Position[3 * p + c] - out.Center[c]);
    }
    r2 = std::max(r2, d2);
  }
  out.BoundingRadius = std::sqrt(r2) + largestRadius;
  out.MeanRadius = radiusSum / static_cast<double>(n);
}

//------------------------------------------------------------------------------
std::vector<double> FibonacciDirections(int d)
{
  std::vector<double> dirs(3 * static_cast<size_t>(d));
  const double golden = Pi * (3.0 - std::sqrt(5.0));
  for (int k = 0; k < d; ++k)
  {
    const double z = 1.0 - (2.0 * k + 1.0) / d;
    const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
    dirs[3 * k] = s * std::cos(golden * k);
    dirs[3 * k + 1] = s * std::sin(golden * k);
    dirs[3 * k + 2] = z;
  }
  return dirs;
}

//------------------------------------------------------------------------------
std::array<double, 9> RandomRotation(unsigned int seed, unsigned int index)
{
  // A uniformly distributed unit quaternion (Shoemake 1992) from a stream seeded by (seed, index).
  std::seed_seq sequence{ seed, index, 0x1f2e3d4cu };
  std::mt19937_64 rng(sequence);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const double u1 = uniform(rng), u2 = uniform(rng), u3 = uniform(rng);
  const double a = std::sqrt(1 - u1), b = std::sqrt(u1);
  const double x = a * std::sin(2 * Pi * u2), y = a * std::cos(2 * Pi * u2);
  const double z = b * std::sin(2 * Pi * u3), w = b * std::cos(2 * Pi * u3);
  return { 1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w), 2 * (x * y + z * w),
    1 - 2 * (x * x + z * z), 2 * (y * z - x * w), 2 * (x * z - y * w), 2 * (y * z + x * w),
    1 - 2 * (x * x + y * y) };
}

//------------------------------------------------------------------------------
std::vector<double> Rotate(const std::vector<double>& directions, const std::array<double, 9>& r)
{
  std::vector<double> out(directions.size());
  for (size_t k = 0; k < directions.size(); k += 3)
  {
    for (int row = 0; row < 3; ++row)
    {
      out[k + row] = r[3 * row] * directions[k] + r[3 * row + 1] * directions[k + 1] +
        r[3 * row + 2] * directions[k + 2];
    }
  }
  return out;
}

//------------------------------------------------------------------------------
void BuildVisibility(const Particles& particles, const std::vector<double>& directions,
  double pixel, std::vector<int>& visible, std::vector<unsigned char>& hasNext)
{
  const int d = static_cast<int>(directions.size() / 3);
  visible.assign(static_cast<size_t>(particles.N) * d, -1);
  hasNext.assign(static_cast<size_t>(particles.N) * d, 0);
  // Directions are independent: each writes its own column of V.
  vtkSMPTools::For(0, d,
    [&](int first, int last)
    {
      for (int i = first; i < last; ++i)
      {
        const std::vector<LineEntry> lines =
          OrthographicLines(particles, &directions[3 * i], pixel);
        for (size_t k = 1; k < lines.size(); ++k)
        {
          if (lines[k].Key == lines[k - 1].Key)
          {
            visible[static_cast<size_t>(lines[k].Particle) * d + i] = lines[k - 1].Particle;
            hasNext[static_cast<size_t>(lines[k - 1].Particle) * d + i] = 1;
          }
        }
      }
    });
}

//------------------------------------------------------------------------------
void BuildPhase(const Particles& particles, const std::vector<double>& directions,
  std::vector<int>& phaseClass, std::vector<float>& phase)
{
  const int d = static_cast<int>(directions.size() / 3);
  std::map<float, int> classes;
  for (float g : particles.Anisotropy)
  {
    classes.emplace(g, 0);
  }
  const int levels = 64;
  const bool quantise = classes.size() > static_cast<size_t>(levels);
  std::vector<double> gOfClass;
  if (quantise)
  {
    for (int k = 0; k < levels; ++k)
    {
      gOfClass.push_back(-0.99 + 1.98 * k / (levels - 1));
    }
  }
  else
  {
    for (auto& entry : classes)
    {
      entry.second = static_cast<int>(gOfClass.size());
      gOfClass.push_back(entry.first);
    }
  }
  phaseClass.resize(static_cast<size_t>(particles.N));
  for (vtkIdType p = 0; p < particles.N; ++p)
  {
    const float g = particles.Anisotropy[p];
    phaseClass[p] = quantise
      ? std::clamp(static_cast<int>(std::lround((g + 0.99) / 1.98 * (levels - 1))), 0, levels - 1)
      : classes[g];
  }
  phase.assign(gOfClass.size() * d * d, 0.0f);
  for (size_t k = 0; k < gOfClass.size(); ++k)
  {
    for (int a = 0; a < d; ++a)
    {
      std::vector<double> row(d);
      double sum = 0;
      for (int b = 0; b < d; ++b)
      {
        const double cosine = directions[3 * a] * directions[3 * b] +
          directions[3 * a + 1] * directions[3 * b + 1] +
          directions[3 * a + 2] * directions[3 * b + 2];
        row[b] = HenyeyGreenstein(gOfClass[k], std::clamp(cosine, -1.0, 1.0));
        sum += row[b];
      }
      for (int b = 0; b < d; ++b)
      {
        phase[(k * d + a) * d + b] = static_cast<float>(row[b] / sum);
      }
    }
  }
}

//------------------------------------------------------------------------------
void DirectIrradiance(const Particles& particles, const Light& light, double pixel,
  std::vector<double>& irradiance, std::vector<double>& travel)
{
  const size_t n = static_cast<size_t>(particles.N);
  irradiance.assign(3 * n, 0.0);
  travel.assign(3 * n, 0.0);
  if (light.Type == vtkIlluminationNetwork::NO_LIGHT)
  {
    return;
  }
  if (light.Type == vtkIlluminationNetwork::DIRECTIONAL_LIGHT)
  {
    double w[3] = { light.Direction[0], light.Direction[1], light.Direction[2] };
    const double len = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    for (double& c : w)
    {
      c /= len;
    }
    const std::vector<double> t =
      LineTransmittance(particles, OrthographicLines(particles, w, pixel));
    for (size_t p = 0; p < n; ++p)
    {
      for (int c = 0; c < 3; ++c)
      {
        irradiance[3 * p + c] = light.Intensity[c] * t[3 * p + c];
        travel[3 * p + c] = w[c];
      }
    }
    return;
  }
  const std::vector<double> t =
    LineTransmittance(particles, CubeMapLines(particles, light.Position, pixel));
  for (size_t p = 0; p < n; ++p)
  {
    const double* x = &particles.Position[3 * p];
    const double d[3] = { x[0] - light.Position[0], x[1] - light.Position[1],
      x[2] - light.Position[2] };
    // The inverse square is capped at the particle's radius: a light inside a particle
    // illuminates it as if it were on its surface.
    const double r2 =
      std::max(d[0] * d[0] + d[1] * d[1] + d[2] * d[2], particles.Radius[p] * particles.Radius[p]);
    const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (int c = 0; c < 3; ++c)
    {
      irradiance[3 * p + c] = light.Intensity[c] / r2 * t[3 * p + c];
      travel[3 * p + c] = len > 0 ? d[c] / len : (c == 2 ? 1.0 : 0.0);
    }
  }
}

//------------------------------------------------------------------------------
void BuildEmitted(const Particles& particles, const std::vector<double>& directions,
  const std::vector<int>& phaseClass, const std::vector<float>& phase,
  const std::vector<double>& irradiance, const std::vector<double>& travel,
  std::vector<float>& emitted)
{
  const int d = static_cast<int>(directions.size() / 3);
  emitted.assign(static_cast<size_t>(particles.N) * d * 3, 0.0f);
  // W rows sum to 1 and the quadrature weight of a direction is 4 pi / D, so the radiance that
  // carries the power fraction W[l, i] along direction i is W[l, i] * D / (4 pi).
  const double toRadiance = d / (4.0 * Pi);
  vtkSMPTools::For(0, particles.N,
    [&](vtkIdType first, vtkIdType last)
    {
      for (vtkIdType p = first; p < last; ++p)
      {
        int nearest = 0;
        double best = -2;
        for (int i = 0; i < d; ++i)
        {
          const double cosine = travel[3 * p] * directions[3 * i] +
            travel[3 * p + 1] * directions[3 * i + 1] + travel[3 * p + 2] * directions[3 * i + 2];
          if (cosine > best)
          {
            best = cosine;
            nearest = i;
          }
        }
        const float* row = &phase[(static_cast<size_t>(phaseClass[p]) * d + nearest) * d];
        for (int i = 0; i < d; ++i)
        {
          for (int c = 0; c < 3; ++c)
          {
            const double scattered = particles.Opacity[3 * p + c] * particles.Albedo[3 * p + c] *
              irradiance[3 * p + c] * row[i] * toRadiance;
            emitted[(static_cast<size_t>(p) * d + i) * 3 + c] =
              static_cast<float>(scattered + particles.Emission[3 * p + c]);
          }
        }
      }
    });
}

//------------------------------------------------------------------------------
std::vector<int> NearestDirections(const std::vector<double>& from, const std::vector<double>& to)
{
  const size_t nf = from.size() / 3, nt = to.size() / 3;
  std::vector<int> nearest(nt, 0);
  for (size_t i = 0; i < nt; ++i)
  {
    double best = -2;
    for (size_t j = 0; j < nf; ++j)
    {
      const double cosine =
        to[3 * i] * from[3 * j] + to[3 * i + 1] * from[3 * j + 1] + to[3 * i + 2] * from[3 * j + 2];
      if (cosine > best)
      {
        best = cosine;
        nearest[i] = static_cast<int>(j);
      }
    }
  }
  return nearest;
}
}
