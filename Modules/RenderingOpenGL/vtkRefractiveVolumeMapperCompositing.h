// Private to vtkRefractiveVolumeMapper (not installed): which pixels the mapper replaces, which it
// blends over, and the two images it draws for that.
//
// Every pixel is one of three kinds:
// - FOREIGN: the depth buffer holds geometry that is not one of the pipeline's surfaces (a prop
//   the mapper does not take). The view ray stops at that depth and the pixel is blended as
//   before surfaces existed: pixel = E (L - B) + B + T pixel_before (T the path's RGB
//   transmittance, B the background seen through the path, which is not exposed).
// - COVERED: the pixel's straight camera ray crosses the medium's active box (the bounding box
//   of the voxels where n != 1 or extinction or emission is non-zero, grown by two voxels), or
//   its depth is one of the pipeline's surfaces (with the mapper's ShadeActorsEverywhere): the
//   view pass's result, which already holds the surfaces and the background seen along the bent
//   ray, replaces the pixel: pixel = E (L - B) + B.
// - CLEAR: neither: VTK's own drawing of the pixel stays.
#ifndef vtkRefractiveVolumeMapperCompositing_h
#define vtkRefractiveVolumeMapperCompositing_h

#include "vtkNew.h"
#include "vtkRefractaViewPass.h" // for RayFrame

#include "vtkMatrix4x4.h"

#include <cstdint>
#include <vector>

class vtkCamera;
class vtkImageData;
class vtkRefractaBVH;
class vtkRenderer;

namespace vtkRefractiveVolumeMapperDetail
{
enum PixelKind : std::uint8_t
{
  CLEAR = 0,
  COVERED = 1,
  FOREIGN = 2
};

/// A box in the medium's grid-local frame (world units; see vtkRefractaGridFrame); empty when
/// Lo > Hi.
struct LocalBox
{
  double Lo[3] = { 0, 0, 0 };
  double Hi[3] = { -1, -1, -1 };
  bool IsEmpty() const { return this->Lo[0] > this->Hi[0]; }
};

/// The active box of a Refracta medium: voxels with |n - 1| > 1e-6, extinction > 0 or emission
/// > 0, grown by `margin` voxels; the whole grid when the medium has none of those arrays.
LocalBox ActiveBox(vtkImageData* medium, double margin);

/// Whether the straight camera ray of pixel (i, j) crosses `box` (frame from
/// vtkRefractaViewPass::ComputeRayFrame), before `limit` (path length) where one is given.
bool RayCrossesBox(const vtkRefractaViewPass::RayFrame& frame, int i, int j, int width, int height,
  const LocalBox& box, double limit);

/// The straight camera rays of the depth buffer's pixels, in world coordinates: from the near
/// plane to the depth drawn there.
class DepthRays
{
public:
  DepthRays(vtkRenderer* renderer, vtkCamera* camera);

  /// Whether the depth drawn at pixel (i, j) (`depth` in [0, 1)) is a triangle of `bvh`: the
  /// closest hit along the pixel's ray lies at or before the drawn point (1% of the ray's
  /// length as slack for the depth buffer's precision).
  bool HitsSurface(vtkRefractaBVH* bvh, int i, int j, int width, int height, float depth) const;

private:
  vtkNew<vtkMatrix4x4> Inverse; // normalized device -> world
};

/// The exposure that puts the 99th percentile of the luminance of the scene's light (the image
/// less its `backgroundPart`, the background seen through the medium, over pixels that are not
/// CLEAR with mean transmittance below 0.98) at 0.8; 1 where there is none, or where it stays
/// below a thousandth of the brightest background part's luminance (a clear medium shows only
/// the background: nothing to meter).
double MeterExposure(const std::vector<float>& image, const std::vector<float>& transmittance,
  const std::vector<float>& backgroundPart, const std::vector<std::uint8_t>& kinds);

/// The RGBA images the mapper draws for the kinds above: `multiply` (blended with ZERO,
/// SRC_COLOR: 0 where COVERED, T where FOREIGN, 1 where CLEAR) and `add` (ONE, ONE:
/// E (L - B) + B where COVERED or FOREIGN, 0 where CLEAR); RGB clamped to [0, 1]. B, the
/// background part of L (`backgroundPart`, RGBA per pixel; vtkRefractaViewPass::Render), is not
/// exposed: whatever the renderer's background (colour, gradient, texture) and the exposure E,
/// the background seen through a clear part of the medium equals what VTK draws around it.
/// With `unbentBackgroundDepth` (the depth buffer VTK drew), a COVERED pixel whose depth is 1
/// (VTK drew the background there) takes that background from the frame, unbent and dimmed by
/// T, instead of B: multiply T, add E (L - B). For a transparent renderer (a layer above 0,
/// over what the layers below drew) and for a screen-space background (gradient, texture) seen
/// through a parallel camera, whose rays share one direction and so would all see the viewport
/// centre's colour in B.
void CompositingImages(const std::vector<float>& image, const std::vector<float>& transmittance,
  const std::vector<float>& backgroundPart, const std::vector<std::uint8_t>& kinds, float exposure,
  const std::vector<float>* unbentBackgroundDepth, std::vector<float>& multiply,
  std::vector<float>& add);
}

#endif
