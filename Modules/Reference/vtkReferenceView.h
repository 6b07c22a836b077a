/**
 * Internal to RefractaReference (a private header: not wrapped, not installed). The camera of the
 * reference estimators in the grid-local frame: view rays through a pixel (perspective with the
 * vertical full view angle and aspect W / H, or parallel with ParallelScale = half the viewport
 * height), shared by the path tracer and the photon mapper so that both see the same rays.
 */
#ifndef vtkReferenceView_h
#define vtkReferenceView_h

#include "vtkReferenceMath.h"

namespace refracta
{
namespace reference
{
struct View
{
  Vec3 Eye = Vec3(0.0);
  Vec3 Forward = Vec3(0.0);
  Vec3 Right = Vec3(0.0);
  Vec3 Up = Vec3(0.0);
  int Width = 1;
  int Height = 1;
  double Aspect = 1;
  double HalfHeight = 1;
  bool Parallel = false;

  // The ray through the point (i + jx, j + jy) of the image (pixel (i, j), jx and jy in [0, 1):
  // 0.5 is the pixel centre).
  void Ray(int i, int j, double jx, double jy, Vec3& origin, Vec3& direction) const
  {
    const double sx = (2 * (i + jx) / Width - 1) * Aspect * HalfHeight;
    const double sy = (2 * (j + jy) / Height - 1) * HalfHeight;
    if (Parallel)
    {
      origin = Eye + sx * Right + sy * Up;
      direction = Forward;
    }
    else
    {
      origin = Eye;
      direction = Normalized(Forward + sx * Right + sy * Up);
    }
  }
};
} // namespace reference
} // namespace refracta

#endif
