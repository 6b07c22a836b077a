// The INTERPOLATED method of vtkLightRaySingleScattering: Ren et al. (2008), sections 4 and 5.
// Dynamic sampling on the host over grids G1, G2, ... (light rays for the samples on the device),
// then eq. 4 at every voxel on the device (light_rays_interpolate).
#include "vtkDoubleArray.h"
#include "vtkIntArray.h"
#include "vtkLightRaySingleScatteringInternals.h"
#include "vtkRefractaGridFrame.h"

#include <algorithm>
#include <array>
#include <cmath>

using namespace vtkPhotonTracerDetail;

namespace
{
// Points per sample: x_j and the six gradient points x_j +- Delta e_a.
constexpr int PointsPerSample = 7;
constexpr double HalfDiagonal = 0.8660254037844386; // sqrt(3) / 2

// One grid G_k: vertex (a, b, c) at Origin + H (a, b, c), valid radius R = H (the paper's choice).
struct Level
{
  int Size[3];
  double Origin[3];
  double H;
  std::vector<int> VertexSample; // final sample index or -1
  size_t Vertices() const { return static_cast<size_t>(Size[0]) * Size[1] * Size[2]; }
  size_t Index(int a, int b, int c) const
  {
    return a + Size[0] * (b + static_cast<size_t>(Size[1]) * c);
  }
  void Position(size_t v, double x[3]) const
  {
    const size_t ijk[3] = { v % Size[0], (v / Size[0]) % Size[1],
      v / (static_cast<size_t>(Size[0]) * Size[1]) };
    for (int a = 0; a < 3; ++a)
    {
      x[a] = Origin[a] + H * static_cast<double>(ijk[a]);
    }
  }
};

// Counts of scattering voxels in boxes of voxels, by a summed-volume table.
class ScatteringCounter
{
public:
  ScatteringCounter(const Medium& m, const std::vector<float>& scattering)
    : Medium_(m)
  {
    for (int a = 0; a < 3; ++a)
    {
      this->Stride[a] = m.Dims[a] + 1;
    }
    this->Table.assign(static_cast<size_t>(this->Stride[0]) * this->Stride[1] * this->Stride[2], 0);
    for (int k = 0; k < m.Dims[2]; ++k)
    {
      for (int j = 0; j < m.Dims[1]; ++j)
      {
        for (int i = 0; i < m.Dims[0]; ++i)
        {
          const size_t v = i + m.Dims[0] * (j + static_cast<size_t>(m.Dims[1]) * k);
          const int here =
            scattering[3 * v] > 0 || scattering[3 * v + 1] > 0 || scattering[3 * v + 2] > 0;
          this->At(i + 1, j + 1, k + 1) = here + this->At(i, j + 1, k + 1) +
            this->At(i + 1, j, k + 1) + this->At(i + 1, j + 1, k) - this->At(i, j, k + 1) -
            this->At(i, j + 1, k) - this->At(i + 1, j, k) + this->At(i, j, k);
        }
      }
    }
  }

