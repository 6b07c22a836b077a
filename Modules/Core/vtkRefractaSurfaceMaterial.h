/**
 * @class   vtkRefractaSurfaceMaterial
 * @brief   The appearance of a Refracta surface: an opaque Lambertian reflector or a dielectric
 *          interface.
 *
 * Surfaces are two-sided Lambertian reflectors: a photon that meets one deposits its flux and is
 * reflected diffusely with probability equal to the albedo (per RGB channel, as a weight), the
 * rest is absorbed. The albedo of a point comes from one of four sources, in this order:
 *
 * 1. UseScalarColors (default off) and the polydata carries colour scalars (point or cell
 *    scalars that are unsigned char 0-255 with 3 or 4 components, or float/double in [0, 1] with
 *    3 or 4 components; alpha is ignored): those colours, as the VTK mapper would map them. A
 *    mesh without such scalars falls back to the next source (vtkRefractaSurfaceSet warns).
 * 2. Texture (default none): an image sampled at the texture coordinates (below), times Albedo,
 *    as VTK modulates an actor's texture by its colour (see SetTexture).
 * 3. UseChecker (default off): a checkerboard of CheckerSquares (default 8 x 8) squares over the
 *    texture coordinates (u, v) in [0, 1]: square (floor(u Su), floor(v Sv)) takes CheckerColor1
 *    (default (0.9, 0.9, 0.9)) when the sum of its indices is even, CheckerColor2 (default
 *    (0.1, 0.1, 0.1)) when odd. Texture coordinates are the polydata's TCoords when present
 *    (first two components), else planar: the mesh's own (untransformed) points projected on the
 *    two axes of its largest bounding-box extents, scaled to [0, 1] over that box.
 * 4. Albedo (default (0.8, 0.8, 0.8)).
 *
 * All colours are linear RGB, clamped to [0, 1] by the setters (an albedo above 1 would create
 * energy). vtkRefractaSurfaceSet bakes the chosen source into one albedo per texel, so every
 * pass sees one colour path.
 *
 * Kind DIELECTRIC (default LAMBERTIAN) makes the surface a transparent interface between two
 * refractive indices instead (Documentation/Physics.md, "Dielectric interfaces"): IndexInside on
 * the side opposite the triangles' winding normal (v1 - v0) x (v2 - v0), IndexOutside on the side
 * it points to. Light meeting it is reflected (Fresnel, unpolarised) or refracted (Snell); the
 * colour settings are then unused. SmoothNormals (default on) interpolates corner normals over
 * each triangle where the mesh is smooth.
 *
 * A DIELECTRIC surface that bounds a homogeneous body (a mesh voxelized with
 * vtkMeshVoxelizer::EXACT_INTERFACES) can carry the medium filling its inside: UseInsideMedium
 * with InsideExtinction, InsideAlbedo, InsideAnisotropy and InsideEmission. The passes then use
 * these values, not the grid, while a path is inside (Documentation/Physics.md "Glass bodies"):
 * the grid mixes the materials of the voxels the surface cuts, which would leak the outer
 * medium's fog about a voxel into the glass.
 */
#ifndef vtkRefractaSurfaceMaterial_h
#define vtkRefractaSurfaceMaterial_h

#include "RefractaCoreModule.h" // for export macro
#include "vtkObject.h"
#include "vtkSmartPointer.h" // for the texture

class vtkImageData;

