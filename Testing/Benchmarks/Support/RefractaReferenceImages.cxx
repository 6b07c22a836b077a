#include "RefractaReferenceImages.h"

#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkReferencePhotonMapper.h"
#include "vtkReferenceRenderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace refracta
{
namespace bench
{
Image ReadImage(vtkImageData* output)
{
  Image image;
  vtkDataArray* hdr = output->GetPointData()->GetArray("HDR");
  vtkDataArray* se = output->GetPointData()->GetArray("StandardError");
  for (vtkIdType p = 0; hdr && p < hdr->GetNumberOfTuples(); ++p)
  {
    for (int c = 0; c < 3; ++c)
    {
      image.Value.push_back(hdr->GetComponent(p, c));
      image.Error.push_back(se ? std::max(0.0, se->GetComponent(p, c)) : 0.0);
    }
  }
  if (vtkDataArray* seconds = output->GetFieldData()->GetArray("RenderSeconds"))
  {
    image.Seconds = seconds->GetComponent(0, 0);
  }
  return image;
}

// Render `scene` with the reference renderer; `output`, when given, receives its whole output.
Image RenderReference(
  const scenes::Scene& scene, int size, int spp, unsigned int seed, vtkImageData* output)
{
  vtkNew<vtkReferenceRenderer> reference;
  reference->SetInputData(scene.Medium);
  reference->SetCamera(scene.Camera);
  for (const auto& light : scene.Lights)
  {
    reference->AddLight(light);
  }
  reference->SetImageSize(size, size);
  reference->SetBackgroundColor(scene.Background[0], scene.Background[1], scene.Background[2]);
  reference->SetLightRadius(scene.LightRadius);
  reference->SetDirectionalLightAngularRadius(scene.LightAngularRadius);
  reference->SetSamplesPerPixel(spp);
  reference->SetSeed(seed);
  const auto start = std::chrono::steady_clock::now();
  reference->Update();
  Image image = ReadImage(reference->GetOutput());
  image.Seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (output)
  {
    output->ShallowCopy(reference->GetOutput());
  }
  return image;
}

Image RenderPhotonReference(const scenes::Scene& scene, int size, int passes, int photons,
  int viewSamples, unsigned int seed, vtkImageData* output, double gatherSpacing)
{
  vtkNew<vtkReferencePhotonMapper> reference;
  if (gatherSpacing >= 0)
  {
    reference->SetGatherSpacing(gatherSpacing);
  }
  reference->SetInputData(scene.Medium);
  reference->SetCamera(scene.Camera);
  for (const auto& light : scene.Lights)
  {
    reference->AddLight(light);
  }
  reference->SetImageSize(size, size);
  reference->SetBackgroundColor(scene.Background[0], scene.Background[1], scene.Background[2]);
  reference->SetLightRadius(scene.LightRadius);
  reference->SetDirectionalLightAngularRadius(scene.LightAngularRadius);
  reference->SetPasses(passes);
  reference->SetPhotonsPerPass(photons);
  reference->SetSamplesPerPixel(viewSamples);
  reference->SetSeed(seed);
  const auto start = std::chrono::steady_clock::now();
  reference->Update();
  Image image = ReadImage(reference->GetOutput());
  image.Seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (output)
  {
    output->ShallowCopy(reference->GetOutput());
  }
  return image;
}

// Relative RMSE of `image` against `reference` over the masked pixels, with the reference's
// variance taken out: E[(a - r)^2] = (a - truth)^2 + var(r) for an unbiased r independent of a.
double RelativeError(const Image& image, const Image& reference, const std::vector<bool>& mask)
{
  double squared = 0.0, variance = 0.0, norm = 0.0;
  for (size_t p = 0; p < mask.size(); ++p)
  {
    if (!mask[p])
    {
      continue;
    }
    for (int c = 0; c < 3; ++c)
    {
      const size_t v = 3 * p + c;
      const double d = image.Value[v] - reference.Value[v];
      squared += d * d;
      variance += reference.Error[v] * reference.Error[v];
      norm += reference.Value[v] * reference.Value[v];
    }
  }
  return norm > 0 ? std::sqrt(std::max(0.0, squared - variance) / norm) : 0.0;
}

// sqrt(sum SE^2 / sum value^2): the relative RMSE the reference's own noise amounts to.
double NoiseLevel(const Image& image, const std::vector<bool>& mask)
{
  double variance = 0.0, norm = 0.0;
  for (size_t v = 0; v < image.Value.size(); ++v)
  {
    if (mask[v / 3])
    {
      variance += image.Error[v] * image.Error[v];
      norm += image.Value[v] * image.Value[v];
    }
  }
  return norm > 0 ? std::sqrt(variance / norm) : 0.0;
}
}
}
