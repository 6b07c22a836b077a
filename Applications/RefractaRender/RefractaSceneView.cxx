#include "RefractaSceneView.h"

#include "RefractaSceneMedium.h"

#include "vtkCamera.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkRefractaEnvironmentMap.h"
#include "vtkRefractaImageRenderer.h"

#include <algorithm>
#include <vector>

namespace RefractaRender
{
namespace
{
vtkSmartPointer<vtkLight> ReadLight(const json& l, const std::string& p)
{
  CheckKeys(
    l, p, { "type", "position", "focal_point", "color", "intensity", "cone_angle", "exponent" });
  const std::string type = String(l, "type", p, "", { "directional", "point", "spot" });
  if (type.empty())
  {
    Fail(p + ".type", "missing (directional, point or spot)");
  }
  if (!l.contains("position"))
  {
    Fail(p + ".position", "missing");
  }
  auto light = vtkSmartPointer<vtkLight>::New();
  light->SetLightTypeToSceneLight();
  auto pos = Vector(l, "position", p, {}, 3, -1e30, 1e30);
  auto fp = Vector(l, "focal_point", p, { 0, 0, 0 }, 3, -1e30, 1e30);
  if (pos == fp && type != "point") // a point light shines everywhere: no direction to give
  {
    Fail(p + ".focal_point",
      "must differ from the position (it gives the " + type + " light's direction)");
  }
  light->SetPosition(pos.data());
  light->SetFocalPoint(fp.data());
  auto colour = Vector(l, "color", p, { 1, 1, 1 }, 3, 0, 1e30);
  light->SetDiffuseColor(colour.data());
  light->SetIntensity(Number(l, "intensity", p, 1.0, 0.0, 1e30));
  light->SetPositional(type != "directional");
  light->SetConeAngle(type == "spot" ? Number(l, "cone_angle", p, 30.0, 0.01, 89.99) : 180.0);
  light->SetExponent(Number(l, "exponent", p, 1.0, 0.0, 128.0));
  if (type != "spot" && l.contains("cone_angle"))
  {
    Fail(p + ".cone_angle", "only for spot lights");
  }
  return light;
}
}

int AddLights(const json& scene, vtkRefractaImageRenderer* renderer)
{
  if (!scene.contains("lights"))
  {
    return 0;
  }
  const json& lights = scene["lights"];
  if (!lights.is_array())
  {
    Fail("scene.lights", "must be an array of lights");
  }
  for (size_t i = 0; i < lights.size(); ++i)
  {
    renderer->AddLight(ReadLight(lights[i], "scene.lights[" + std::to_string(i) + "]"));
  }
  return static_cast<int>(lights.size());
}

vtkSmartPointer<vtkCamera> ReadCamera(const json& scene, vtkImageData* medium)
{
  const json cam = scene.value("camera", json::object());
  CheckKeys(cam, "scene.camera",
    { "position", "focal_point", "view_up", "view_angle", "projection", "parallel_scale" });
  double bounds[6];
  medium->GetBounds(bounds);
  const double centre[3] = { 0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3]),
    0.5 * (bounds[4] + bounds[5]) };
  // The voxels' extent, half a voxel past the outer centres (a single voxel still has a size).
  const double* spacing = medium->GetSpacing();
  const double size = std::max({ bounds[1] - bounds[0] + spacing[0],
    bounds[3] - bounds[2] + spacing[1], bounds[5] - bounds[4] + spacing[2] });
  auto fp =
    Vector(cam, "focal_point", "scene.camera", { centre[0], centre[1], centre[2] }, 3, -1e30, 1e30);
  auto pos = Vector(cam, "position", "scene.camera",
    { centre[0], centre[1] + 0.3 * size, centre[2] + 2.2 * size }, 3, -1e30, 1e30);
  if (pos == fp)
  {
    Fail("scene.camera.position", "must differ from the focal point");
  }
  auto up = Vector(cam, "view_up", "scene.camera", { 0, 1, 0 }, 3, -1e30, 1e30);
  // The view-up must give the image a vertical: not zero, not along the line of sight.
  const double dir[3] = { fp[0] - pos[0], fp[1] - pos[1], fp[2] - pos[2] };
  double side[3];
  vtkMath::Cross(dir, up.data(), side);
  if (!(vtkMath::Norm(side) > 1e-9 * vtkMath::Norm(dir) * vtkMath::Norm(up.data())))
  {
    Fail("scene.camera.view_up",
      "must be non-zero and not parallel to the line of sight "
      "(from position to focal_point)");
  }
  auto camera = vtkSmartPointer<vtkCamera>::New();
  camera->SetFocalPoint(fp.data());
  camera->SetPosition(pos.data());
  camera->SetViewUp(up.data());
  camera->SetViewAngle(Number(cam, "view_angle", "scene.camera", 30.0, 0.1, 179.0));
  const std::string projection =
    String(cam, "projection", "scene.camera", "perspective", { "perspective", "parallel" });
  camera->SetParallelProjection(projection == "parallel");
  camera->SetParallelScale(Number(cam, "parallel_scale", "scene.camera", 0.6 * size, 1e-30, 1e30));
  return camera;
}

