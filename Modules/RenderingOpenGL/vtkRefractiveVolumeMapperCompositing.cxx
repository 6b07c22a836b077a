#include "vtkRefractiveVolumeMapperCompositing.h"

#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkPointData.h"
#include "vtkRefractaBVH.h"
#include "vtkRefractaMedium.h"
#include "vtkRenderer.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vtkRefractiveVolumeMapperDetail
{
namespace
{
// Whether point `id` of the medium can change a view ray: |n - 1| > 1e-6, or any channel of the
// extinction or the emission above 0.
bool Active(vtkDataArray* index, vtkDataArray* extinction, vtkDataArray* emission, vtkIdType id)
{
  if (index && std::abs(index->GetComponent(id, 0) - 1.0) > 1e-6)
  {
    return true;
  }
  for (vtkDataArray* a : { extinction, emission })
  {
    for (int c = 0; a && c < a->GetNumberOfComponents(); ++c)
    {
      if (a->GetComponent(id, c) > 0.0)
      {
        return true;
      }
    }
  }
  return false;
}
}

LocalBox ActiveBox(vtkImageData* medium, double margin)
{
  LocalBox box;
  int dims[3];
  double spacing[3];
  medium->GetDimensions(dims);
  medium->GetSpacing(spacing);
  vtkPointData* pd = medium->GetPointData();
  vtkDataArray* index =
    pd->GetArray(vtkRefractaMedium::GetArrayName(vtkRefractaMedium::REFRACTIVE_INDEX));
  vtkDataArray* extinction =
    pd->GetArray(vtkRefractaMedium::GetArrayName(vtkRefractaMedium::EXTINCTION));
  vtkDataArray* emission =
    pd->GetArray(vtkRefractaMedium::GetArrayName(vtkRefractaMedium::EMISSION));
  int lo[3] = { dims[0], dims[1], dims[2] }, hi[3] = { -1, -1, -1 };
  if (!index && !extinction && !emission)
  {
    std::fill(lo, lo + 3, 0);
    for (int a = 0; a < 3; ++a)
    {
      hi[a] = dims[a] - 1;
    }
  }
  vtkIdType id = 0;
  for (int k = 0; k < dims[2] && (index || extinction || emission); ++k)
  {
    for (int j = 0; j < dims[1]; ++j)
    {
      for (int i = 0; i < dims[0]; ++i, ++id)
      {
        if (Active(index, extinction, emission, id))
        {
          const int ijk[3] = { i, j, k };
          for (int a = 0; a < 3; ++a)
          {
            lo[a] = std::min(lo[a], ijk[a]);
            hi[a] = std::max(hi[a], ijk[a]);
          }
        }
      }
    }
  }
  if (hi[0] < 0)
  {
    return box; // nothing in the medium changes a ray
  }
  for (int a = 0; a < 3; ++a)
  {
    box.Lo[a] = spacing[a] * (lo[a] - margin);
    box.Hi[a] = spacing[a] * (hi[a] + margin);
  }
  return box;
}

bool RayCrossesBox(const vtkRefractaViewPass::RayFrame& frame, int i, int j, int width, int height,
  const LocalBox& box, double limit)
{
  if (box.IsEmpty())
  {
    return false;
  }
  const double sx = 2.0 * (i + 0.5) / width - 1.0, sy = 2.0 * (j + 0.5) / height - 1.0;
  double origin[3], d[3];
  for (int a = 0; a < 3; ++a)
  {
    origin[a] = frame.Eye[a] + (frame.Parallel ? sx * frame.U[a] + sy * frame.V[a] : 0.0);
    d[a] = frame.W[a] + (frame.Parallel ? 0.0 : sx * frame.U[a] + sy * frame.V[a]);
  }
  const double length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  double t0 = 0.0, t1 = std::isfinite(limit) ? limit : std::numeric_limits<double>::max();
  for (int a = 0; a < 3; ++a)
  {
    const double da = d[a] / length;
    if (std::abs(da) < 1e-300)
    {
      if (origin[a] < box.Lo[a] || origin[a] > box.Hi[a])
      {
        return false;
      }
      continue;
    }
    double ta = (box.Lo[a] - origin[a]) / da, tb = (box.Hi[a] - origin[a]) / da;
    if (ta > tb)
    {
      std::swap(ta, tb);
    }
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  return t0 <= t1;
}

DepthRays::DepthRays(vtkRenderer* renderer, vtkCamera* camera)
{
  vtkMatrix4x4* projection =
    camera->GetCompositeProjectionTransformMatrix(renderer->GetTiledAspectRatio(), -1, 1);
  vtkMatrix4x4::Invert(projection, this->Inverse);
}

bool DepthRays::HitsSurface(
  vtkRefractaBVH* bvh, int i, int j, int width, int height, float depth) const
{
  const double sx = 2.0 * (i + 0.5) / width - 1.0, sy = 2.0 * (j + 0.5) / height - 1.0;
  double nearNdc[4] = { sx, sy, -1.0, 1.0 }, farNdc[4] = { sx, sy, 2.0 * depth - 1.0, 1.0 };
  double nearWorld[4], farWorld[4];
  this->Inverse->MultiplyPoint(nearNdc, nearWorld);
  this->Inverse->MultiplyPoint(farNdc, farWorld);
  double origin[3], direction[3], hit[3];
  for (int a = 0; a < 3; ++a)
  {
    origin[a] = nearWorld[a] / nearWorld[3];
    direction[a] = farWorld[a] / farWorld[3] - origin[a];
  }
  return bvh->IntersectRay(origin, direction, 1.01, hit) >= 0;
}

double MeterExposure(const std::vector<float>& image, const std::vector<float>& transmittance,
  const std::vector<float>& backgroundPart, const std::vector<std::uint8_t>& kinds)
{
  std::vector<double> luminance;
  double background = 0.0; // the brightest background seen through the medium
  const bool hasBackground = backgroundPart.size() >= image.size();
  for (size_t p = 0; 4 * p + 3 < image.size() && 4 * p + 3 < transmittance.size(); ++p)
  {
    if (p < kinds.size() && kinds[p] == CLEAR)
    {
      continue;
    }
    const float* b = hasBackground ? backgroundPart.data() + 4 * p : nullptr;
    const double t =
      (transmittance[4 * p] + transmittance[4 * p + 1] + transmittance[4 * p + 2]) / 3.0;
    const double weight[3] = { 0.2126, 0.7152, 0.0722 }; // luminance of linear RGB
    double y = 0.0, yb = 0.0;
    for (int c = 0; c < 3; ++c)
    {
      y += weight[c] * (image[4 * p + c] - (b ? b[c] : 0.0f));
      yb += weight[c] * (b ? b[c] : 0.0f);
    }
    background = std::max(background, yb);
    if (t < 0.98 && std::isfinite(y))
    {
      luminance.push_back(y);
    }
  }
  if (luminance.empty())
  {
    return 1.0;
  }
  auto at = luminance.begin() + static_cast<std::ptrdiff_t>(0.99 * (luminance.size() - 1));
  std::nth_element(luminance.begin(), at, luminance.end());
  // Where the medium shows only the background (a clear glass ball: L - B is float round-off)
  // there is no light of the scene's to meter: metering it would amplify the round-off (an
  // outside review measured an exposure of 6e7). The scene's light must reach a thousandth of
  // the background's luminance to be metered.
  return *at > 1e-3 * background && *at > 0.0 ? 0.8 / *at : 1.0;
}

void CompositingImages(const std::vector<float>& image, const std::vector<float>& transmittance,
  const std::vector<float>& backgroundPart, const std::vector<std::uint8_t>& kinds, float exposure,
  const std::vector<float>* unbentBackgroundDepth, std::vector<float>& multiply,
  std::vector<float>& add)
{
  const size_t pixels = kinds.size();
  multiply.assign(4 * pixels, 1.0f);
  add.assign(4 * pixels, 0.0f);
  auto clamp01 = [](float v) { return std::min(std::max(v, 0.0f), 1.0f); };
  const bool hasBackground = backgroundPart.size() >= 4 * pixels;
  for (size_t p = 0; p < pixels; ++p)
  {
    if (kinds[p] == CLEAR)
    {
      continue;
    }
    // VTK's background drawn at this very pixel, seen unbent through T, instead of the view
    // pass's part (a screen-space background through a parallel camera).
    const bool fromFrame = kinds[p] == COVERED && unbentBackgroundDepth &&
      p < unbentBackgroundDepth->size() && (*unbentBackgroundDepth)[p] >= 1.0f;
    for (int c = 0; c < 3; ++c)
    {
      const float b = hasBackground ? backgroundPart[4 * p + c] : 0.0f;
      const float scene = exposure * std::max(image[4 * p + c] - b, 0.0f);
      add[4 * p + c] = clamp01(fromFrame ? scene : scene + b);
      multiply[4 * p + c] =
        kinds[p] == COVERED && !fromFrame ? 0.0f : clamp01(transmittance[4 * p + c]);
    }
  }
}
}
