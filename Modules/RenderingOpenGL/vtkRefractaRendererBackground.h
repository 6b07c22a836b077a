/**
 * @class   vtkRefractaRendererBackground
 * @brief   What a vtkRenderer shows behind everything, as the view pass's background: the
 *          radiance a bent view ray sees when it escapes.
 *
 * vtkRefractiveVolumeMapper hands the renderer's background to its view pass through this class
 * (the one place that converts it). The rules, first match wins:
 * 0. A visible vtkSkybox with a texture (what VTK draws behind everything): with the Sphere
 *    projection and a 2D texture with an input image, that image, equirectangular about the
 *    skybox's floor plane normal (up) and FloorRight, as VTK's skybox shader reads it; with
 *    another projection (cube, floor, stereo) or a cube map, nothing (rule 2-4; a cube map is
 *    reported once).
 * 1. UseImageBasedLighting on and an EnvironmentTexture that is a 2D (not cube-map) texture with
 *    an input image: that image, equirectangular, oriented by the renderer's EnvironmentUp and
 *    EnvironmentRight (the vtkRefractaEnvironmentMap convention, VTK's own).
 * 2. TexturedBackground on and a BackgroundTexture with an input image: the image as VTK draws
 *    it, stretched over the viewport, placed at infinity in front of the camera.
 * 3. GradientBackground on: Background (bottom of the viewport) to Background2 (top), linear in
 *    the viewport's height, placed at infinity in front of the camera as VTK draws it.
 * 4. Otherwise the solid Background colour.
 * Cases 2 and 3 are screen-space backgrounds, which have no direction of their own: a direction
 * d is given the viewport position (x, y) at which the camera would see a point infinitely far
 * along d (the camera's view transform and ViewAngle; a parallel camera uses its ViewAngle as
 * well), clamped to the viewport's edges (so directions behind the camera see the edge colour
 * nearest to them). The result is baked into an equirectangular map with the default basis
 * (EquirectangularWidth x its half, default 512 x 256, bilinear), rebuilt only when the camera,
 * the renderer's background settings or the texture change. Unbent rays therefore see what VTK
 * draws there, up to the map's resolution (0.7 degrees per texel by default). A parallel
 * camera's rays all share one direction, so they would all see the viewport centre's colour:
 * vtkRefractiveVolumeMapper then takes the background VTK drew at each pixel instead (unbent).
 *
 * Colours and texels are used as stored (unsigned char / 255, floating types as they are): the
 * framebuffer's values, so that glass in front of the background shows the colour VTK drew.
 * A cube-map environment texture is not converted: an error is reported once, and rule 2-4
 * applies. With image-based lighting and no skybox, VTK draws the rule 2-4 background around the
 * medium while bent rays see the environment, as VTK's PBR actors reflect it in front of a plain
 * background (rule 1: the environment that lights the scene, see
 * vtkRefractaRenderPipeline::BackgroundIlluminates, is the one they see). A skybox's
 * GammaCorrect is not applied.
 */
#ifndef vtkRefractaRendererBackground_h
#define vtkRefractaRendererBackground_h

#include "RefractaRenderingOpenGLModule.h" // for export macro
#include "vtkObject.h"
#include "vtkSmartPointer.h" // for members

#include <vector> // for std::vector

class vtkCamera;
class vtkImageData;
class vtkRenderer;
class vtkRefractaViewPass;
class vtkSkybox;
class vtkTexture;

class REFRACTARENDERINGOPENGL_EXPORT vtkRefractaRendererBackground : public vtkObject
{
public:
  static vtkRefractaRendererBackground* New();
  vtkTypeMacro(vtkRefractaRendererBackground, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Which rule applied in the last Update().
  enum Source
  {
    SOLID_COLOR = 0,
    ENVIRONMENT_TEXTURE = 1,
    BACKGROUND_TEXTURE = 2,
    GRADIENT = 3,
    SKYBOX = 4
  };

  ///@{
  /**
   * Width of the equirectangular map baked for screen-space backgrounds (rules 2 and 3), in
   * texels; the height is half of it. Clamped to [16, 8192]; default 512.
   */
  vtkSetClampMacro(EquirectangularWidth, int, 16, 8192);
  vtkGetMacro(EquirectangularWidth, int);
  ///@}

  /**
   * Reads `renderer`'s background for `camera` (the renderer's aspect ratio) and sets the view
   * pass's BackgroundColor, EnvironmentMap, EnvironmentUp and EnvironmentRight. The view pass's
   * settings are touched only when they change, so an unchanged background never re-runs it.
   */
  void Apply(vtkRenderer* renderer, vtkCamera* camera, vtkRefractaViewPass* pass);

  /// The rule of the last Apply() (see Source).
  vtkGetMacro(LastSource, int);

  /**
   * Whether, at the last Apply(), what shows behind the medium is the frame's own pixel rather
   * than anything a direction can look up: in a transparent renderer (a layer above 0, over
   * what the layers below drew; its own background is never drawn), and for a screen-space
   * background (rules 2, 3) seen through a parallel camera, whose rays share one direction and
   * would all see the viewport centre's colour. vtkRefractiveVolumeMapper then takes VTK's pixel,
   * unbent (vtkRefractiveVolumeMapperCompositing.h).
   */
  vtkGetMacro(LastShowsFramePixels, bool);

  /// The environment image handed over by the last Apply() (nullptr for a solid colour).
  vtkImageData* GetEnvironmentMap();

  /**
   * The radiance a screen-space background (rules 2, 3) shows in world direction `d` for
   * `camera`: what the baked map samples. For tests and for documentation of the convention.
   */
  static void ScreenBackgroundAt(
    vtkRenderer* renderer, vtkCamera* camera, double aspect, const double d[3], double rgb[3]);

protected:
  vtkRefractaRendererBackground();
  ~vtkRefractaRendererBackground() override;

  int EquirectangularWidth = 512;
  int LastSource = SOLID_COLOR;
  bool LastShowsFramePixels = false;

private:
  vtkRefractaRendererBackground(const vtkRefractaRendererBackground&) = delete;
  void operator=(const vtkRefractaRendererBackground&) = delete;

  // Rules 0 and 1: the equirectangular image and its basis, or nullptr.
  vtkImageData* EnvironmentImage(vtkRenderer* renderer, double up[3], double right[3]);
  // The texture's image, or nullptr (and one error) for a cube map; `what` names it.
  vtkImageData* EquirectangularImage(vtkTexture* texture, const char* what);
  static vtkSkybox* VisibleSkybox(vtkRenderer* renderer);
  void BakeScreenBackground(vtkRenderer* renderer, vtkCamera* camera, double aspect);
  bool ScreenBackgroundIsStale(vtkRenderer* renderer, vtkCamera* camera, double aspect);

  static int ScreenBackgroundSource(vtkRenderer* renderer);

  vtkSmartPointer<vtkImageData> Baked;
  vtkSmartPointer<vtkImageData> Handed;
  std::vector<double> BakedKey; // what the baked map was made from
  bool CubeMapReported = false;
};

#endif
