#include "vtkRefractaRendererBackground.h"

#include "vtkAlgorithm.h"
#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPropCollection.h"
#include "vtkRefractaEnvironmentMap.h"
#include "vtkRefractaViewPass.h"
#include "vtkRenderer.h"
#include "vtkSkybox.h"
#include "vtkTexture.h"

#include <algorithm>
#include <cmath>
#include <vector>

vtkStandardNewMacro(vtkRefractaRendererBackground);

namespace
{
// The texture's input image, its producer updated first; nullptr without one.
vtkImageData* TextureImage(vtkTexture* texture)
{
  if (!texture)
  {
    return nullptr;
  }
  if (vtkAlgorithm* producer = texture->GetInputAlgorithm())
  {
    producer->Update();
  }
  vtkImageData* image = texture->GetInput();
  return image && image->GetPointData()->GetScalars() && image->GetNumberOfPoints() > 0 ? image
                                                                                        : nullptr;
}

// Bilinear, edge-clamped lookup of a 2D image's scalars at (u, v) in [0, 1]^2 (texel centres at
// (i + 0.5) / W), normalised as VTK's textures are (vtkRefractaEnvironmentMap::NormalizingScale).
void SampleClamped(vtkImageData* image, double u, double v, double rgb[3])
{
  int dims[3];
  image->GetDimensions(dims);
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  const int nc = scalars->GetNumberOfComponents();
  const double scale = vtkRefractaEnvironmentMap::NormalizingScale(scalars);
  const double x = std::min(std::max(u * dims[0] - 0.5, 0.0), dims[0] - 1.0);
  const double y = std::min(std::max(v * dims[1] - 0.5, 0.0), dims[1] - 1.0);
  const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
  const int x1 = std::min(x0 + 1, dims[0] - 1), y1 = std::min(y0 + 1, dims[1] - 1);
  const double fx = x - x0, fy = y - y0;
  for (int c = 0; c < 3; ++c)
  {
    const int k = nc < 3 ? 0 : c; // grey (+ alpha) images: the grey channel for R, G and B
    auto at = [&](int i, int j) { return scalars->GetComponent(i + dims[0] * j, k); };
    rgb[c] = scale *
      ((1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x1, y0)) +
        fy * ((1 - fx) * at(x0, y1) + fx * at(x1, y1)));
  }
}

// The viewport position (x, y) in [-1, 1]^2 at which `camera` sees a point infinitely far along
// the world direction d (clamped to the viewport's edges).
void DirectionToViewport(vtkCamera* camera, double aspect, const double d[3], double xy[2])
{
  vtkMatrix4x4* view = camera->GetViewTransformMatrix();
  double c[3];
  for (int r = 0; r < 3; ++r)
  {
    c[r] =
      view->GetElement(r, 0) * d[0] + view->GetElement(r, 1) * d[1] + view->GetElement(r, 2) * d[2];
  }
  const double length = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
  const double ahead = std::max(-c[2], 1e-9 * length); // behind the camera: towards the edges
  const double t = std::tan(0.5 * vtkMath::RadiansFromDegrees(camera->GetViewAngle()));
  // The window centre shifts the frustum, not the screen-space background drawn over it.
  const double* centre = camera->GetWindowCenter();
  xy[0] = std::min(std::max(c[0] / (ahead * t * aspect) - centre[0], -1.0), 1.0);
  xy[1] = std::min(std::max(c[1] / (ahead * t) - centre[1], -1.0), 1.0);
}
}

//------------------------------------------------------------------------------
vtkRefractaRendererBackground::vtkRefractaRendererBackground() = default;
vtkRefractaRendererBackground::~vtkRefractaRendererBackground() = default;

vtkImageData* vtkRefractaRendererBackground::GetEnvironmentMap()
{
  return this->Handed;
}

