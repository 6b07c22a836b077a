// The rasterisation stages of vtkMeshVoxelizer (see vtkMeshVoxelizerRaster.h).
#include "vtkMeshVoxelizerRaster.h"

#include "vtkMediumMaterial.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#if defined(__linux__)
#include <sys/mman.h> // madvise
#endif

namespace refracta_voxelize
{
// Range of voxel indices along one axis whose closed box overlaps [lo, hi]; empty when first >
// last. Slightly conservative (a voxel too many only costs a test).
void VoxelRange(double lo, double hi, double origin, double spacing, int n, int& first, int& last)
{
  const double a = std::ceil((lo - origin) / spacing - 0.5 - 1e-9);
  const double b = std::floor((hi - origin) / spacing + 0.5 + 1e-9);
  first = static_cast<int>(std::max(0.0, std::min(a, static_cast<double>(n))));
  last = static_cast<int>(std::max(-1.0, std::min(b, static_cast<double>(n - 1))));
}

void RowBuckets::Build(const PreparedMesh& mesh, const Grid& g)
{
  const vtkIdType rows = static_cast<vtkIdType>(g.N[1]) * g.N[2];
  this->Offsets.assign(rows + 1, 0);
  const vtkIdType numTris = static_cast<vtkIdType>(mesh.Triangles.size());
  std::vector<int> ranges(4 * numTris);
  for (int pass = 0; pass < 2; ++pass)
  {
    std::vector<vtkIdType> fill;
    if (pass == 1)
    {
      std::partial_sum(this->Offsets.begin(), this->Offsets.end(), this->Offsets.begin());
      this->Ids.resize(this->Offsets[rows]);
      fill.assign(this->Offsets.begin(), this->Offsets.end() - 1);
    }
    for (vtkIdType t = 0; t < numTris; ++t)
    {
      int* r = &ranges[4 * t];
      if (pass == 0)
      {
        double b[6];
        mesh.GetTriangleBounds(t, b);
        VoxelRange(b[2], b[3], g.O[1], g.S[1], g.N[1], r[0], r[1]);
        VoxelRange(b[4], b[5], g.O[2], g.S[2], g.N[2], r[2], r[3]);
      }
      for (int k = r[2]; k <= r[3]; ++k)
      {
        for (int j = r[0]; j <= r[1]; ++j)
        {
          const vtkIdType row = j + static_cast<vtkIdType>(g.N[1]) * k;
          if (pass == 0)
          {
            ++this->Offsets[row + 1];
          }
          else
          {
            this->Ids[fill[row]++] = t;
          }
        }
      }
    }
  }
}

void LineWalker::Start(const PreparedMesh* mesh, const vtkIdType* ids, size_t count, double y,
  double z, double tolerance, std::atomic<vtkIdType>& fallbacks)
{
  this->Mesh = mesh;
  this->Crossings.clear();
  this->Cursor = 0;
  this->Parity = 0;
  this->Y = y;
  this->Z = z;
  this->Tolerance = tolerance;
  this->Fallback = count > 0 && !mesh->LineCrossings(ids, count, y, z, this->Crossings);
  if (this->Fallback)
  {
    ++fallbacks;
  }
  std::sort(this->Crossings.begin(), this->Crossings.end());
}

double LineWalker::StateAt(double x)
{
  const double p[3] = { x, this->Y, this->Z };
  if (this->Fallback)
  {
    return this->Mesh->Classify(p);
  }
  const size_t n = this->Crossings.size();
  while (this->Cursor < n && this->Crossings[this->Cursor].X < x - this->Tolerance)
  {
    this->Parity ^= 1;
    ++this->Cursor;
  }
  int parity = this->Parity;
  // Crossings within rounding distance: decide exactly which side of the face p is on.
  for (size_t c = this->Cursor; c < n && this->Crossings[c].X <= x + this->Tolerance; ++c)
  {
    const int side = this->Mesh->SideAlongX(this->Crossings[c].Triangle, p);
    if (side == 0)
    {
      return 0.5;
    }
    parity ^= side > 0 ? 1 : 0;
  }
  return parity;
}

void Mixer::Init()
{
  this->Cached.resize(this->Materials.size());
  this->Heterogeneous.resize(this->Materials.size());
  for (size_t m = 0; m < this->Materials.size(); ++m)
  {
    this->Heterogeneous[m] = this->Materials[m]->IsHeterogeneous();
    Props& p = this->Cached[m];
    this->Materials[m]->GetPropertiesAtDensity(1.0, p.N, p.Ext, p.Alb, p.G, p.Em);
  }
}

void Mixer::Get(size_t m, const double x[3], Props& p) const
{
  if (!this->Heterogeneous[m])
  {
    p = this->Cached[m];
    return;
  }
  const double d = this->Materials[m]->EvaluateDensity(x);
  this->Materials[m]->GetPropertiesAtDensity(d, p.N, p.Ext, p.Alb, p.G, p.Em);
}

void Mixer::Mix(const double* fractions, const double x[3], vtkIdType v) const
{
  double n = 0, st[3] = { 0, 0, 0 }, ss[3] = { 0, 0, 0 }, alb[3] = { 0, 0, 0 };
  double em[3] = { 0, 0, 0 }, gw = 0, w = 0, gOcc = 0;
  Props p;
  for (size_t m = 0; m < this->Materials.size(); ++m)
  {
    const double f = fractions[m];
    if (f <= 0.0)
    {
      continue;
    }
    this->Get(m, x, p);
    n += f * p.N;
    double meanScattering = 0.0;
    for (int c = 0; c < 3; ++c)
    {
      st[c] += f * p.Ext[c];
      ss[c] += f * p.Alb[c] * p.Ext[c];
      alb[c] += f * p.Alb[c];
      em[c] += f * p.Em[c];
      meanScattering += p.Alb[c] * p.Ext[c] / 3.0;
    }
    gw += f * meanScattering * p.G;
    w += f * meanScattering;
    gOcc += f * p.G;
  }
  this->N[v] = static_cast<float>(std::max(1.0, n));
  for (int c = 0; c < 3; ++c)
  {
    this->Ext[3 * v + c] = static_cast<float>(st[c]);
    const double a = st[c] > 0.0 ? ss[c] / st[c] : alb[c];
    this->Alb[3 * v + c] = static_cast<float>(std::min(1.0, std::max(0.0, a)));
    this->Em[3 * v + c] = static_cast<float>(em[c]);
  }
  const double g = w > 0.0 ? gw / w : gOcc;
  this->G[v] = static_cast<float>(std::min(0.9999, std::max(-0.9999, g)));
  this->Occ[v] = static_cast<float>(std::min(1.0, std::max(0.0, 1.0 - fractions[0])));
}

// Ask Linux for transparent huge pages on a large fresh buffer: first-touching 60 bytes per voxel
// in 4 KiB pages costs seconds at 256^3 on machines with expensive page faults (VMs).
void AdviseHugePages(void* data, size_t bytes)
{
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  const std::uintptr_t huge = 2u << 20;
  const std::uintptr_t begin = (reinterpret_cast<std::uintptr_t>(data) + huge - 1) & ~(huge - 1);
  const std::uintptr_t end = (reinterpret_cast<std::uintptr_t>(data) + bytes) & ~(huge - 1);
  if (end > begin)
  {
    madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
  }
#else
  (void)data;
  (void)bytes;
#endif
}

// One pass of a separable convolution along `axis`, edge voxels replicated.
void SmoothAxis(float* data, const Grid& g, int axis, const std::vector<double>& weights)
{
  const int half = static_cast<int>(weights.size() / 2);
  const int n = g.N[axis];
  const vtkIdType stride[3] = { 1, g.N[0], static_cast<vtkIdType>(g.N[0]) * g.N[1] };
  const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
  const vtkIdType lines = static_cast<vtkIdType>(g.N[a1]) * g.N[a2];
  vtkSMPTools::For(0, lines,
    [&](vtkIdType begin, vtkIdType end)
    {
      std::vector<double> line(n);
      for (vtkIdType l = begin; l < end; ++l)
      {
        const vtkIdType u = l % g.N[a1], w = l / g.N[a1];
        float* base = data + u * stride[a1] + w * stride[a2];
        for (int i = 0; i < n; ++i)
        {
          line[i] = base[i * stride[axis]];
        }
        for (int i = 0; i < n; ++i)
        {
          double sum = 0.0;
          for (int t = -half; t <= half; ++t)
          {
            sum += weights[t + half] * line[std::min(n - 1, std::max(0, i + t))];
          }
          base[i * stride[axis]] = static_cast<float>(sum);
        }
      }
    });
}

//------------------------------------------------------------------------------
Rasterizer::Rasterizer(const std::vector<std::unique_ptr<PreparedMesh>>& meshes, const Grid& grid,
  int supersampling, bool surfaceOnly)
  : Meshes(meshes)
  , G(grid)
  , S(supersampling)
  , SurfaceOnly(surfaceOnly)
{
}

vtkIdType Rasterizer::GetNumberOfRows() const
{
  return static_cast<vtkIdType>(this->G.N[1]) * this->G.N[2];
}

void Rasterizer::Prepare()
{
  const int numMeshes = static_cast<int>(this->Meshes.size());
  // Owner order: the smallest enclosed volume wins (later connection on ties).
  this->InnermostFirst.resize(numMeshes);
  std::iota(this->InnermostFirst.begin(), this->InnermostFirst.end(), 0);
  std::sort(this->InnermostFirst.begin(), this->InnermostFirst.end(),
    [&](int a, int b)
    {
      return this->Meshes[a]->Volume < this->Meshes[b]->Volume ||
        (this->Meshes[a]->Volume == this->Meshes[b]->Volume && a > b);
    });
  this->Buckets.resize(numMeshes);
  for (int m = 0; m < numMeshes; ++m)
  {
    this->Buckets[m].Build(*this->Meshes[m], this->G);
  }
  this->Offsets.resize(this->S);
  for (int a = 0; a < this->S; ++a)
  {
    this->Offsets[a] = (a + 0.5) / this->S - 0.5;
  }
  // Crossings closer than this to a sample are decided by an exact orientation test; it covers
  // the rounding of the interpolated crossing x (relative to the coordinates' magnitude).
  const Grid& g = this->G;
  double maxAbsX = std::max(std::abs(g.O[0] - g.S[0]), std::abs(g.O[0] + g.N[0] * g.S[0]));
  for (const auto& m : this->Meshes)
  {
    maxAbsX = std::max(maxAbsX, std::max(std::abs(m->Bounds[0]), std::abs(m->Bounds[1])));
  }
  this->Tolerance = 1e-9 * g.S[0] + 1e-12 * maxAbsX;
}

//------------------------------------------------------------------------------
void Rasterizer::ClassifyRows(vtkIdType begin, vtkIdType end)
{
  const int numMeshes = static_cast<int>(this->Meshes.size());
  const Grid& g = this->G;
  const auto& meshes = this->Meshes;
  const auto& buckets = this->Buckets;
  const auto& offsets = this->Offsets;
  const auto& innermostFirst = this->InnermostFirst;
  const double tolerance = this->Tolerance;
  auto& labels = this->Labels;
  auto& fallbacks = this->Fallbacks;
  const bool surfaceOnly = this->SurfaceOnly;
  LineWalker walker;
  std::vector<double> state(g.N[0]);
  for (vtkIdType row = begin; row < end; ++row)
  {
    const int j = static_cast<int>(row % g.N[1]), k = static_cast<int>(row / g.N[1]);
    std::uint16_t* label = &labels[g.Id(0, j, k)];
    const double y = g.O[1] + (j + offsets[0]) * g.S[1];
    const double z = g.O[2] + (k + offsets[0]) * g.S[2];
    // Surface voxels: boxes that touch a triangle (exact test), or every voxel.
    for (int m = 0; m < numMeshes; ++m)
    {
      const vtkIdType* ids = buckets[m].Ids.data() + buckets[m].Offsets[row];
      const vtkIdType count = buckets[m].Offsets[row + 1] - buckets[m].Offsets[row];
      for (vtkIdType n = 0; n < count && surfaceOnly; ++n)
      {
        double b[6];
        meshes[m]->GetTriangleBounds(ids[n], b);
        int i0, i1;
        VoxelRange(b[0], b[1], g.O[0], g.S[0], g.N[0], i0, i1);
        for (int i = i0; i <= i1; ++i)
        {
          if (label[i] == SurfaceLabel)
          {
            continue;
          }
          const double box[6] = { g.O[0] + (i - 0.5) * g.S[0], g.O[0] + (i + 0.5) * g.S[0],
            g.O[1] + (j - 0.5) * g.S[1], g.O[1] + (j + 0.5) * g.S[1], g.O[2] + (k - 0.5) * g.S[2],
            g.O[2] + (k + 0.5) * g.S[2] };
          if (meshes[m]->TriangleTouchesBox(ids[n], box))
          {
            label[i] = SurfaceLabel;
          }
        }
      }
    }
    if (!surfaceOnly)
    {
      std::fill(label, label + g.N[0], SurfaceLabel);
      continue;
    }
    // One sample per remaining voxel: the whole box is on that sample's side of every mesh.
    std::fill(state.begin(), state.end(), 0.0);
    for (int r = numMeshes - 1; r >= 0; --r) // outermost first, inner ones overwrite
    {
      const int m = innermostFirst[r];
      const vtkIdType count = buckets[m].Offsets[row + 1] - buckets[m].Offsets[row];
      if (count == 0)
      {
        continue; // the line misses the mesh: outside
      }
      walker.Start(meshes[m].get(), buckets[m].Ids.data() + buckets[m].Offsets[row],
        static_cast<size_t>(count), y, z, tolerance, fallbacks);
      for (int i = 0; i < g.N[0]; ++i)
      {
        if (label[i] != SurfaceLabel && walker.StateAt(g.O[0] + (i + offsets[0]) * g.S[0]) > 0.75)
        {
          label[i] = static_cast<std::uint16_t>(m + 1);
        }
      }
    }
  }
}

//------------------------------------------------------------------------------
void Rasterizer::SupersampleRows(vtkIdType begin, vtkIdType end, const Mixer& mixer)
{
  const int numMeshes = static_cast<int>(this->Meshes.size());
  const Grid& g = this->G;
  const auto& meshes = this->Meshes;
  const auto& buckets = this->Buckets;
  const auto& offsets = this->Offsets;
  const auto& innermostFirst = this->InnermostFirst;
  const double tolerance = this->Tolerance;
  auto& labels = this->Labels;
  auto& fallbacks = this->Fallbacks;
  const int S = this->S;
  std::vector<LineWalker> walkers(numMeshes);
  std::vector<double> fractions; // (numMeshes + 1) per voxel of the row
  std::vector<int> surface;
  std::vector<double> state(numMeshes);
  for (vtkIdType row = begin; row < end; ++row)
  {
    const int j = static_cast<int>(row % g.N[1]), k = static_cast<int>(row / g.N[1]);
    const std::uint16_t* label = &labels[g.Id(0, j, k)];
    surface.clear();
    for (int i = 0; i < g.N[0]; ++i)
    {
      if (label[i] == SurfaceLabel)
      {
        surface.push_back(i);
      }
    }
    if (surface.empty())
    {
      continue;
    }
    this->Supersampled += static_cast<vtkIdType>(surface.size());
    fractions.assign(surface.size() * (numMeshes + 1), 0.0);
    for (int b = 0; b < S; ++b)
    {
      for (int a = 0; a < S; ++a)
      {
        const double y = g.O[1] + (j + offsets[a]) * g.S[1];
        const double z = g.O[2] + (k + offsets[b]) * g.S[2];
        for (int m = 0; m < numMeshes; ++m)
        {
          const vtkIdType count = buckets[m].Offsets[row + 1] - buckets[m].Offsets[row];
          walkers[m].Start(meshes[m].get(), buckets[m].Ids.data() + buckets[m].Offsets[row],
            static_cast<size_t>(count), y, z, tolerance, fallbacks);
        }
        for (size_t s = 0; s < surface.size(); ++s)
        {
          double* f = &fractions[s * (numMeshes + 1)];
          for (int c = 0; c < S; ++c)
          {
            const double x = g.O[0] + (surface[s] + offsets[c]) * g.S[0];
            // Innermost wins: each mesh takes its share of what inner meshes left.
            double remaining = 1.0;
            for (int r = 0; r < numMeshes && remaining > 0.0; ++r)
            {
              const int m = innermostFirst[r];
              const double take = remaining * walkers[m].StateAt(x);
              f[m + 1] += take;
              remaining -= take;
            }
            f[0] += remaining;
          }
        }
      }
    }
    const double norm = 1.0 / (static_cast<double>(S) * S * S);
    for (size_t s = 0; s < surface.size(); ++s)
    {
      double* f = &fractions[s * (numMeshes + 1)];
      for (int m = 0; m <= numMeshes; ++m)
      {
        f[m] *= norm;
      }
      const double x[3] = { g.O[0] + surface[s] * g.S[0], g.O[1] + j * g.S[1],
        g.O[2] + k * g.S[2] };
      mixer.Mix(f, x, g.Id(surface[s], j, k));
    }
  }
}

//------------------------------------------------------------------------------
void Rasterizer::MixInteriorVoxels(const Mixer& mixer)
{
  const int numMeshes = static_cast<int>(this->Meshes.size());
  const Grid& g = this->G;
  const auto& labels = this->Labels;
  const vtkIdType numVoxels = static_cast<vtkIdType>(labels.size());
  vtkSMPTools::For(0, numVoxels,
    [&](vtkIdType begin, vtkIdType end)
    {
      std::vector<double> f(numMeshes + 1, 0.0);
      for (vtkIdType v = begin; v < end; ++v)
      {
        const std::uint16_t l = labels[v];
        if (l == SurfaceLabel)
        {
          continue;
        }
        const int i = static_cast<int>(v % g.N[0]);
        const int j = static_cast<int>((v / g.N[0]) % g.N[1]);
        const int k = static_cast<int>(v / (static_cast<vtkIdType>(g.N[0]) * g.N[1]));
        const double x[3] = { g.O[0] + i * g.S[0], g.O[1] + j * g.S[1], g.O[2] + k * g.S[2] };
        f[l] = 1.0;
        mixer.Mix(f.data(), x, v);
        f[l] = 0.0;
      }
    });
  this->Labels = std::vector<std::uint16_t>();
}

//------------------------------------------------------------------------------
void SmoothIndex(float* n, const Grid& g, int window, double sigma)
{
  if (sigma <= 0.0)
  {
    sigma = window / 6.0;
  }
  std::vector<double> weights(window);
  double sum = 0.0;
  for (int t = 0; t < window; ++t)
  {
    const double u = t - window / 2;
    weights[t] = std::exp(-0.5 * u * u / (sigma * sigma));
    sum += weights[t];
  }
  for (double& w : weights)
  {
    w /= sum;
  }
  for (int axis = 0; axis < 3; ++axis)
  {
    SmoothAxis(n, g, axis, weights);
  }
}

//------------------------------------------------------------------------------
void IndexGradient(const float* n, float* grad, const Grid& g, const std::uint8_t* cut)
{
  const vtkIdType numVoxels = static_cast<vtkIdType>(g.N[0]) * g.N[1] * g.N[2];
  const vtkIdType stride[3] = { 1, g.N[0], static_cast<vtkIdType>(g.N[0]) * g.N[1] };
  vtkSMPTools::For(0, numVoxels,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType v = begin; v < end; ++v)
      {
        const int idx[3] = { static_cast<int>(v % g.N[0]), static_cast<int>((v / g.N[0]) % g.N[1]),
          static_cast<int>(v / stride[2]) };
        for (int a = 0; a < 3; ++a)
        {
          double d = 0.0;
          if (g.N[a] > 1)
          {
            const int lo = std::max(0, idx[a] - 1), hi = std::min(g.N[a] - 1, idx[a] + 1);
            if (cut &&
              (cut[v] || cut[v + (hi - idx[a]) * stride[a]] || cut[v + (lo - idx[a]) * stride[a]]))
            {
              grad[3 * v + a] = 0.0f;
              continue;
            }
            d = (static_cast<double>(n[v + (hi - idx[a]) * stride[a]]) -
                  n[v + (lo - idx[a]) * stride[a]]) /
              ((hi - lo) * g.S[a]);
          }
          grad[3 * v + a] = static_cast<float>(d);
        }
      }
    });
}
}
