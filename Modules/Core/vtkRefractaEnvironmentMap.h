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
 *
 * **Procedural checkerboard.** MakeChecker(nu, nv, color1, color2) describes a checkerboard of
 * nu x nv squares over (u, v): square (floor(u nu), floor(v nv)) takes color1 when the sum of its
 * indices is odd, else color2 (EvaluateChecker). The image it returns carries the description in
 * its field data (CheckerSquaresName(), CheckerColorsName(); read back by GetChecker) so that the
 * view pass and the reference renderer evaluate the pattern exactly per ray (sharp square edges
 * at any resolution), and its texels (at most 4096 x 2048) are the exact area means of the
 * pattern over each texel, for whatever samples the image itself (the photon pass's emission from
 * the background, the mapper).
 */
#ifndef vtkRefractaEnvironmentMap_h
#define vtkRefractaEnvironmentMap_h

#include "RefractaCoreModule.h" // for export macro
#include "vtkObject.h"
#include "vtkSmartPointer.h" // for MakeChecker

#include <string> // for ReadRadiance
#include <vector> // for ReadRadiance

class vtkDataArray;
class vtkImageData;

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

  /**
   * An environment image describing the procedural checkerboard of `squaresU` x `squaresV`
   * squares (each clamped to [1, 4096]) of linear RGB colours `color1` and `color2` (see the class
   * description): RGB float texels, the exact area means of the pattern, and the description in
   * the field data.
   */
  static vtkSmartPointer<vtkImageData> MakeChecker(
    int squaresU, int squaresV, const double color1[3], const double color2[3]);

  /**
   * The radiance of an environment image, the one conversion every pass uses: a W x H x 1
   * vtkImageData with point scalars of 1 (grey), 2 (grey, alpha), 3 (RGB) or 4 (RGBA)
   * components; unsigned char and unsigned short scalars are normalised to [0, 1] (divided by
   * 255 and 65535, as VTK's textures read them: an 8- or 16-bit PNG), other types are radiance
   * as stored. Fills `rgb` with W H x 3 values (texel i + W j) and `size` with W and H. False,
   * with `error` saying why, for another shape or a texel that is not finite and >= 0.
   */
  static bool ReadRadiance(
    vtkImageData* image, std::vector<double>& rgb, int size[2], std::string& error);

  /**
   * What ReadRadiance multiplies stored values by: 1 / 255 for unsigned char, 1 / 65535 for
   * unsigned short scalars, else 1.
   */
  static double NormalizingScale(vtkDataArray* scalars);

  /**
   * Whether `map` describes a procedural checkerboard (made by MakeChecker, with a valid
   * description: squares >= 1, six finite colours); then its squares and colours.
   */
  static bool GetChecker(vtkImageData* map, int squares[2], double color1[3], double color2[3]);

  /**
   * The checkerboard's colour at (u, v) (u in [0, 1), v in [0, 1]; v = 1 is in the last row).
   */
  static void EvaluateChecker(double u, double v, const int squares[2], const double color1[3],
    const double color2[3], double rgb[3]);

  ///@{
  /**
   * Field-data names of the checkerboard's description: squares (2 components) and colours (6:
   * color1 RGB, color2 RGB).
   */
  static const char* CheckerSquaresName() { return "CheckerSquares"; }
  static const char* CheckerColorsName() { return "CheckerColors"; }
  ///@}

protected:
  vtkRefractaEnvironmentMap() = default;
  ~vtkRefractaEnvironmentMap() override = default;

private:
  vtkRefractaEnvironmentMap(const vtkRefractaEnvironmentMap&) = delete;
  void operator=(const vtkRefractaEnvironmentMap&) = delete;
};

#endif
