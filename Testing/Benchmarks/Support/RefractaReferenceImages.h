/**
 * @file    RefractaReferenceImages.h
 * @brief   Images of a procedural scene by vtkReferenceRenderer, with their standard errors, and
 *          the relative error of another image against them with the reference's variance taken
 *          out: the one definition the accuracy benchmark and the consistency test share.
 */
#ifndef RefractaReferenceImages_h
#define RefractaReferenceImages_h

#include "RefractaScenes.h"

#include <vector>

class vtkImageData;

namespace refracta
{
namespace bench
{
/** An image as RGB values per pixel (row 0 at the bottom) with a standard error per value. */
struct Image
{
  std::vector<double> Value;
  std::vector<double> Error; ///< 0 where the image is not a Monte Carlo estimate
  double Seconds = 0.0;
};

/** `HDR` (and `StandardError`, `RenderSeconds` when present) of a renderer's output. */
Image ReadImage(vtkImageData* output);

/**
 * Render `scene` (its lights with their extents, camera, background) with vtkReferenceRenderer,
 * size x size pixels, `spp` samples per pixel; `output`, when given, receives its whole output.
 */
Image RenderReference(
  const scenes::Scene& scene, int size, int spp, unsigned int seed, vtkImageData* output = nullptr);

/**
 * Render `scene` like RenderReference, with the consistent estimator vtkReferencePhotonMapper
 * (stochastic progressive photon mapping; for scenes where light is refracted before it scatters,
 * which the unbiased renderer does not converge on): `passes` passes of `photons` photons and
 * `viewSamples` view rays per pixel, radius and alpha at their defaults, its view rays gathering
 * every `gatherSpacing` radii (vtkReferencePhotonMapper::GatherSpacing; < 0: the class default).
 * Its `Error` is the stream estimate of the noise (not the kernel's bias, which falls with the
 * passes).
 */
Image RenderPhotonReference(const scenes::Scene& scene, int size, int passes, int photons,
  int viewSamples, unsigned int seed, vtkImageData* output = nullptr, double gatherSpacing = -1);

/**
 * Relative RMSE of `image` against `reference` over the masked pixels with the reference's
 * variance taken out: E[(a - r)^2] = (a - truth)^2 + var(r) for an unbiased r independent of a,
 * so sqrt(max(0, sum (a - r)^2 - sum SE^2) / sum r^2).
 */
double RelativeError(const Image& image, const Image& reference, const std::vector<bool>& mask);

/** sqrt(sum SE^2 / sum value^2) over the masked pixels: the relative RMSE of the noise alone. */
double NoiseLevel(const Image& image, const std::vector<bool>& mask);
}
}

#endif
