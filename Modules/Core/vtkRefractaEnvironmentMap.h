/**
 * @class   vtkRefractaEnvironmentMap
 * @brief   The one equirectangular environment-map convention of Refracta.
 *
 * A WORLD direction d (any length > 0) is looked up in an equirectangular image (W x H texels,
 * row 0 first in memory) through an orthonormal basis built from two world vectors, Up and Right
 * (defaults (0, 1, 0) and (1, 0, 0), the defaults of vtkRenderer::EnvironmentUp/Right):
 *
 *     up = normalize(Up), right = normalize(Right - (Right . up) up), front = up x right
 *     x = d . right, y = d . up, z = d . front
 *     u = atan2(x, z) / (2 pi) + 1/2   (wrapped into [0, 1))
 *     v = atan2(y, sqrt(x^2 + z^2)) / pi + 1/2   (in [0, 1])
 *
 * This is VTK's own convention: vtkOpenGLSkybox's "Sphere" projection (and the equirectangular
 * environment textures of vtkOpenGLRenderer, which use the renderer's EnvironmentUp/Right the same
 * way) computes front = cross(up, right) and u = 0.5 atan(x, z) / pi + 0.5,
 * v = atan(y, |(x, z)|) / pi + 0.5. So an image that looks right as a VTK skybox looks the same
 * behind a Refracta volume.
 *
 * Consequences, with the defaults: u = 0.5 is the direction `front` = up x right = (0, 0, -1),
 * the direction a default vtkCamera looks along; u = 0.75 is +right (+x), u = 0.25 is -x, and
 * u = 0 (= 1) is (0, 0, +1). u grows from front towards right, so seen from inside the sphere the
 * image is not mirrored (left of the image on the viewer's left when up is up). v = 0 is the -up
 * pole (the first row of a vtkImageData, the bottom of the picture), v = 1 the +up pole. For the
 * world direction (1, 1, 0): u = 0.75, v = 0.75.
 *
 * Texel (i, j) has its centre at ((i + 0.5) / W, (j + 0.5) / H); lookups are bilinear, wrapping
 * in u and clamping in v. The OpenCL view pass (Kernels/view_pass.cl, refracta_background)
 * computes the identical mapping from the same basis vectors, passed as kernel arguments.
 */
#ifndef vtkRefractaEnvironmentMap_h
#define vtkRefractaEnvironmentMap_h

#include "RefractaCoreModule.h" // for export macro
#include "vtkObject.h"

class REFRACTACORE_EXPORT vtkRefractaEnvironmentMap : public vtkObject
{
public:
  static vtkRefractaEnvironmentMap* New();
  vtkTypeMacro(vtkRefractaEnvironmentMap, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * The orthonormal basis (right, up, front) from Up and Right as documented above. Returns
   * false (and the default basis) when Up is zero or parallel to Right.
   */
  static bool ComputeBasis(const double up[3], const double rightHint[3], double right[3],
    double upOut[3], double front[3]);

  /**
   * (u, v) of world direction `d` for the basis from `up` and `right`; u in [0, 1), v in [0, 1].
   */
  static void DirectionToTexture(
    const double d[3], const double up[3], const double right[3], double uv[2]);

  /**
   * (u, v) with the default Up (0, 1, 0) and Right (1, 0, 0).
   */
  static void DirectionToTexture(const double d[3], double uv[2]);

  /**
   * The unit world direction of texture coordinate (u, v): the inverse of DirectionToTexture.
   */
  static void TextureToDirection(
    const double uv[2], const double up[3], const double right[3], double d[3]);

  /**
   * Bilinear lookup of interleaved RGB values (`width` x `height`, row 0 first) at (u, v),
   * wrapping in u and clamping in v, texel centres at ((i + 0.5) / W, (j + 0.5) / H).
   */
  static void Sample(const double* rgb, int width, int height, double u, double v, double out[3]);

  /**
   * Index i + W j of the texel whose centre is nearest to (u, v) (wrapping in u, clamping in v).
   */
  static int NearestTexel(int width, int height, double u, double v);

protected:
  vtkRefractaEnvironmentMap() = default;
  ~vtkRefractaEnvironmentMap() override = default;

private:
  vtkRefractaEnvironmentMap(const vtkRefractaEnvironmentMap&) = delete;
  void operator=(const vtkRefractaEnvironmentMap&) = delete;
};

#endif
