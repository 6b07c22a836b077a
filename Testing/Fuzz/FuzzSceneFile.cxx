// Fuzz target: refracta-render's scene reader. The bytes are a scene file (JSON); it is parsed,
// then read and checked exactly as refracta-render does before it renders (RefractaRender::
// ReadScene: settings, medium, lights, camera, background), without the GPU passes.
//
// Contract checked: a scene is either rejected with a SceneError (a message naming the key), or
// building its medium fails with an error VTK reported, or it yields a medium that passes
// vtkMediumValidator and a camera with finite position and focal point. Any other exception, a
// crash, a hang or a sanitizer report is a bug.
//
// Valid but costly settings are shrunk before reading (grid dimensions to 6 per axis, sphere
// resolution to 8, supersampling to 2, smoothing window to 5, checker squares to 4), so that one
// input runs in about a millisecond; files are looked up in Corpus/Files (tiny meshes and volumes).
#include "FuzzSupport.h"

#include "RefractaScene.h"

#include "vtkCamera.h"
#include "vtkImageData.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkRefractaImageRenderer.h"

#include <cmath>
#include <map>
#include <string>

namespace
{
using RefractaRender::json;

// The costly settings and the largest value each keeps.
const std::map<std::string, double> CostCaps = { { "dimensions", 6 }, { "resolution", 8 },
  { "supersampling", 2 }, { "smoothing_window", 5 }, { "squares", 4 } };

void ClampNumber(json& value, double cap)
{
  if (value.is_number_integer() && value.get<double>() > cap)
  {
    value = static_cast<int>(cap);
  }
  else if (value.is_number() && value.get<double>() > cap)
  {
    value = cap;
  }
}

// Shrinks every costly setting wherever it appears (numbers only: wrong types stay wrong).
void LimitCost(json& node)
{
  if (node.is_object())
  {
    for (auto it = node.begin(); it != node.end(); ++it)
    {
      const auto cap = CostCaps.find(it.key());
      if (cap == CostCaps.end())
      {
        LimitCost(it.value());
        continue;
      }
      if (it.value().is_array())
      {
        for (auto& element : it.value())
        {
          ClampNumber(element, cap->second);
        }
      }
      else
      {
        ClampNumber(it.value(), cap->second);
      }
    }
  }
  else if (node.is_array())
  {
    for (auto& element : node)
    {
      LimitCost(element);
    }
  }
}

// Meshes without grid dimensions would get the default 64^3 grid: give them a small one.
void SmallDefaultGrid(json& scene)
{
  if (!scene.is_object() || !scene.contains("medium") || !scene["medium"].is_object() ||
    !scene["medium"].contains("meshes"))
  {
    return;
  }
  json& medium = scene["medium"];
  if (!medium.contains("grid"))
  {
    medium["grid"] = json::object();
  }
  if (medium["grid"].is_object() && !medium["grid"].contains("dimensions"))
  {
    medium["grid"]["dimensions"] = { 4, 4, 4 };
  }
}

bool IsFinite(const double* v)
{
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

// A camera the view pass can use: finite position and focal point, a proper view frame.
bool IsUsableCamera(vtkCamera* camera)
{
  if (!camera || !IsFinite(camera->GetPosition()) || !IsFinite(camera->GetFocalPoint()))
  {
    return false;
  }
  // The view transform's rotation part: finite, and a rotation (determinant 1), not a
  // collapsed frame from a view-up along the line of sight.
  vtkMatrix4x4* view = camera->GetViewTransformMatrix();
  double rotation[3][3];
  for (int i = 0; i < 9; ++i)
  {
    rotation[i / 3][i % 3] = view->GetElement(i / 3, i % 3);
  }
  const double det = vtkMath::Determinant3x3(rotation);
  return std::isfinite(det) && std::abs(det - 1.0) < 1e-6;
}
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  refracta_fuzz::InstallQuietOutput();
  json scene = json::parse(data, data + size, nullptr, /*allow_exceptions=*/false);
  if (scene.is_discarded())
  {
    return 0; // not JSON: refracta-render says so before reading any key
  }
  LimitCost(scene);
  SmallDefaultGrid(scene);
  refracta_fuzz::ResetErrorCount();
  vtkNew<vtkRefractaImageRenderer> renderer;
  try
  {
    const RefractaRender::Scene read =
      RefractaRender::ReadScene(scene, REFRACTA_FUZZ_FILES_DIR, renderer, /*quiet=*/true);
    refracta_fuzz::Require(read.Medium.Image != nullptr, "a read scene has a medium");
    refracta_fuzz::Require(
      refracta_fuzz::IsValidMedium(read.Medium.Image), "a read scene's medium is valid");
    refracta_fuzz::Require(IsUsableCamera(read.Camera), "a read scene's camera is usable");
  }
  catch (const RefractaRender::SceneError& e)
  {
    // Rejected with a message naming the key: the expected answer to a bad scene.
    refracta_fuzz::Print(e.what());
  }
  catch (const RefractaRender::FilterError& e)
  {
    // A filter refused to build the medium; it must have said why (its message, captured).
    refracta_fuzz::Require(
      !e.Reason.empty(), "a medium that cannot be built comes with its filter's error message");
  }
  return 0;
}