class REFRACTACORE_EXPORT vtkRefractaSurfaceMaterial : public vtkObject
{
public:
  static vtkRefractaSurfaceMaterial* New();
  vtkTypeMacro(vtkRefractaSurfaceMaterial, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Diffuse albedo (linear RGB, each clamped to [0, 1]). Default (0.8, 0.8, 0.8).
   */
  void SetAlbedo(double r, double g, double b);
  void SetAlbedo(const double rgb[3]) { this->SetAlbedo(rgb[0], rgb[1], rgb[2]); }
  vtkGetVector3Macro(Albedo, double);
  ///@}

  ///@{
  /**
   * Checkerboard over the texture coordinates (see the class description). Default off.
   */
  vtkSetMacro(UseChecker, bool);
  vtkGetMacro(UseChecker, bool);
  vtkBooleanMacro(UseChecker, bool);
  ///@}

  ///@{
  /**
   * Number of checker squares along u and v, each clamped to [1, 4096]. Default 8 x 8.
   */
  void SetCheckerSquares(int u, int v);
  void SetCheckerSquares(const int uv[2]) { this->SetCheckerSquares(uv[0], uv[1]); }
  vtkGetVector2Macro(CheckerSquares, int);
  ///@}

  ///@{
  /**
   * The two checker colours (linear RGB, clamped to [0, 1]). Defaults (0.9, 0.9, 0.9) and
   * (0.1, 0.1, 0.1).
   */
  void SetCheckerColor1(double r, double g, double b);
  void SetCheckerColor1(const double rgb[3]) { this->SetCheckerColor1(rgb[0], rgb[1], rgb[2]); }
  vtkGetVector3Macro(CheckerColor1, double);
  void SetCheckerColor2(double r, double g, double b);
  void SetCheckerColor2(const double rgb[3]) { this->SetCheckerColor2(rgb[0], rgb[1], rgb[2]); }
  vtkGetVector3Macro(CheckerColor2, double);
  ///@}

  ///@{
  /**
   * Take the albedo from the polydata's colour scalars (see the class description). Default off.
   */
  vtkSetMacro(UseScalarColors, bool);
  vtkGetMacro(UseScalarColors, bool);
  vtkBooleanMacro(UseScalarColors, bool);
  ///@}

  enum Kinds
  {
    LAMBERTIAN = 0, ///< opaque, two-sided Lambertian reflector (the colour settings apply)
    DIELECTRIC = 1  ///< transparent interface between IndexInside and IndexOutside
  };

  ///@{
  /**
   * LAMBERTIAN (default) or DIELECTRIC (see the class description).
   */
  vtkSetClampMacro(Kind, int, LAMBERTIAN, DIELECTRIC);
  vtkGetMacro(Kind, int);
  void SetKindToLambertian() { this->SetKind(LAMBERTIAN); }
  void SetKindToDielectric() { this->SetKind(DIELECTRIC); }
  ///@}

  ///@{
  /**
   * Refractive index on the inner side (against the winding normal) and the outer side (along
   * it) of a DIELECTRIC surface, each clamped to [1, 100] as vtkMediumMaterial's. Defaults 1.5
   * and 1.
   */
  void SetIndexInside(double value);
  vtkGetMacro(IndexInside, double);
  void SetIndexOutside(double value);
  vtkGetMacro(IndexOutside, double);
  ///@}

  ///@{
  /**
   * Interpolate the normal of a DIELECTRIC surface from corner normals (the mesh's point normals
   * when it has them, else the area-weighted mean of the faces at the point, each kept only
   * within 30 degrees of the face's own normal). Off: the flat face normal. Default on.
   */
  vtkSetMacro(SmoothNormals, bool);
  vtkGetMacro(SmoothNormals, bool);
  vtkBooleanMacro(SmoothNormals, bool);
  ///@}

  ///@{
  /**
   * The homogeneous medium inside a DIELECTRIC surface (see the class description). Off
   * (default): the passes sample the grid inside it. Extinction in 1 / world unit (each clamped
   * to [0, 1e30]; NaN or Inf is an error that keeps the value, as for every setter here), albedo
   * in [0, 1], anisotropy g in [-0.9999, 0.9999], emission in radiance
   * per world unit (>= 0): vtkMediumMaterial's units. Defaults: 0, 0, 0 and 0 (clear glass).
   */
  vtkSetMacro(UseInsideMedium, bool);
  vtkGetMacro(UseInsideMedium, bool);
  vtkBooleanMacro(UseInsideMedium, bool);
  void SetInsideExtinction(double r, double g, double b);
  void SetInsideExtinction(const double rgb[3])
  {
    this->SetInsideExtinction(rgb[0], rgb[1], rgb[2]);
  }
  vtkGetVector3Macro(InsideExtinction, double);
  void SetInsideAlbedo(double r, double g, double b);
  void SetInsideAlbedo(const double rgb[3]) { this->SetInsideAlbedo(rgb[0], rgb[1], rgb[2]); }
  vtkGetVector3Macro(InsideAlbedo, double);
  void SetInsideAnisotropy(double value);
  vtkGetMacro(InsideAnisotropy, double);
  void SetInsideEmission(double r, double g, double b);
  void SetInsideEmission(const double rgb[3]) { this->SetInsideEmission(rgb[0], rgb[1], rgb[2]); }
  vtkGetVector3Macro(InsideEmission, double);
  ///@}

  ///@{
  /**
   * A texture (source 2 of the class description): a vtkImageData whose point scalars are colours
   * (unsigned char 0-255 or float/double in [0, 1]; 3 or 4 components, alpha ignored; 1 or 2:
   * grey), pixel (i, j) covering u in [i, i + 1) / width and v in [j, j + 1) / height of the
   * texture coordinates, as vtkTexture maps it. TextureRepeat (default on, vtkTexture's default):
   * coordinates outside [0, 1] wrap; off: clamped to the edge. TextureInterpolate (default off,
   * vtkTexture's default): the nearest pixel; on: bilinear between pixel centres. Kept by
   * reference (its MTime is the material's). nullptr (default): none. A texture that is not
   * usable (HasUsableTexture(): a 2D image, one slice thick, with one scalar tuple of at most 4
   * components per pixel) is ignored, and vtkRefractaSurfaceSet warns.
   */
  void SetTexture(vtkImageData* image);
  vtkImageData* GetTexture() const;
  vtkSetMacro(TextureRepeat, bool);
  vtkGetMacro(TextureRepeat, bool);
  vtkBooleanMacro(TextureRepeat, bool);
  vtkSetMacro(TextureInterpolate, bool);
  vtkGetMacro(TextureInterpolate, bool);
  vtkBooleanMacro(TextureInterpolate, bool);
  ///@}

  /**
   * The texture's colour at texture coordinates (u, v), in [0, 1] (not yet times Albedo); false
   * (rgb untouched) without a usable texture.
   */
  bool EvaluateTexture(double u, double v, double rgb[3]) const;

  /**
   * Whether the texture can be sampled (see SetTexture).
   */
  bool HasUsableTexture() const;

  /**
   * The checker colour at texture coordinates (u, v) (whatever UseChecker says).
   */
  void EvaluateChecker(double u, double v, double rgb[3]) const;

  /**
   * Modification time including the texture's.
   */
  vtkMTimeType GetMTime() override;

  /**
   * Copies every setting of `other` (nullptr: nothing).
   */
  void DeepCopy(vtkRefractaSurfaceMaterial* other);

protected:
  vtkRefractaSurfaceMaterial();
  ~vtkRefractaSurfaceMaterial() override;

  double Albedo[3] = { 0.8, 0.8, 0.8 };
  bool UseChecker = false;
  int CheckerSquares[2] = { 8, 8 };
  double CheckerColor1[3] = { 0.9, 0.9, 0.9 };
  double CheckerColor2[3] = { 0.1, 0.1, 0.1 };
  bool UseScalarColors = false;
  int Kind = LAMBERTIAN;
  double IndexInside = 1.5;
  double IndexOutside = 1.0;
  bool SmoothNormals = true;
  bool UseInsideMedium = false;
  double InsideExtinction[3] = { 0.0, 0.0, 0.0 };
  double InsideAlbedo[3] = { 0.0, 0.0, 0.0 };
  double InsideAnisotropy = 0.0;
  double InsideEmission[3] = { 0.0, 0.0, 0.0 };
  vtkSmartPointer<vtkImageData> Texture;
  bool TextureRepeat = true;
  bool TextureInterpolate = false;

private:
  vtkRefractaSurfaceMaterial(const vtkRefractaSurfaceMaterial&) = delete;
  void operator=(const vtkRefractaSurfaceMaterial&) = delete;
  void SetColor(const char* name, double target[3], double r, double g, double b);
  void SetNonNegative(const char* name, double target[3], double r, double g, double b);
};

#endif