  // Whether a scattering voxel meets the box [x - r, x + r] (grid-local).
  bool Touches(const double x[3], double r) const
  {
    int lo[3], hi[3];
    for (int a = 0; a < 3; ++a)
    {
      const double s = this->Medium_.Spacing[a];
      lo[a] = std::max(0, static_cast<int>(std::floor((x[a] - r) / s + 0.5)));
      hi[a] =
        std::min(this->Medium_.Dims[a] - 1, static_cast<int>(std::floor((x[a] + r) / s + 0.5)));
      if (lo[a] > hi[a])
      {
        return false;
      }
      ++hi[a];
    }
    const long long n = static_cast<long long>(this->At(hi[0], hi[1], hi[2])) -
      this->At(lo[0], hi[1], hi[2]) - this->At(hi[0], lo[1], hi[2]) -
      this->At(hi[0], hi[1], lo[2]) + this->At(lo[0], lo[1], hi[2]) +
      this->At(lo[0], hi[1], lo[2]) + this->At(hi[0], lo[1], lo[2]) - this->At(lo[0], lo[1], lo[2]);
    return n > 0;
  }

private:
  int& At(int i, int j, int k)
  {
    return this->Table[i + this->Stride[0] * (j + static_cast<size_t>(this->Stride[1]) * k)];
  }
  int At(int i, int j, int k) const
  {
    return this->Table[i + this->Stride[0] * (j + static_cast<size_t>(this->Stride[1]) * k)];
  }
  const Medium& Medium_;
  int Stride[3];
  std::vector<int> Table;
};

// sigma_s (RGB) of the voxel holding grid-local x, zero outside the grid.
std::array<float, 3> ScatteringAt(
  const Medium& m, const std::vector<float>& scattering, const float x[3])
{
  int ijk[3];
  for (int a = 0; a < 3; ++a)
  {
    ijk[a] = static_cast<int>(std::floor(x[a] / m.Spacing[a] + 0.5));
    if (ijk[a] < 0 || ijk[a] >= m.Dims[a])
    {
      return { 0.0f, 0.0f, 0.0f };
    }
  }
  const size_t v = ijk[0] + m.Dims[0] * (ijk[1] + static_cast<size_t>(m.Dims[1]) * ijk[2]);
  return { scattering[3 * v], scattering[3 * v + 1], scattering[3 * v + 2] };
}

// Clamps grid-local x into the box of voxel centres, where the output is evaluated. The voxel
// model's light field is discontinuous at the medium's faces (a ray beside the medium never
// crosses it), so a sample's light rays start inside and its gradient stays one-sided there:
// central differences across a face, or a grid vertex half a voxel outside it, would carry the
// unattenuated light outside into the voxels next to the faces.
void ClampToVoxelCentres(const Medium& m, double x[3])
{
  for (int a = 0; a < 3; ++a)
  {
    x[a] = std::min(std::max(x[a], 0.0), (m.Dims[a] - 1) * m.Spacing[a]);
  }
}

// One sample's record for light_rays_interpolate (phi, flux, their gradients) from the light rays
// at its 7 points (the clamped centre, then +- each axis, clamped; a difference over the distance
// between them, zero on an axis one voxel thick), moved to the grid vertex by the first-order
// expansion so that eq. 4's L_j + (x - x_j).grad L_j uses the vertex as x_j.
void MakeSampleRecord(
  const float* points, const float* L, const float* F, const double vertex[3], cl_float4 record[8])
{
  double gradL[3][3] = {}, gradF[3][3] = {};
  for (int a = 0; a < 3; ++a)
  {
    const int plus = 1 + 2 * a, minus = 2 + 2 * a;
    const double span = static_cast<double>(points[4 * plus + a]) - points[4 * minus + a];
    if (span <= 0)
    {
      continue;
    }
    for (int c = 0; c < 3; ++c)
    {
      gradL[a][c] = (L[4 * plus + c] - L[4 * minus + c]) / span;
      gradF[a][c] = (F[4 * plus + c] - F[4 * minus + c]) / span;
    }
  }
  double atVertexL[3], atVertexF[3];
  for (int c = 0; c < 3; ++c)
  {
    atVertexL[c] = L[c];
    atVertexF[c] = F[c];
    for (int a = 0; a < 3; ++a)
    {
      const double d = vertex[a] - points[a];
      atVertexL[c] += d * gradL[a][c];
      atVertexF[c] += d * gradF[a][c];
    }
  }
  record[0] = Float4(atVertexL[0], atVertexL[1], atVertexL[2]);
  record[1] = Float4(atVertexF[0], atVertexF[1], atVertexF[2]);
  for (int a = 0; a < 3; ++a)
  {
    record[2 + a] = Float4(gradL[a][0], gradL[a][1], gradL[a][2]);
    record[5 + a] = Float4(gradF[a][0], gradF[a][1], gradF[a][2]);
  }
}

// The grids G1, G2, ...: CoarsestGridResolution cells along the longest axis, doubling up to the
// finest of MaximumGridResolution and half the medium's resolution, which is always the last.
std::vector<Level> MakeLevels(const Medium& m, int coarsest, int finest)
{
  double longest = 0;
  int maxDim = 1;
  for (int a = 0; a < 3; ++a)
  {
    longest = std::max(longest, m.Hi[a] - m.Lo[a]);
    maxDim = std::max(maxDim, m.Dims[a]);
  }
  const int limit = std::min(finest, std::max(2, maxDim / 2));
  std::vector<int> resolutions;
  for (int r = coarsest; r <= limit; r *= 2)
  {
    resolutions.push_back(r);
  }
  if (resolutions.empty() || resolutions.back() < limit)
  {
    resolutions.push_back(limit); // the finest grid is half the medium's resolution (paper, 5)
  }
  std::vector<Level> levels;
  for (int r : resolutions)
  {
    Level level;
    level.H = longest / r;
    for (int a = 0; a < 3; ++a)
    {
      level.Origin[a] = m.Lo[a];
      level.Size[a] = static_cast<int>(std::ceil((m.Hi[a] - m.Lo[a]) / level.H - 1e-9)) + 1;
    }
    level.VertexSample.assign(level.Vertices(), -1);
    levels.push_back(std::move(level));
  }
  return levels;
}

// One sample being refined: its vertex, eq. 6's transmittance to the viewer (inherited).
struct Candidate
{
  size_t Vertex;
  float Tau;
};
}

