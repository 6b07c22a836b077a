// What the consistency tests against the reference renderer share
// (Refracta.SurfacesAgainstReference, Refracta.SingleScatteringAgainstReference): images pooled
// into square regions with the standard error of each region's mean, and the count of region values
// outside
//     |P - R| <= kSigma SE + b max(R, RMS_R),
// R the reference's region mean, SE its standard error, P the tested image's, RMS_R the root mean
// square of the reference's region values (the dim regions are held to the image's scale).
#ifndef RegionComparison_h
#define RegionComparison_h

#include "RefractaReferenceImages.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

namespace refracta_test
{
struct Regions
{
  std::vector<double> Mean, Error; // per region and channel
  double Rms = 0;
};

// Pools a size x size RGB image into regions of block x block pixels: per region and channel the
// mean and its standard error sqrt(sum of the pixels' SE^2) / block^2.
inline Regions Pool(const refracta::bench::Image& image, int size, int block)
{
  const int nb = size / block;
  Regions r;
  r.Mean.assign(3 * nb * nb, 0.0);
  r.Error.assign(3 * nb * nb, 0.0);
  for (int j = 0; j < nb * block; ++j)
  {
    for (int i = 0; i < nb * block; ++i)
    {
      const int region = i / block + nb * (j / block);
      for (int c = 0; c < 3; ++c)
      {
        const size_t v = 3 * (static_cast<size_t>(j) * size + i) + c;
        r.Mean[3 * region + c] += image.Value[v] / (block * block);
        const double se = image.Error.empty() ? 0.0 : std::max(0.0, image.Error[v]);
        r.Error[3 * region + c] += se * se;
      }
    }
  }
  double sum2 = 0;
  for (size_t k = 0; k < r.Mean.size(); ++k)
  {
    r.Error[k] = std::sqrt(r.Error[k]) / (block * block);
    sum2 += r.Mean[k] * r.Mean[k];
  }
  r.Rms = std::sqrt(sum2 / r.Mean.size());
  return r;
}

// Number of region values of `image` (pooled like `ref`) outside the bound; prints the bias, the
// largest region error, the largest |P - R| / SE and the smallest b with none failed.
inline int FailedRegions(
  const Regions& p, const Regions& ref, double kSigma, double b, const std::string& what)
{
  int failed = 0;
  double worst = 0, worstZ = 0, needed = 0, diff = 0, sum = 0;
  for (size_t k = 0; k < ref.Mean.size() && k < p.Mean.size(); ++k)
  {
    const double d = std::abs(p.Mean[k] - ref.Mean[k]);
    const double scale = std::max(ref.Mean[k], ref.Rms);
    worst = std::max(worst, d / scale);
    worstZ = std::max(worstZ, ref.Error[k] > 0 ? d / ref.Error[k] : 0.0);
    needed = std::max(needed, (d - kSigma * ref.Error[k]) / scale);
    failed += d > kSigma * ref.Error[k] + b * scale ? 1 : 0;
    diff += p.Mean[k] - ref.Mean[k];
    sum += ref.Mean[k];
  }
  std::cout << "  " << what << ": bias " << 100 * diff / sum << "%, largest region error "
            << 100 * worst << "% of max(R, RMS_R), largest |P - R| / SE " << worstZ << ", failed "
            << failed << " of " << ref.Mean.size()
            << " region values; the smallest B with none failed is " << 100 * std::max(0.0, needed)
            << "%" << std::endl;
  return failed;
}

inline refracta::bench::Image Scaled(refracta::bench::Image image, double f)
{
  for (double& v : image.Value)
  {
    v *= f;
  }
  return image;
}
}

#endif