//------------------------------------------------------------------------------
void vtkRefractaRendererBackground::ScreenBackgroundAt(
  vtkRenderer* renderer, vtkCamera* camera, double aspect, const double d[3], double rgb[3])
{
  double xy[2];
  DirectionToViewport(camera, aspect, d, xy);
  vtkImageData* texture =
    renderer->GetTexturedBackground() ? TextureImage(renderer->GetBackgroundTexture()) : nullptr;
  if (texture)
  {
    SampleClamped(texture, 0.5 * (xy[0] + 1.0), 0.5 * (xy[1] + 1.0), rgb);
    return;
  }
  const double* bottom = renderer->GetBackground();
  const double* top = renderer->GetBackground2();
  const double f = renderer->GetGradientBackground() ? 0.5 * (xy[1] + 1.0) : 0.0;
  for (int c = 0; c < 3; ++c)
  {
    rgb[c] = (1.0 - f) * bottom[c] + f * top[c];
  }
}

//------------------------------------------------------------------------------
int vtkRefractaRendererBackground::ScreenBackgroundSource(vtkRenderer* renderer)
{
  if (renderer->GetTexturedBackground() && TextureImage(renderer->GetBackgroundTexture()))
  {
    return BACKGROUND_TEXTURE; // VTK: a background texture has priority over the gradient
  }
  return renderer->GetGradientBackground() ? GRADIENT : SOLID_COLOR;
}

//------------------------------------------------------------------------------
vtkSkybox* vtkRefractaRendererBackground::VisibleSkybox(vtkRenderer* renderer)
{
  vtkPropCollection* props = renderer->GetViewProps();
  vtkCollectionSimpleIterator it;
  props->InitTraversal(it);
  while (vtkProp* prop = props->GetNextProp(it))
  {
    auto* sky = vtkSkybox::SafeDownCast(prop);
    if (sky && sky->GetVisibility() && sky->GetTexture())
    {
      return sky;
    }
  }
  return nullptr;
}

//------------------------------------------------------------------------------
vtkImageData* vtkRefractaRendererBackground::EquirectangularImage(
  vtkTexture* texture, const char* what)
{
  if (texture->GetCubeMap())
  {
    if (!this->CubeMapReported)
    {
      vtkErrorMacro(<< what
                    << " is a cube map; bent rays see only equirectangular (2D) textures, so "
                       "they see the renderer's background instead.");
      this->CubeMapReported = true;
    }
    return nullptr;
  }
  return TextureImage(texture);
}

//------------------------------------------------------------------------------
vtkImageData* vtkRefractaRendererBackground::EnvironmentImage(
  vtkRenderer* renderer, double up[3], double right[3])
{
  // What VTK draws behind everything first: a skybox (its Sphere projection is the
  // equirectangular image about its floor plane's normal and FloorRight).
  if (vtkSkybox* sky = VisibleSkybox(renderer))
  {
    if (sky->GetProjection() != vtkSkybox::Sphere)
    {
      return nullptr; // cube, floor and stereo projections are not converted
    }
    const float* plane = sky->GetFloorPlane();
    const float* floorRight = sky->GetFloorRight();
    for (int a = 0; a < 3; ++a)
    {
      up[a] = plane[a];
      right[a] = floorRight[a];
    }
    return this->EquirectangularImage(sky->GetTexture(), "The skybox's texture");
  }
  vtkTexture* texture = renderer->GetEnvironmentTexture();
  if (!renderer->GetUseImageBasedLighting() || !texture)
  {
    return nullptr;
  }
  renderer->GetEnvironmentUp(up);
  renderer->GetEnvironmentRight(right);
  return this->EquirectangularImage(texture, "The renderer's environment texture");
}

