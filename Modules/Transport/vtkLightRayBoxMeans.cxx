// Box means at sharp voxels for vtkLightRaySingleScattering (both methods): where sigma_t changes
// steeply within a voxel's box, the voxel's S1 is the mean of sigma_s phi over the box
// (light_rays_boxes in light_rays.cl) instead of the value at its centre.
#include "vtkLightRaySingleScatteringInternals.h"
#include "vtkSMPTools.h"

#include <algorithm>

using namespace vtkPhotonTracerDetail;

namespace
{
// Half the range of sigma_t (over a voxel and its neighbours) times the spacing above which a
// voxel gets its box mean: a jump of optical depth per voxel above 0.5. Below it the centre
// values are within 2.5% (a dense slab's face at 0.32 per voxel: 0.975 of the reference), and
// the box means, read by the view pass as point values, overshoot about as much the other way
// (a sharp ball of 0.33 per voxel in Refracta.SingleScatteringAgainstReference: +5.6% bias
// against -7.3% at the centres).
constexpr double SharpVoxelOpticalDepth = 0.25;

float LargestChannel(const std::vector<float>& rgb, size_t v)
{
  return std::max({ rgb[3 * v], rgb[3 * v + 1], rgb[3 * v + 2] });
}

// The voxels whose box holds a steep part of the trilinear sigma_t, where some scattering is:
// over the voxel and its 26 neighbours (the centres whose values reach into its box; 0 outside
// the grid), half the range of sigma_t (largest channel) times the largest spacing exceeds
// `depth`, and one of them scatters. In index order.
std::vector<cl_ulong> FindSharpVoxels(
  const Medium& m, const std::vector<float>& scattering, double depth)
{
  const int* n = m.Dims;
  const double h = std::max({ m.Spacing[0], m.Spacing[1], m.Spacing[2] });
  const float range = static_cast<float>(2.0 * depth / h);
  std::vector<std::vector<cl_ulong>> perSlice(n[2]);
  vtkSMPTools::For(0, n[2],
    [&](int kBegin, int kEnd)
    {
      for (int k = kBegin; k < kEnd; ++k)
      {
        for (int j = 0; j < n[1]; ++j)
        {
          for (int i = 0; i < n[0]; ++i)
          {
            // Past the grid's faces there is no medium: a dense voxel on a face is sharp too (its
            // box reaches the face, where the light is less attenuated than at its centre).
            const bool onFace =
              i == 0 || j == 0 || k == 0 || i == n[0] - 1 || j == n[1] - 1 || k == n[2] - 1;
            float lo = onFace ? 0.0f : 3.4e38f, hi = 0.0f;
            bool scatters = false;
            for (int c = std::max(k - 1, 0); c <= std::min(k + 1, n[2] - 1); ++c)
            {
              for (int b = std::max(j - 1, 0); b <= std::min(j + 1, n[1] - 1); ++b)
              {
                for (int a = std::max(i - 1, 0); a <= std::min(i + 1, n[0] - 1); ++a)
                {
                  const size_t u =
                    a + static_cast<size_t>(n[0]) * (b + static_cast<size_t>(n[1]) * c);
                  const float sigma = LargestChannel(m.Extinction, u);
                  lo = std::min(lo, sigma);
                  hi = std::max(hi, sigma);
                  scatters = scatters || LargestChannel(scattering, u) > 0.0f;
                }
              }
            }
            if (scatters && hi - lo > range)
            {
              perSlice[k].push_back(
                i + static_cast<size_t>(n[0]) * (j + static_cast<size_t>(n[1]) * k));
            }
          }
        }
      }
    });
  std::vector<cl_ulong> voxels;
  for (const auto& slice : perSlice)
  {
    voxels.insert(voxels.end(), slice.begin(), slice.end());
  }
  return voxels;
}
}

//------------------------------------------------------------------------------
bool vtkLightRaySingleScattering::RunBoxMeans(Internals& run)
{
  const auto start = Clock::now();
  const std::vector<cl_ulong> voxels =
    FindSharpVoxels(run.M, run.Scattering, SharpVoxelOpticalDepth);
  this->NumberOfBoxMeanVoxels = static_cast<long long>(voxels.size());
  if (voxels.empty())
  {
    return true;
  }
  vtkOpenCLContext* ctx = run.Context;
  const size_t count = voxels.size();
  const cl_mem_flags in = CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR;
  vtkOpenCLBuffer albedo =
    ctx->CreateBuffer(in, run.M.Albedo.size() * sizeof(float), run.M.Albedo.data(), "albedo", this);
  vtkOpenCLBuffer list =
    ctx->CreateBuffer(in, count * sizeof(cl_ulong), voxels.data(), "sharp voxels", this);
  // Blocks of `count` entries: all lights, then each lobe (light_rays.cl).
  const size_t values = 3 * count * run.Blocks();
  vtkOpenCLBuffer radiance =
    ctx->CreateBuffer(CL_MEM_WRITE_ONLY, values * sizeof(float), nullptr, "box means", this);
  vtkOpenCLBuffer direction = ctx->CreateBuffer(
    CL_MEM_WRITE_ONLY, values * sizeof(float), nullptr, "box mean directions", this);
  vtkOpenCLKernel kernel = ctx->CreateKernel(run.Program, "light_rays_boxes", this);
  const float minDistance = static_cast<float>(run.MinimumDistance);
  const cl_ulong n = count;
  if (!albedo || !list || !radiance || !direction || !kernel ||
    !ctx->Check(run.SetArgs(kernel.Get(), albedo.Get(), run.LightBuffer.Get(), run.LightCount,
                  minDistance, list.Get(), radiance.Get(), direction.Get(), n),
      "clSetKernelArg(light_rays_boxes)", this) ||
    !this->RunChunked(run, kernel.Get(), count, "light_rays_boxes", 0.9, 0.95))
  {
    return false;
  }
  if (run.Aborted)
  {
    return true; // RequestData leaves the output empty
  }
  std::vector<float> means(values), directions(values);
  if (!ctx->ReadBuffer(radiance.Get(), means.size() * sizeof(float), means.data(), this) ||
    !ctx->ReadBuffer(direction.Get(), directions.size() * sizeof(float), directions.data(), this))
  {
    return false;
  }
  for (int b = 0; b < run.Blocks(); ++b)
  {
    float* out = run.BlockValues(b, false);
    float* outDirection = run.BlockValues(b, true);
    for (size_t e = 0; e < count; ++e)
    {
      std::copy_n(&means[3 * (b * count + e)], 3, out + 3 * voxels[e]);
      std::copy_n(&directions[3 * (b * count + e)], 3, outDirection + 3 * voxels[e]);
    }
  }
  this->BoxMeanSeconds = Seconds(start);
  return true;
}
