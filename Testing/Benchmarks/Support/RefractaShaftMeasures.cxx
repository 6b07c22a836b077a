#include "RefractaShaftMeasures.h"

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkPointData.h"
#include "vtkRefractaLightingVolume.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace RefractaShaftMeasures
{
ScatteringLattice FineScatteringLattice(vtkImageData* lighting, int factor)
{
  ScatteringLattice l;
  vtkDataArray* s1 = lighting
    ? lighting->GetPointData()->GetArray(vtkRefractaLightingVolume::RadianceName())
    : nullptr;
  if (!s1)
  {
    return l;
  }
  vtkFieldData* fd = lighting->GetFieldData();
  vtkDataArray* bricks = fd->GetArray(vtkRefractaLightingVolume::VolumeCausticBricksName());
  vtkDataArray* fine = fd->GetArray(vtkRefractaLightingVolume::VolumeCausticRadianceName());
  int d[3];
  double origin[3], h[3];
  lighting->GetDimensions(d);
  lighting->GetOrigin(origin);
  lighting->GetSpacing(h);
  const int c = vtkRefractaLightingVolume::GetVolumeCausticSubdivision(lighting);
  for (int a = 0; a < 3; ++a)
  {
    l.Dimensions[a] = factor * d[a];
    l.Spacing[a] = h[a] / factor;
    l.Origin[a] = origin[a] - 0.5 * h[a] + 0.5 * l.Spacing[a];
  }
  l.S1.assign(static_cast<size_t>(l.Dimensions[0]) * l.Dimensions[1] * l.Dimensions[2], 0.0f);
  size_t i = 0;
  for (int z = 0; z < l.Dimensions[2]; ++z)
  {
    for (int y = 0; y < l.Dimensions[1]; ++y)
    {
      for (int x = 0; x < l.Dimensions[0]; ++x, ++i)
      {
        const int f[3] = { x, y, z };
        int v[3], b[3];
        for (int a = 0; a < 3; ++a)
        {
          v[a] = f[a] / factor; // the voxel, and the fine point's fine voxel in its brick
          b[a] = std::min(c - 1, static_cast<int>((f[a] % factor + 0.5) * c / factor));
        }
        const vtkIdType voxel = v[0] + vtkIdType(d[0]) * (v[1] + vtkIdType(d[1]) * v[2]);
        double value = s1->GetComponent(voxel, 0);
        const int brick = c > 1 ? static_cast<int>(bricks->GetComponent(voxel, 0)) : -1;
        if (brick >= 0)
        {
          value += fine->GetComponent(brick * vtkIdType(c) * c * c + (b[2] * c + b[1]) * c + b[0], 0);
        }
        l.S1[i] = static_cast<float>(value);
      }
    }
  }
  return l;
}

double PairNoise(const std::vector<double>& mask, const std::vector<double>& a,
  const std::vector<double>& b, int size, int firstRow, int lastRow)
{
  double squares = 0, sum = 0;
  int count = 0;
  const size_t n = static_cast<size_t>(size) * size;
  if (a.size() != n || b.size() != n || mask.size() != n)
  {
    return 0.0;
  }
  for (int row = std::max(firstRow, 0); row <= std::min(lastRow, size - 1); ++row)
  {
    const std::vector<double> line = ImageRow(mask, size, row);
    const double peak = *std::max_element(line.begin(), line.end());
    for (int i = 0; i < size; ++i)
    {
      if (line[i] > 0.1 * peak)
      {
        const size_t p = static_cast<size_t>(row) * size + i;
        squares += 0.5 * (a[p] - b[p]) * (a[p] - b[p]);
        sum += 0.5 * (a[p] + b[p]);
        ++count;
      }
    }
  }
  return count > 0 && sum > 0 ? std::sqrt(squares / count) / (sum / count) : 0.0;
}

double Fwhm(const std::vector<double>& values, int peak)
{
  const double half = 0.5 * values[peak];
  auto edge = [&](int step)
  {
    int k = peak;
    while (k + step >= 0 && k + step < static_cast<int>(values.size()) && values[k + step] >= half)
    {
      k += step;
    }
    const int out = k + step;
    if (out < 0 || out >= static_cast<int>(values.size()) || values[out] < 0)
    {
      return double(k) + 0.5 * step;
    }
    // Linear between the last pixel above and the first below.
    const double f = (values[k] - half) / (values[k] - values[out]);
    return k + step * f;
  };
  return edge(1) - edge(-1);
}

double ProfileFwhm(std::vector<double> values, double h, int reach)
{
  for (double& v : values)
  {
    v = std::max(v, 0.0);
  }
  int peak = -1;
  const int middle = static_cast<int>(values.size()) / 2;
  for (int i = std::max(0, middle - reach); i < std::min<int>(values.size(), middle + reach); ++i)
  {
    peak = (peak < 0 || values[i] > values[peak]) ? i : peak;
  }
  return peak < 0 || !(values[peak] > 0) ? 0.0 : Fwhm(values, peak) * h;
}

std::vector<double> LatticeProfile(
  const ScatteringLattice& r, const ScatteringLattice& reference, double y)
{
  std::vector<double> line;
  if (r.S1.empty() || r.S1.size() != reference.S1.size())
  {
    return line;
  }
  const int* n = r.Dimensions;
  const double fy = (y - r.Origin[1]) / r.Spacing[1], fz = -r.Origin[2] / r.Spacing[2];
  const int j = static_cast<int>(fy), k = static_cast<int>(fz);
  const double wy = fy - j, wz = fz - k;
  auto at = [&](int i, int jj, int kk)
  {
    const size_t p = i + static_cast<size_t>(n[0]) * (jj + static_cast<size_t>(n[1]) * kk);
    return static_cast<double>(r.S1[p]) - reference.S1[p];
  };
  for (int i = 0; i < n[0]; ++i)
  {
    if (std::abs(r.Origin[0] + i * r.Spacing[0]) < 0.44)
    {
      line.push_back((1 - wz) * ((1 - wy) * at(i, j, k) + wy * at(i, j + 1, k)) +
        wz * ((1 - wy) * at(i, j, k + 1) + wy * at(i, j + 1, k + 1)));
    }
  }
  return line;
}

double LatticeHalfRadius(const ScatteringLattice& r, const ScatteringLattice& reference, double y)
{
  if (r.S1.empty() || r.S1.size() != reference.S1.size())
  {
    return 0;
  }
  const int* n = r.Dimensions;
  const double fy = (y - r.Origin[1]) / r.Spacing[1];
  const int j = static_cast<int>(fy);
  const double wy = fy - j, ring = 0.001;
  std::vector<double> rings(static_cast<size_t>(0.5 / ring), 0.0);
  double total = 0;
  for (int k = 0; k < n[2]; ++k)
  {
    for (int i = 0; i < n[0]; ++i)
    {
      const double x = r.Origin[0] + i * r.Spacing[0], z = r.Origin[2] + k * r.Spacing[2];
      if (std::hypot(x, z) >= 0.44)
      {
        continue;
      }
      double v = 0;
      for (int dj = 0; dj < 2; ++dj)
      {
        const size_t p = i + static_cast<size_t>(n[0]) * (j + dj + static_cast<size_t>(n[1]) * k);
        v += (dj ? wy : 1 - wy) * (static_cast<double>(r.S1[p]) - reference.S1[p]);
      }
      total += v;
      for (int a = 0; a < 64; ++a)
      {
        const double sx = x + ((a % 8 + 0.5) / 8 - 0.5) * r.Spacing[0];
        const double sz = z + ((a / 8 + 0.5) / 8 - 0.5) * r.Spacing[2];
        rings[std::min(rings.size() - 1, static_cast<size_t>(std::hypot(sx, sz) / ring))] += v / 64;
      }
    }
  }
  double sum = 0;
  for (size_t k = 0; k < rings.size() && total > 0; ++k)
  {
    if (sum + rings[k] >= 0.5 * total && rings[k] > 0)
    {
      return (k + (0.5 * total - sum) / rings[k]) * ring;
    }
    sum += rings[k];
  }
  return 0;
}

double DirectLightResidual(const ScatteringLattice& r, const ScatteringLattice& reference)
{
  const int* n = r.Dimensions;
  const int j = static_cast<int>(std::lround((-0.6 - r.Origin[1]) / r.Spacing[1]));
  double sum = 0, peak = 0;
  int count = 0;
  for (int k = 0; k < n[2] && r.S1.size() == reference.S1.size(); ++k)
  {
    for (int i = 0; i < n[0]; ++i)
    {
      const size_t p = i + static_cast<size_t>(n[0]) * (j + static_cast<size_t>(n[1]) * k);
      const double d = static_cast<double>(r.S1[p]) - reference.S1[p];
      const double rho = std::hypot(r.Origin[0] + i * r.Spacing[0], r.Origin[2] + k * r.Spacing[2]);
      peak = std::max(peak, d);
      if (rho > 0.55 && rho < 0.75)
      {
        sum += std::abs(d);
        ++count;
      }
    }
  }
  return count && peak > 0 ? sum / count / peak : 0.0;
}
std::vector<double> ImageRow(const std::vector<double>& image, int size, int row)
{
  return std::vector<double>(image.begin() + static_cast<size_t>(size) * row,
    image.begin() + static_cast<size_t>(size) * (row + 1));
}

std::vector<double> RedDifference(const std::vector<float>& a, const std::vector<float>& b)
{
  std::vector<double> d(a.size() == b.size() ? a.size() / 4 : 0, 0.0);
  for (size_t p = 0; p < d.size(); ++p)
  {
    d[p] = a[4 * p] - b[4 * p];
  }
  return d;
}
}