//------------------------------------------------------------------------------
bool vtkRefractaRendererBackground::ScreenBackgroundIsStale(
  vtkRenderer* renderer, vtkCamera* camera, double aspect)
{
  // Compared by value (not by MTime): what the baked map depends on, and nothing else, so that
  // a render that changes nothing never rebakes it (and never re-runs the view pass).
  std::vector<double> key(renderer->GetBackground(), renderer->GetBackground() + 3);
  key.insert(key.end(), renderer->GetBackground2(), renderer->GetBackground2() + 3);
  key.push_back(renderer->GetGradientBackground());
  key.push_back(renderer->GetTexturedBackground());
  vtkImageData* texture = TextureImage(renderer->GetBackgroundTexture());
  key.push_back(texture ? static_cast<double>(texture->GetMTime()) : -1.0);
  vtkMatrix4x4* view = camera->GetViewTransformMatrix();
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      key.push_back(view->GetElement(r, c));
    }
  }
  key.push_back(camera->GetViewAngle());
  key.push_back(camera->GetWindowCenter()[0]);
  key.push_back(camera->GetWindowCenter()[1]);
  key.push_back(aspect);
  key.push_back(this->EquirectangularWidth);
  const bool stale = !this->Baked || key != this->BakedKey;
  this->BakedKey = key;
  return stale;
}

void vtkRefractaRendererBackground::BakeScreenBackground(
  vtkRenderer* renderer, vtkCamera* camera, double aspect)
{
  const int w = this->EquirectangularWidth, h = w / 2;
  if (!this->Baked)
  {
    this->Baked = vtkSmartPointer<vtkImageData>::New();
  }
  vtkNew<vtkFloatArray> rgb;
  rgb->SetName("Background");
  rgb->SetNumberOfComponents(3);
  rgb->SetNumberOfTuples(static_cast<vtkIdType>(w) * h);
  const double up[3] = { 0, 1, 0 }, right[3] = { 1, 0, 0 };
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      const double uv[2] = { (i + 0.5) / w, (j + 0.5) / h };
      double d[3], colour[3];
      vtkRefractaEnvironmentMap::TextureToDirection(uv, up, right, d);
      ScreenBackgroundAt(renderer, camera, aspect, d, colour);
      rgb->SetTuple(i + static_cast<vtkIdType>(w) * j, colour);
    }
  }
  this->Baked->SetDimensions(w, h, 1);
  this->Baked->GetPointData()->SetScalars(rgb);
  this->Baked->Modified();
}

//------------------------------------------------------------------------------
void vtkRefractaRendererBackground::Apply(
  vtkRenderer* renderer, vtkCamera* camera, vtkRefractaViewPass* pass)
{
  const double* colour = renderer->GetBackground();
  pass->SetBackgroundColor(colour[0], colour[1], colour[2]);
  double up[3], right[3];
  vtkImageData* environment = this->EnvironmentImage(renderer, up, right);
  if (environment)
  {
    this->LastSource = VisibleSkybox(renderer) ? SKYBOX : ENVIRONMENT_TEXTURE;
    pass->SetEnvironmentUp(up);
    pass->SetEnvironmentRight(right);
  }
  else if (this->ScreenBackgroundSource(renderer) != SOLID_COLOR)
  {
    this->LastSource = this->ScreenBackgroundSource(renderer);
    const double aspect = renderer->GetTiledAspectRatio();
    if (this->ScreenBackgroundIsStale(renderer, camera, aspect))
    {
      this->BakeScreenBackground(renderer, camera, aspect);
    }
    environment = this->Baked;
    pass->SetEnvironmentUp(0, 1, 0);
    pass->SetEnvironmentRight(1, 0, 0);
  }
  else
  {
    this->LastSource = SOLID_COLOR;
  }
  this->Handed = environment;
  pass->SetEnvironmentMap(environment);
  this->LastShowsFramePixels = renderer->Transparent() ||
    (camera->GetParallelProjection() &&
      (this->LastSource == GRADIENT || this->LastSource == BACKGROUND_TEXTURE));
}

//------------------------------------------------------------------------------
void vtkRefractaRendererBackground::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "EquirectangularWidth: " << this->EquirectangularWidth << "\n";
  os << indent << "LastSource: " << this->LastSource << "\n";
  os << indent << "LastShowsFramePixels: " << this->LastShowsFramePixels << "\n";
  os << indent << "EnvironmentMap: " << this->Handed.Get() << "\n";
}