bool ReadBackground(const json& scene, const std::string& base, vtkRefractaImageRenderer* renderer)
{
  const json bg = scene.value("background", json::object());
  CheckKeys(
    bg, "scene.background", { "color", "environment", "checker", "up", "right", "illuminates" });
  if (bg.contains("environment") + bg.contains("checker") + bg.contains("color") > 1)
  {
    Fail("scene.background", "give one of 'color', 'environment' or 'checker'");
  }
  auto colour = Vector(bg, "color", "scene.background", { 0, 0, 0 }, 3, 0, 1e30);
  renderer->SetBackgroundColor(colour[0], colour[1], colour[2]);
  if (bg.contains("environment"))
  {
    if (!bg["environment"].is_string())
    {
      Fail("scene.background.environment", "must be an image file name");
    }
    const std::string file = Resolve(base, bg["environment"].get<std::string>());
    vtkSmartPointer<vtkImageData> map = ReadImageFile(file, "scene.background.environment");
    // Checked now, not after the light passes that would run first.
    std::vector<double> radiance;
    int size[2];
    std::string error;
    if (!vtkRefractaEnvironmentMap::ReadRadiance(map, radiance, size, error))
    {
      Fail("scene.background.environment", "'" + file + "': " + error);
    }
    renderer->SetEnvironmentMap(map);
  }
  if (bg.contains("checker"))
  {
    const json& c = bg["checker"];
    const std::string p = "scene.background.checker";
    CheckKeys(c, p, { "squares", "color1", "color2" });
    const auto squares = IntegerVector(c, "squares", p, { 16, 8 }, 2, 1, 512);
    const auto color1 = Vector(c, "color1", p, { 0.9, 0.9, 0.9 }, 3, 0, 1e30);
    const auto color2 = Vector(c, "color2", p, { 0.1, 0.1, 0.1 }, 3, 0, 1e30);
    // Procedural: the passes evaluate the squares per ray (sharp edges at any resolution).
    renderer->SetEnvironmentMap(
      vtkRefractaEnvironmentMap::MakeChecker(squares[0], squares[1], color1.data(), color2.data()));
  }
  auto up = Vector(bg, "up", "scene.background", { 0, 1, 0 }, 3, -1e30, 1e30);
  auto right = Vector(bg, "right", "scene.background", { 1, 0, 0 }, 3, -1e30, 1e30);
  double basis[3][3];
  if (!vtkRefractaEnvironmentMap::ComputeBasis(
        up.data(), right.data(), basis[0], basis[1], basis[2]))
  {
    Fail("scene.background.up",
      "must not be zero nor parallel to scene.background.right (the "
      "two orient the environment)");
  }
  renderer->SetEnvironmentUp(up[0], up[1], up[2]);
  renderer->SetEnvironmentRight(right[0], right[1], right[2]);
  const bool illuminates = Boolean(bg, "illuminates", "scene.background", false);
  return illuminates;
}
}