//------------------------------------------------------------------------------
bool vtkLightRaySingleScattering::RunInterpolation(Internals& run)
{
  const auto start = Clock::now();
  const Medium& m = run.M;
  std::vector<Level> levels =
    MakeLevels(m, this->CoarsestGridResolution, this->MaximumGridResolution);
  const ScatteringCounter counter(m, run.Scattering);
  const int blocks = run.Blocks();
  const size_t record = 8 * static_cast<size_t>(blocks); // float4 per sample and its lobes
  std::vector<cl_float4> samples; // `record` float4 per final sample (light_rays_interpolate)
  std::vector<Candidate> current;
  {
    const Level& g1 = levels[0];
    for (size_t v = 0; v < g1.Vertices(); ++v)
    {
      double x[3];
      g1.Position(v, x);
      if (counter.Touches(x, g1.H))
      {
        current.push_back({ v, 1.0f });
      }
    }
  }
  double epsilon = 0;
  this->SamplesPerLevel.assign(levels.size(), 0);
  for (size_t k = 0; k < levels.size() && !current.empty(); ++k)
  {
    // Dynamic sampling takes the first half of the progress, a share per grid level.
    this->UpdateProgress(0.5 * static_cast<double>(k) / levels.size());
    if (this->GetAbortExecute())
    {
      run.Aborted = true;
      return true;
    }
    Level& level = levels[k];
    const double radius = level.H;
    // Every candidate's 7 points (x_j and x_j +- Delta e_a), then the error points x_j +- R e_a
    // (eq. 6) that are not already a candidate: with R = h they are the grid's neighbouring
    // vertices, so a candidate's centre value serves its neighbours' error metric. The finest
    // grid splits nothing and needs no error points.
    const bool finest = k + 1 == levels.size();
    std::vector<float> points(4 * PointsPerSample * current.size(), 0.0f);
    std::vector<int> pointOf(level.Vertices(), -1);
    for (size_t j = 0; j < current.size(); ++j)
    {
      double x[3];
      level.Position(current[j].Vertex, x);
      ClampToVoxelCentres(m, x);
      pointOf[current[j].Vertex] = static_cast<int>(PointsPerSample * j);
      float* p = &points[4 * PointsPerSample * j];
      for (int q = 0; q < PointsPerSample; ++q)
      {
        double y[3] = { x[0], x[1], x[2] };
        if (q > 0)
        {
          const int a = (q - 1) / 2;
          y[a] += q % 2 == 1 ? m.Spacing[a] : -m.Spacing[a];
          ClampToVoxelCentres(m, y);
        }
        for (int a = 0; a < 3; ++a)
        {
          p[4 * q + a] = static_cast<float>(y[a]);
        }
      }
    }
    std::vector<int> errorPoint(finest ? 0 : 6 * current.size(), -1);
    for (size_t j = 0; j < errorPoint.size() / 6; ++j)
    {
      const size_t v = current[j].Vertex;
      const int ijk[3] = { static_cast<int>(v % level.Size[0]),
        static_cast<int>((v / level.Size[0]) % level.Size[1]),
        static_cast<int>(v / (static_cast<size_t>(level.Size[0]) * level.Size[1])) };
      for (int q = 0; q < 6; ++q)
      {
        int n[3] = { ijk[0], ijk[1], ijk[2] };
        n[q / 2] += q % 2 == 0 ? 1 : -1;
        if (n[q / 2] < 0 || n[q / 2] >= level.Size[q / 2])
        {
          continue; // outside the box: nothing scatters there, no error
        }
        const size_t w = level.Index(n[0], n[1], n[2]);
        if (pointOf[w] < 0)
        {
          double y[3];
          level.Position(w, y);
          ClampToVoxelCentres(m, y);
          pointOf[w] = static_cast<int>(points.size() / 4);
          points.insert(points.end(),
            { static_cast<float>(y[0]), static_cast<float>(y[1]), static_cast<float>(y[2]), 0.0f });
        }
        errorPoint[6 * j + q] = pointOf[w];
      }
    }
    std::vector<std::vector<float>> phiBlocks, fluxBlocks;
    if (!this->EvaluatePoints(run, points, nullptr, run.LightCount, phiBlocks, fluxBlocks))
    {
      return false;
    }
    const std::vector<float>& phi = phiBlocks[0]; // all lights
    if (k == 0)
    {
      // epsilon relative to the brightest source sigma_s phi seen at G1, times R_1^3.
      double brightest = 0;
      for (size_t q = 0; q < phi.size() / 4; ++q)
      {
        const auto sc = ScatteringAt(m, run.Scattering, &points[4 * q]);
        for (int c = 0; c < 3; ++c)
        {
          brightest = std::max(brightest, static_cast<double>(sc[c]) * phi[4 * q + c]);
        }
      }
      epsilon = this->ErrorTolerance * brightest * radius * radius * radius;
      if (this->UseViewPoint)
      {
        // tau_{x_j v}: the transmittance to the viewer, as a unit point light's fluence x d^2.
        vtkNew<vtkRefractaGridFrame> grid;
        grid->SetImage(run.Input);
        double viewLocal[3];
        grid->WorldToLocalPoint(this->ViewPoint, viewLocal);
        const cl_float4 viewer[4] = { Float4(viewLocal, 1.0), Float4(0, 0, 1, -2.0),
          Float4(1, 1, 1, 0), Float4(0, 1, 0, 0) };
        std::vector<float> centres(4 * current.size());
        for (size_t j = 0; j < current.size(); ++j)
        {
          std::copy_n(&points[4 * PointsPerSample * j], 4, &centres[4 * j]);
        }
        std::vector<std::vector<float>> tauBlocks, tauFlux;
        if (!this->EvaluatePoints(run, centres, viewer, 1, tauBlocks, tauFlux))
        {
          return false;
        }
        const std::vector<float>& tauPhi = tauBlocks[0];
        for (size_t j = 0; j < current.size(); ++j)
        {
          double d2 = 0;
          for (int a = 0; a < 3; ++a)
          {
            const double d = centres[4 * j + a] - viewLocal[a];
            d2 += d * d;
          }
          d2 = std::max(d2, run.MinimumDistance * run.MinimumDistance);
          current[j].Tau = static_cast<float>(
            std::min(1.0, d2 * (tauPhi[4 * j] + tauPhi[4 * j + 1] + tauPhi[4 * j + 2]) / 3.0));
        }
      }
    }
    Level* next = finest ? nullptr : &levels[k + 1];
    std::vector<char> marked(next ? next->Vertices() : 0, 0);
    std::vector<Candidate> children;
    for (size_t j = 0; j < current.size(); ++j)
    {
      const float* centre = &points[4 * PointsPerSample * j];
      std::vector<cl_float4> records(record); // all lights, then each lobe
      double vertex[3];
      level.Position(current[j].Vertex, vertex);
      for (int b = 0; b < blocks; ++b)
      {
        MakeSampleRecord(centre, &phiBlocks[b][4 * PointsPerSample * j],
          &fluxBlocks[b][4 * PointsPerSample * j], vertex, &records[8 * b]);
      }
      bool split = false;
      if (!finest)
      {
        // Eq. 6 with eq. 7's single-sample estimate at the six points x_j +- R e_a.
        double error = 0;
        for (int q = 0; q < 6; ++q)
        {
          const int at = errorPoint[6 * j + q];
          if (at < 0)
          {
            continue;
          }
          // The estimate of eq. 7 where the neighbour's light rays started (its vertex clamped
          // into the box of voxel centres, like this sample's).
          const float* y = &points[4 * at];
          const auto sc = ScatteringAt(m, run.Scattering, y);
          double worst = 0;
          for (int c = 0; c < 3; ++c)
          {
            double estimate = records[0].s[c];
            for (int a = 0; a < 3; ++a)
            {
              estimate += (y[a] - vertex[a]) * records[2 + a].s[c];
            }
            worst = std::max(worst, std::fabs(estimate - phi[4 * at + c]) * sc[c]);
          }
          error += worst;
        }
        error *= radius * radius * radius * current[j].Tau / 6.0;
        split = error > epsilon;
      }
      if (split)
      {
        // Replace the sample by the next grid's vertices within R_j + (sqrt 3 / 2) h_{k+1}.
        double x[3];
        level.Position(current[j].Vertex, x);
        const double reach = radius + HalfDiagonal * next->H;
        int lo[3], hi[3];
        for (int a = 0; a < 3; ++a)
        {
          lo[a] =
            std::max(0, static_cast<int>(std::ceil((x[a] - reach - next->Origin[a]) / next->H)));
          hi[a] = std::min(next->Size[a] - 1,
            static_cast<int>(std::floor((x[a] + reach - next->Origin[a]) / next->H)));
        }
        for (int c = lo[2]; c <= hi[2]; ++c)
        {
          for (int b = lo[1]; b <= hi[1]; ++b)
          {
            for (int a = lo[0]; a <= hi[0]; ++a)
            {
              const size_t v = next->Index(a, b, c);
              double y[3];
              next->Position(v, y);
              const double d2 = (y[0] - x[0]) * (y[0] - x[0]) + (y[1] - x[1]) * (y[1] - x[1]) +
                (y[2] - x[2]) * (y[2] - x[2]);
              if (!marked[v] && d2 < reach * reach && counter.Touches(y, next->H))
              {
                marked[v] = 1;
                children.push_back({ v, current[j].Tau });
              }
            }
          }
        }
        continue;
      }
      level.VertexSample[current[j].Vertex] = static_cast<int>(samples.size() / record);
      samples.insert(samples.end(), records.begin(), records.end());
      double x[3];
      level.Position(current[j].Vertex, x);
      this->SamplePositions->InsertNextTuple(x);
      this->SampleLevels->InsertNextValue(static_cast<int>(k));
      ++this->SamplesPerLevel[k];
    }
    current = std::move(children);
  }
  this->NumberOfSamples = static_cast<int>(samples.size() / record);
  this->SamplingSeconds = Seconds(start);

  // Eq. 4 at every voxel.
  const auto voxelStart = Clock::now();
  std::vector<int> vertexSample;
  std::vector<cl_int4> levelSize;
  std::vector<int> levelOffset;
  std::vector<cl_float4> levelGrid;
  for (const Level& level : levels)
  {
    levelOffset.push_back(static_cast<int>(vertexSample.size()));
    vertexSample.insert(vertexSample.end(), level.VertexSample.begin(), level.VertexSample.end());
    levelSize.push_back(Int4(level.Size));
    levelGrid.push_back(Float4(level.Origin, level.H));
    levelGrid.push_back(Float4(level.H, level.H, level.H));
  }
  if (samples.empty())
  {
    samples.resize(record, Float4(0, 0, 0));
  }
  vtkOpenCLContext* ctx = run.Context;
  const cl_mem_flags in = CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR;
  const size_t voxels = m.Voxels;
  vtkOpenCLBuffer vertexBuffer = ctx->CreateBuffer(
    in, vertexSample.size() * sizeof(int), vertexSample.data(), "sample vertices", this);
  vtkOpenCLBuffer sizeBuffer = ctx->CreateBuffer(
    in, levelSize.size() * sizeof(cl_int4), levelSize.data(), "sample levels", this);
  vtkOpenCLBuffer offsetBuffer = ctx->CreateBuffer(
    in, levelOffset.size() * sizeof(int), levelOffset.data(), "sample level offsets", this);
  vtkOpenCLBuffer gridBuffer = ctx->CreateBuffer(
    in, levelGrid.size() * sizeof(cl_float4), levelGrid.data(), "sample grids", this);
  vtkOpenCLBuffer sampleBuffer =
    ctx->CreateBuffer(in, samples.size() * sizeof(cl_float4), samples.data(), "samples", this);
  const int zero = 0;
  vtkOpenCLBuffer uncovered = ctx->CreateBuffer(
    CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, sizeof(int), &zero, "uncovered count", this);
  const size_t outputBytes = blocks * 3 * voxels * sizeof(float);
  vtkOpenCLBuffer radiance =
    ctx->CreateBuffer(CL_MEM_WRITE_ONLY, outputBytes, nullptr, "radiance", this);
  vtkOpenCLBuffer direction =
    ctx->CreateBuffer(CL_MEM_WRITE_ONLY, outputBytes, nullptr, "direction", this);
  vtkOpenCLKernel kernel = ctx->CreateKernel(run.Program, "light_rays_interpolate", this);
  const int levelCount = static_cast<int>(levels.size());
  const float minDistance = static_cast<float>(run.MinimumDistance);
  const cl_ulong count = voxels;
  int uncoveredCount = 0;
  if (!vertexBuffer || !sizeBuffer || !offsetBuffer || !gridBuffer || !sampleBuffer || !uncovered ||
    !radiance || !direction || !kernel ||
    !ctx->Check(
      run.SetArgs(kernel.Get(), run.ScatteringBuffer.Get(), run.LightBuffer.Get(), run.LightCount,
        minDistance, vertexBuffer.Get(), sizeBuffer.Get(), offsetBuffer.Get(), gridBuffer.Get(),
        levelCount, sampleBuffer.Get(), radiance.Get(), direction.Get(), uncovered.Get(), count),
      "clSetKernelArg(light_rays_interpolate)", this) ||
    !this->RunChunked(run, kernel.Get(), voxels, "light_rays_interpolate", 0.5, 0.9))
  {
    return false;
  }
  if (run.Aborted)
  {
    return true;
  }
  if (!run.ReadBlocks(radiance.Get(), direction.Get(), this) ||
    !ctx->ReadBuffer(uncovered.Get(), sizeof(int), &uncoveredCount, this))
  {
    return false;
  }
  this->NumberOfUncoveredVoxels = uncoveredCount;
  this->NumberOfEvaluatedPoints += uncoveredCount;
  this->VoxelSeconds = Seconds(voxelStart);
  return true;
}
