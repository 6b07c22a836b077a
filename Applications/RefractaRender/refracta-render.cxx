// refracta-render: Refracta's command-line renderer.
//
//   refracta-render                          render the embedded default scene to refracta.png
//   refracta-render --scene FILE.json        render a scene described in JSON (README: schema)
//   options: --output FILE.png, --hdr FILE.vti (HDR image), --radiance FILE.vti (medium +
//   lighting volume), --report FILE.json, --preview (a cheaper version of the same scene),
//   --print-default-scene, --list-devices,
//   --device-check (the OpenCL end-to-end check of earlier versions), --help.
//
// Pipeline: scene JSON -> medium (vtkMeshVoxelizer for meshes, vtkTransferFunctionMedium or the
// file itself for volumes) -> vtkRefractaRenderPipeline (effect plan, light passes, view pass;
// through vtkRefractaImageRenderer) -> PNG; each stage printed as it runs, a short report on
// stdout and, optionally, a JSON report with per-stage timings, settings, counts and the energy
// balance.
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkCommand.h"
#include "vtkCubeSource.h"
#include "vtkDataArray.h"
#include "vtkEffectPlan.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkJPEGReader.h"
#include "vtkLatticeBoltzmannSolver.h"
#include "vtkLight.h"
#include "vtkMediumMaterial.h"
#include "vtkMediumValidator.h"
#include "vtkMeshVoxelizer.h"
#include "vtkMetaImageReader.h"
#include "vtkNew.h"
#include "vtkNrrdReader.h"
#include "vtkOBJReader.h"
#include "vtkOpenCLContext.h"
#include "vtkPLYReader.h"
#include "vtkPNGReader.h"
#include "vtkPNGWriter.h"
#include "vtkPhotonTracer.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkRefractaImageRenderer.h"
#include "vtkRefractaRenderPipeline.h"
#include "vtkRefractaViewPass.h"
#include "vtkSTLReader.h"
#include "vtkSceneAnalysis.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"
#include "vtkTransferFunctionMedium.h"
#include "vtkTriangleFilter.h"
#include "vtkUnsignedCharArray.h"
#include "vtkVolumeProperty.h"
#include "vtkXMLImageDataReader.h"
#include "vtkXMLImageDataWriter.h"
#include "vtkXMLPolyDataReader.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unistd.h>
#include <vector>

using json = nlohmann::ordered_json;

namespace
{
// The embedded default scene: a glass sphere (n = 1.5) in a light fog above a scattering floor,
// lit by a spot light from above (the sphere focuses it into a caustic on the floor and in the
// fog), in front of a checkerboard environment that the sphere bends.
const char* const DefaultScene = R"JSON({
  "image": { "width": 256, "height": 256, "exposure": 1.5, "tone_mapping": "reinhard" },
  "camera": { "position": [0.0, 0.55, 3.2], "focal_point": [0.0, -0.1, 0.0],
              "view_up": [0, 1, 0], "view_angle": 34 },
  "background": { "checker": { "squares": [24, 12],
                  "color1": [0.9, 0.85, 0.75], "color2": [0.08, 0.12, 0.3] } },
  "medium": {
    "grid": { "dimensions": [80, 80, 80], "bounds": [-1, 1, -1, 1, -1, 1] },
    "surrounding": { "extinction": [0.35, 0.35, 0.35], "albedo": [0.9, 0.9, 0.9],
                     "anisotropy": 0.3 },
    "meshes": [
      { "sphere": { "center": [0, 0.05, 0], "radius": 0.42, "resolution": 96 },
        "material": { "refractive_index": 1.5, "extinction": [0.02, 0.02, 0.02] } },
      { "box": { "bounds": [-1.2, 1.2, -1.2, -0.8, -1.2, 1.2] },
        "material": { "extinction": [12, 12, 12], "albedo": [0.85, 0.8, 0.7] } }
    ]
  },
  "lights": [
    { "type": "spot", "position": [0, 3, 0], "focal_point": [0, 0, 0], "cone_angle": 12,
      "exponent": 1, "color": [1.0, 0.95, 0.85], "intensity": 60 }
  ],
  "quality": { "photons": 262144, "view_step": 1.0, "seed": 1,
               "multiple_scattering": true, "multiple_scattering_tolerance": 0.001 }
})JSON";

// ---------------------------------------------------------------------------------------------
// Strict JSON access: every key must be known, every value checked; errors name the key path.
struct SceneError : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

[[noreturn]] void Fail(const std::string& path, const std::string& what)
{
  throw SceneError(path + ": " + what);
}

void CheckKeys(const json& object, const std::string& path, const std::set<std::string>& allowed)
{
  if (!object.is_object())
  {
    Fail(path, "must be a JSON object");
  }
  for (auto it = object.begin(); it != object.end(); ++it)
  {
    if (!allowed.count(it.key()))
    {
      std::string list;
      for (const auto& a : allowed)
      {
        list += (list.empty() ? "" : ", ") + a;
      }
      Fail(path + "." + it.key(), "unknown key (allowed here: " + list + ")");
    }
  }
}

double Number(const json& object, const std::string& key, const std::string& path, double fallback,
  double lo, double hi)
{
  if (!object.contains(key))
  {
    return fallback;
  }
  const json& v = object[key];
  if (!v.is_number())
  {
    Fail(path + "." + key, "must be a number");
  }
  const double d = v.get<double>();
  if (!std::isfinite(d) || d < lo || d > hi)
  {
    std::ostringstream os;
    os << "value " << d << " is out of range [" << lo << ", " << hi << "]";
    Fail(path + "." + key, os.str());
  }
  return d;
}

int Integer(
  const json& object, const std::string& key, const std::string& path, int fallback, int lo, int hi)
{
  if (object.contains(key) && !object[key].is_number_integer())
  {
    Fail(path + "." + key, "must be an integer");
  }
  return static_cast<int>(Number(object, key, path, fallback, lo, hi));
}

std::vector<double> Vector(const json& object, const std::string& key, const std::string& path,
  std::vector<double> fallback, size_t size, double lo, double hi)
{
  if (!object.contains(key))
  {
    return fallback;
  }
  const json& v = object[key];
  if (!v.is_array() || v.size() != size)
  {
    Fail(path + "." + key, "must be an array of " + std::to_string(size) + " numbers");
  }
  std::vector<double> out;
  for (size_t i = 0; i < size; ++i)
  {
    if (!v[i].is_number())
    {
      Fail(path + "." + key + "[" + std::to_string(i) + "]", "must be a number");
    }
    const double d = v[i].get<double>();
    if (!std::isfinite(d) || d < lo || d > hi)
    {
      std::ostringstream os;
      os << "value " << d << " is out of range [" << lo << ", " << hi << "]";
      Fail(path + "." + key + "[" + std::to_string(i) + "]", os.str());
    }
    out.push_back(d);
  }
  return out;
}

std::string String(const json& object, const std::string& key, const std::string& path,
  const std::string& fallback, const std::set<std::string>& choices = {})
{
  if (!object.contains(key))
  {
    return fallback;
  }
  if (!object[key].is_string())
  {
    Fail(path + "." + key, "must be a string");
  }
  const std::string s = object[key].get<std::string>();
  if (!choices.empty() && !choices.count(s))
  {
    std::string list;
    for (const auto& c : choices)
    {
      list += (list.empty() ? "" : ", ") + c;
    }
    Fail(path + "." + key, "'" + s + "' is not one of: " + list);
  }
  return s;
}

bool Boolean(const json& object, const std::string& key, const std::string& path, bool fallback)
{
  if (!object.contains(key))
  {
    return fallback;
  }
  if (!object[key].is_boolean())
  {
    Fail(path + "." + key, "must be true or false");
  }
  return object[key].get<bool>();
}

std::string Lower(std::string s)
{
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

std::string Extension(const std::string& file)
{
  const size_t dot = file.find_last_of('.');
  return dot == std::string::npos ? "" : Lower(file.substr(dot + 1));
}

std::string Resolve(const std::string& base, const std::string& file)
{
  if (file.empty() || file[0] == '/' || base.empty())
  {
    return file;
  }
  return base + "/" + file;
}

bool FileExists(const std::string& file)
{
  std::ifstream in(file);
  return in.good();
}

// Collects VTK error messages of a reader or filter so they can name the scene key.
struct Timer
{
  std::chrono::steady_clock::time_point Start = std::chrono::steady_clock::now();
  double Seconds() const
  {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - this->Start).count();
  }
};

vtkSmartPointer<vtkMediumMaterial> ReadMaterial(const json& m, const std::string& path)
{
  CheckKeys(m, path, { "refractive_index", "extinction", "albedo", "anisotropy", "emission" });
  auto material = vtkSmartPointer<vtkMediumMaterial>::New();
  material->SetRefractiveIndex(Number(m, "refractive_index", path, 1.0, 1.0, 100.0));
  auto e = Vector(m, "extinction", path, { 0, 0, 0 }, 3, 0.0, 1e9);
  material->SetExtinction(e.data());
  auto a = Vector(m, "albedo", path, { 0, 0, 0 }, 3, 0.0, 1.0);
  material->SetAlbedo(a.data());
  material->SetAnisotropy(Number(m, "anisotropy", path, 0.0, -0.9999, 0.9999));
  auto em = Vector(m, "emission", path, { 0, 0, 0 }, 3, 0.0, 1e9);
  material->SetEmission(em.data());
  return material;
}

vtkSmartPointer<vtkPolyData> ReadMesh(
  const json& mesh, const std::string& path, const std::string& base)
{
  vtkSmartPointer<vtkPolyData> poly;
  int kinds = mesh.contains("file") + mesh.contains("sphere") + mesh.contains("box");
  if (kinds != 1)
  {
    Fail(path, "needs exactly one of 'file', 'sphere' or 'box'");
  }
  if (mesh.contains("sphere"))
  {
    const json& s = mesh["sphere"];
    const std::string p = path + ".sphere";
    CheckKeys(s, p, { "center", "radius", "resolution" });
    auto c = Vector(s, "center", p, { 0, 0, 0 }, 3, -1e30, 1e30);
    vtkNew<vtkSphereSource> source;
    source->SetCenter(c.data());
    source->SetRadius(Number(s, "radius", p, 1.0, 1e-30, 1e30));
    const int res = Integer(s, "resolution", p, 64, 8, 1024);
    source->SetThetaResolution(res);
    source->SetPhiResolution(res / 2);
    source->Update();
    poly = source->GetOutput();
  }
  else if (mesh.contains("box"))
  {
    const json& b = mesh["box"];
    const std::string p = path + ".box";
    CheckKeys(b, p, { "bounds" });
    if (!b.contains("bounds"))
    {
      Fail(p + ".bounds", "missing (xmin, xmax, ymin, ymax, zmin, zmax)");
    }
    auto bounds = Vector(b, "bounds", p, {}, 6, -1e30, 1e30);
    for (int a = 0; a < 3; ++a)
    {
      if (!(bounds[2 * a] < bounds[2 * a + 1]))
      {
        Fail(p + ".bounds", "every min must be below its max");
      }
    }
    vtkNew<vtkCubeSource> cube;
    cube->SetBounds(bounds.data());
    vtkNew<vtkTriangleFilter> triangles;
    triangles->SetInputConnection(cube->GetOutputPort());
    triangles->Update();
    poly = triangles->GetOutput();
  }
  else
  {
    if (!mesh["file"].is_string())
    {
      Fail(path + ".file", "must be a file name");
    }
    const std::string file = Resolve(base, mesh["file"].get<std::string>());
    if (!FileExists(file))
    {
      Fail(path + ".file", "cannot read '" + file + "'");
    }
    const std::string ext = Extension(file);
    vtkSmartPointer<vtkAlgorithm> reader;
    if (ext == "ply")
    {
      auto r = vtkSmartPointer<vtkPLYReader>::New();
      r->SetFileName(file.c_str());
      reader = r;
    }
    else if (ext == "stl")
    {
      auto r = vtkSmartPointer<vtkSTLReader>::New();
      r->SetFileName(file.c_str());
      reader = r;
    }
    else if (ext == "obj")
    {
      auto r = vtkSmartPointer<vtkOBJReader>::New();
      r->SetFileName(file.c_str());
      reader = r;
    }
    else if (ext == "vtp")
    {
      auto r = vtkSmartPointer<vtkXMLPolyDataReader>::New();
      r->SetFileName(file.c_str());
      reader = r;
    }
    else
    {
      Fail(path + ".file",
        "'" + file + "' has an unsupported extension (use .ply, .stl, .obj or .vtp)");
    }
    reader->Update();
    poly = vtkPolyData::SafeDownCast(reader->GetOutputDataObject(0));
    if (!poly || poly->GetNumberOfPolys() == 0)
    {
      Fail(path + ".file", "'" + file + "' holds no polygons");
    }
  }
  return poly;
}

vtkSmartPointer<vtkImageData> ReadImageFile(const std::string& file, const std::string& path)
{
  if (!FileExists(file))
  {
    Fail(path, "cannot read '" + file + "'");
  }
  const std::string ext = Extension(file);
  vtkSmartPointer<vtkAlgorithm> reader;
  if (ext == "vti")
  {
    auto r = vtkSmartPointer<vtkXMLImageDataReader>::New();
    r->SetFileName(file.c_str());
    reader = r;
  }
  else if (ext == "mha" || ext == "mhd")
  {
    auto r = vtkSmartPointer<vtkMetaImageReader>::New();
    r->SetFileName(file.c_str());
    reader = r;
  }
  else if (ext == "nrrd" || ext == "nhdr")
  {
    auto r = vtkSmartPointer<vtkNrrdReader>::New();
    r->SetFileName(file.c_str());
    reader = r;
  }
  else if (ext == "png")
  {
    auto r = vtkSmartPointer<vtkPNGReader>::New();
    r->SetFileName(file.c_str());
    reader = r;
  }
  else if (ext == "jpg" || ext == "jpeg")
  {
    auto r = vtkSmartPointer<vtkJPEGReader>::New();
    r->SetFileName(file.c_str());
    reader = r;
  }
  else
  {
    Fail(path,
      "'" + file +
        "' has an unsupported extension (use .vti, .mha, .mhd, .nrrd, .nhdr, .png or .jpg)");
  }
  reader->Update();
  auto image = vtkSmartPointer<vtkImageData>::New();
  if (auto* out = vtkImageData::SafeDownCast(reader->GetOutputDataObject(0)))
  {
    image->ShallowCopy(out);
  }
  if (image->GetNumberOfPoints() == 0)
  {
    Fail(path, "'" + file + "' could not be read as an image");
  }
  return image;
}

// Equirectangular checkerboard (linear RGB floats).
vtkSmartPointer<vtkImageData> Checker(
  int nu, int nv, const std::vector<double>& c1, const std::vector<double>& c2)
{
  const int w = std::max(nu * 16, 64), h = std::max(nv * 16, 32);
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(w, h, 1);
  vtkNew<vtkFloatArray> rgb;
  rgb->SetName("checker");
  rgb->SetNumberOfComponents(3);
  rgb->SetNumberOfTuples(static_cast<vtkIdType>(w) * h);
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      const bool odd = ((i * nu / w) + (j * nv / h)) % 2;
      const std::vector<double>& c = odd ? c1 : c2;
      rgb->SetTuple3(i + w * j, c[0], c[1], c[2]);
    }
  }
  image->GetPointData()->SetScalars(rgb);
  return image;
}

json FieldDataToJson(vtkFieldData* fd)
{
  json out = json::object();
  for (int i = 0; fd && i < fd->GetNumberOfArrays(); ++i)
  {
    vtkDataArray* a = fd->GetArray(i);
    if (!a || !a->GetName() || a->GetNumberOfTuples() < 1)
    {
      continue;
    }
    if (a->GetNumberOfComponents() == 1)
    {
      out[a->GetName()] = a->GetComponent(0, 0);
    }
    else
    {
      json v = json::array();
      for (int c = 0; c < a->GetNumberOfComponents(); ++c)
      {
        v.push_back(a->GetComponent(0, c));
      }
      out[a->GetName()] = v;
    }
  }
  return out;
}

struct Options
{
  std::string Scene;
  std::string Output = "refracta.png";
  std::string Hdr;
  std::string Radiance;
  std::string Report;
  bool Preview = false;
  bool Quiet = false;
};

// Prints each stage of the render pipeline as it starts and ends (with its seconds) and, on a
// terminal, a progress bar; silent with --quiet.
class StageReporter
{
public:
  StageReporter(vtkRefractaRenderPipeline* pipeline, bool quiet)
    : Pipeline(pipeline)
    , Terminal(isatty(STDOUT_FILENO) != 0)
  {
    if (quiet)
    {
      return;
    }
    this->Command->SetClientData(this);
    this->Command->SetCallback(&StageReporter::OnEvent);
    for (unsigned long event :
      { vtkCommand::StartEvent, vtkCommand::EndEvent, vtkCommand::ProgressEvent })
    {
      this->Tags.push_back(pipeline->AddObserver(event, this->Command));
    }
  }
  ~StageReporter()
  {
    for (unsigned long tag : this->Tags)
    {
      this->Pipeline->RemoveObserver(tag);
    }
  }
  StageReporter(const StageReporter&) = delete;
  StageReporter& operator=(const StageReporter&) = delete;

private:
  static void OnEvent(vtkObject*, unsigned long event, void* client, void* call)
  {
    auto* self = static_cast<StageReporter*>(client);
    if (event == vtkCommand::ProgressEvent)
    {
      self->Bar(*static_cast<double*>(call));
      return;
    }
    const char* stage = static_cast<const char*>(call);
    if (event == vtkCommand::StartEvent)
    {
      self->Stage.Start = std::chrono::steady_clock::now();
      self->Line(std::string("  ") + stage + " ...");
      return;
    }
    std::ostringstream line;
    line << "  " << stage << " done, " << self->Stage.Seconds() << " s";
    self->Line(line.str());
  }

  void Line(const std::string& text)
  {
    std::cout << (this->Terminal ? "\r\033[K" : "") << text << std::endl;
    this->Drawn = -1;
  }

  void Bar(double fraction)
  {
    const int width = 40;
    const int filled = static_cast<int>(fraction * width);
    if (!this->Terminal || filled == this->Drawn)
    {
      return;
    }
    this->Drawn = filled;
    std::cout << "\r  [" << std::string(filled, '#') << std::string(width - filled, ' ') << "] "
              << static_cast<int>(100 * fraction) << "%" << std::flush;
  }

  vtkRefractaRenderPipeline* Pipeline;
  bool Terminal;
  int Drawn = -1;
  Timer Stage;
  vtkNew<vtkCallbackCommand> Command;
  std::vector<unsigned long> Tags;
};

// --preview: the same scene at a quarter of the cost or less: half the image size, a quarter of
// the photons and (for meshes with explicit grid dimensions) half the grid resolution.
void MakePreview(json& scene)
{
  if (!scene.is_object())
  {
    return;
  }
  json& image = scene["image"];
  if (image.is_null())
  {
    image = json::object();
  }
  if (image.is_object())
  {
    image["width"] = std::max(16, image.value("width", 256) / 2);
    image["height"] = std::max(16, image.value("height", 256) / 2);
  }
  json& quality = scene["quality"];
  if (quality.is_null())
  {
    quality = json::object();
  }
  if (quality.is_object())
  {
    quality["photons"] = std::max(4096, quality.value("photons", 1 << 18) / 4);
  }
  if (scene.contains("medium") && scene["medium"].is_object() && scene["medium"].contains("grid") &&
    scene["medium"]["grid"].is_object() && scene["medium"]["grid"].contains("dimensions") &&
    scene["medium"]["grid"]["dimensions"].is_array())
  {
    for (auto& d : scene["medium"]["grid"]["dimensions"])
    {
      if (d.is_number_integer())
      {
        d = std::max(8, d.get<int>() / 2);
      }
    }
  }
}

// Renders a scene; throws SceneError for bad scenes, std::runtime_error for failed stages.
int Render(const json& scene, const std::string& base, const Options& options)
{
  Timer total;
  json report;
  json timings = json::object();
  CheckKeys(
    scene, "scene", { "image", "camera", "background", "medium", "lights", "quality", "effects" });

  // --- settings ---
  const json image = scene.value("image", json::object());
  CheckKeys(image, "scene.image", { "width", "height", "exposure", "tone_mapping" });
  const int width = Integer(image, "width", "scene.image", 256, 1, 16384);
  const int height = Integer(image, "height", "scene.image", 256, 1, 16384);
  const double exposure = Number(image, "exposure", "scene.image", 1.0, 0.0, 1e30);
  const std::string toneMapping =
    String(image, "tone_mapping", "scene.image", "clamp", { "clamp", "reinhard", "exponential" });

  const json quality = scene.value("quality", json::object());
  CheckKeys(quality, "scene.quality",
    { "preset", "photons", "seed", "view_step", "ray_mode", "transmittance_cutoff",
      "photon_min_step", "octree_tolerance", "photon_smoothing", "multiple_scattering",
      "multiple_scattering_tolerance", "multiple_scattering_block_size", "tolerance" });
  // One render pipeline does the work (vtkRefractaRenderPipeline, through the image renderer
  // that tone-maps its image). A quality preset supplies the defaults of the pass settings and of
  // the plan's tolerance; keys given explicitly win.
  vtkNew<vtkRefractaImageRenderer> renderer;
  vtkRefractaRenderPipeline* pipeline = renderer->GetPipeline();
  vtkEffectPlan* plan = pipeline->GetEffectPlan();
  const std::string preset = String(
    quality, "preset", "scene.quality", "none", { "none", "draft", "interactive", "production" });
  const bool hasPreset = preset != "none";
  if (hasPreset)
  {
    pipeline->SetQuality(preset == "draft"
        ? vtkEffectPlan::DRAFT
        : (preset == "interactive" ? vtkEffectPlan::INTERACTIVE : vtkEffectPlan::PRODUCTION));
  }
  const int photons = Integer(quality, "photons", "scene.quality",
    hasPreset ? plan->GetRecommendedNumberOfPhotons() : 1 << 18, 1, 1 << 28);
  const int seed = Integer(quality, "seed", "scene.quality", 1, 0, 2147483647);
  const double viewStep = Number(quality, "view_step", "scene.quality",
    hasPreset ? plan->GetRecommendedViewStep() : 1.0, 0.01, 16.0);
  const std::string rayMode =
    String(quality, "ray_mode", "scene.quality", "auto", { "auto", "straight", "curved" });
  const double cutoff = Number(quality, "transmittance_cutoff", "scene.quality", 1e-4, 0.0, 1.0);
  const double photonMinStep = Number(quality, "photon_min_step", "scene.quality",
    hasPreset ? plan->GetRecommendedPhotonMinimumStep() : 1.0, 1e-3, 1e6);
  const double octreeTolerance = Number(quality, "octree_tolerance", "scene.quality",
    hasPreset ? plan->GetRecommendedOctreeTolerance() : 0.005, 0.0, 1.0);
  const bool photonSmoothing = Boolean(quality, "photon_smoothing", "scene.quality", true);
  const bool multipleScattering = Boolean(quality, "multiple_scattering", "scene.quality", true);
  const double lblTolerance = Number(quality, "multiple_scattering_tolerance", "scene.quality",
    hasPreset ? plan->GetRecommendedLatticeTolerance() : 1e-4, 1e-8, 1.0);
  const int lblBlockSize = Integer(quality, "multiple_scattering_block_size", "scene.quality",
    hasPreset ? plan->GetRecommendedLatticeBlockSize() : 4, 0, 8);
  // The effect plan: the relative image change an effect may cause and still be skipped, and
  // per-effect overrides ("auto", "on", "off").
  const double planTolerance = Number(
    quality, "tolerance", "scene.quality", hasPreset ? plan->GetTolerance() : 0.01, 0.0, 1.0);
  plan->SetTolerance(planTolerance);
  {
    const json effects = scene.value("effects", json::object());
    CheckKeys(effects, "scene.effects",
      { "refraction", "absorption", "single_scattering", "multiple_scattering", "emission" });
    const char* keys[] = { "refraction", "absorption", "single_scattering", "multiple_scattering",
      "emission" };
    for (int e = 0; e < vtkEffectPlan::NUMBER_OF_EFFECTS; ++e)
    {
      const std::string mode =
        String(effects, keys[e], "scene.effects", "auto", { "auto", "on", "off" });
      plan->SetEffectMode(e,
        mode == "on" ? vtkEffectPlan::FORCE_ON
                     : (mode == "off" ? vtkEffectPlan::FORCE_OFF : vtkEffectPlan::AUTOMATIC));
    }
    if (!multipleScattering)
    {
      plan->SetEffectMode(vtkEffectPlan::MULTIPLE_SCATTERING, vtkEffectPlan::FORCE_OFF);
    }
  }

  // --- medium ---
  Timer mediumTimer;
  if (!scene.contains("medium"))
  {
    Fail("scene.medium", "missing (give 'meshes' or 'volume')");
  }
  const json& medium = scene["medium"];
  CheckKeys(medium, "scene.medium", { "grid", "surrounding", "meshes", "volume" });
  vtkSmartPointer<vtkImageData> mediumImage;
  json mediumReport;
  if (medium.contains("meshes") == medium.contains("volume"))
  {
    Fail("scene.medium", "needs exactly one of 'meshes' or 'volume'");
  }
  if (medium.contains("meshes"))
  {
    const json& meshes = medium["meshes"];
    if (!meshes.is_array() || meshes.empty())
    {
      Fail("scene.medium.meshes", "must be a non-empty array of meshes");
    }
    vtkNew<vtkMeshVoxelizer> voxelizer;
    const json grid = medium.value("grid", json::object());
    CheckKeys(grid, "scene.medium.grid",
      { "dimensions", "bounds", "padding", "supersampling", "smoothing_window" });
    auto dims = Vector(grid, "dimensions", "scene.medium.grid", { 64, 64, 64 }, 3, 1, 2048);
    voxelizer->SetDimensions(
      static_cast<int>(dims[0]), static_cast<int>(dims[1]), static_cast<int>(dims[2]));
    if (grid.contains("bounds"))
    {
      auto b = Vector(grid, "bounds", "scene.medium.grid", {}, 6, -1e30, 1e30);
      for (int a = 0; a < 3; ++a)
      {
        if (!(b[2 * a] < b[2 * a + 1]))
        {
          Fail("scene.medium.grid.bounds", "every min must be below its max");
        }
      }
      voxelizer->SetBounds(b.data());
    }
    voxelizer->SetPadding(Number(grid, "padding", "scene.medium.grid", 0.0, 0.0, 1e30));
    voxelizer->SetSupersampling(Integer(grid, "supersampling", "scene.medium.grid", 4, 1, 16));
    voxelizer->SetSmoothingWindow(Integer(grid, "smoothing_window", "scene.medium.grid", 9, 1, 63));
    if (medium.contains("surrounding"))
    {
      voxelizer->SetSurroundingMaterial(
        ReadMaterial(medium["surrounding"], "scene.medium.surrounding"));
    }
    for (size_t i = 0; i < meshes.size(); ++i)
    {
      const std::string path = "scene.medium.meshes[" + std::to_string(i) + "]";
      CheckKeys(meshes[i], path, { "file", "sphere", "box", "material" });
      voxelizer->AddInputData(ReadMesh(meshes[i], path, base));
      voxelizer->SetMaterial(static_cast<int>(i),
        ReadMaterial(meshes[i].value("material", json::object()), path + ".material"));
    }
    voxelizer->Update();
    mediumImage = voxelizer->GetOutput();
    if (!mediumImage || mediumImage->GetNumberOfPoints() == 0)
    {
      throw std::runtime_error("voxelizing the meshes failed (see the error above)");
    }
    json stages = json::object();
    for (int s = 0; s < vtkMeshVoxelizer::NUMBER_OF_STAGES; ++s)
    {
      stages[vtkMeshVoxelizer::GetStageName(s)] = voxelizer->GetStageTime(s);
    }
    mediumReport["voxelizer_stage_seconds"] = stages;
    mediumReport["source"] = "meshes";
  }
  else
  {
    if (medium.contains("grid") || medium.contains("surrounding"))
    {
      Fail("scene.medium", "'grid' and 'surrounding' apply to meshes only, not to a volume");
    }
    const json& volume = medium["volume"];
    CheckKeys(volume, "scene.medium.volume", { "file", "array", "transfer_function" });
    if (!volume.contains("file") || !volume["file"].is_string())
    {
      Fail("scene.medium.volume.file", "missing (a .vti, .mha, .mhd, .nrrd or .nhdr file)");
    }
    auto input =
      ReadImageFile(Resolve(base, volume["file"].get<std::string>()), "scene.medium.volume.file");
    if (volume.contains("transfer_function"))
    {
      const json& tf = volume["transfer_function"];
      const std::string p = "scene.medium.volume.transfer_function";
      CheckKeys(tf, p,
        { "opacity", "color", "unit_distance", "refractive_index", "anisotropy",
          "emission_scale" });
      auto points = [&](const char* key, size_t width)
      {
        std::vector<std::vector<double>> out;
        if (!tf.contains(key))
        {
          return out;
        }
        if (!tf[key].is_array() || tf[key].empty())
        {
          Fail(p + "." + key, "must be a non-empty array of [scalar, value...] points");
        }
        for (size_t i = 0; i < tf[key].size(); ++i)
        {
          json wrapper = { { "point", tf[key][i] } };
          out.push_back(Vector(wrapper, "point", p + "." + key + "[" + std::to_string(i) + "]", {},
            width, -1e30, 1e30));
        }
        return out;
      };
      vtkNew<vtkPiecewiseFunction> opacity;
      auto op = points("opacity", 2);
      if (op.empty())
      {
        Fail(p + ".opacity", "missing ([[scalar, opacity], ...], opacity in [0, 1])");
      }
      for (auto& q : op)
      {
        if (q[1] < 0 || q[1] > 1)
        {
          Fail(p + ".opacity", "opacities must be in [0, 1]");
        }
        opacity->AddPoint(q[0], q[1]);
      }
      vtkNew<vtkColorTransferFunction> colour;
      auto cp = points("color", 4);
      if (cp.empty())
      {
        colour->AddRGBPoint(0, 1, 1, 1);
      }
      for (auto& q : cp)
      {
        colour->AddRGBPoint(q[0], q[1], q[2], q[3]);
      }
      vtkNew<vtkVolumeProperty> property;
      property->SetScalarOpacity(opacity);
      property->SetColor(colour);
      property->SetScalarOpacityUnitDistance(Number(tf, "unit_distance", p, 1.0, 1e-30, 1e30));
      vtkNew<vtkTransferFunctionMedium> mapping;
      mapping->SetInputData(input);
      if (volume.contains("array"))
      {
        const std::string name = String(volume, "array", "scene.medium.volume", "");
        if (!input->GetPointData()->GetArray(name.c_str()))
        {
          Fail("scene.medium.volume.array", "the file has no point array '" + name + "'");
        }
        mapping->SetInputArrayToProcess(
          0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, name.c_str());
      }
      mapping->SetVolumeProperty(property);
      auto ri = points("refractive_index", 2);
      vtkNew<vtkPiecewiseFunction> index;
      for (auto& q : ri)
      {
        if (q[1] < 1)
        {
          Fail(p + ".refractive_index", "indices must be >= 1");
        }
        index->AddPoint(q[0], q[1]);
      }
      if (!ri.empty())
      {
        mapping->SetRefractiveIndexFunction(index);
      }
      mapping->SetAnisotropy(Number(tf, "anisotropy", p, 0.0, -0.9999, 0.9999));
      mapping->SetEmissionScale(Number(tf, "emission_scale", p, 0.0, 0.0, 1e30));
      mapping->Update();
      mediumImage = mapping->GetOutput();
      if (!mediumImage || mediumImage->GetNumberOfPoints() == 0)
      {
        throw std::runtime_error("mapping the volume through its transfer functions failed");
      }
      mediumReport["source"] = "volume with transfer functions";
    }
    else
    {
      if (volume.contains("array"))
      {
        Fail("scene.medium.volume.array", "only used with a transfer_function");
      }
      vtkNew<vtkMediumValidator> validator;
      if (!validator->Validate(input))
      {
        Fail("scene.medium.volume.file",
          std::string("is not a Refracta medium and no transfer_function is given: ") +
            validator->GetErrorMessage());
      }
      mediumImage = input;
      mediumReport["source"] = "volume with Refracta arrays";
    }
  }
  int mediumDims[3];
  mediumImage->GetDimensions(mediumDims);
  mediumReport["dimensions"] = { mediumDims[0], mediumDims[1], mediumDims[2] };
  timings["medium"] = mediumTimer.Seconds();

  // --- lights ---
  int lightCount = 0;
  if (scene.contains("lights"))
  {
    const json& lights = scene["lights"];
    if (!lights.is_array())
    {
      Fail("scene.lights", "must be an array of lights");
    }
    for (size_t i = 0; i < lights.size(); ++i)
    {
      const std::string p = "scene.lights[" + std::to_string(i) + "]";
      const json& l = lights[i];
      CheckKeys(l, p,
        { "type", "position", "focal_point", "color", "intensity", "cone_angle", "exponent" });
      const std::string type = String(l, "type", p, "", { "directional", "point", "spot" });
      if (type.empty())
      {
        Fail(p + ".type", "missing (directional, point or spot)");
      }
      if (!l.contains("position"))
      {
        Fail(p + ".position", "missing");
      }
      vtkNew<vtkLight> light;
      light->SetLightTypeToSceneLight();
      auto pos = Vector(l, "position", p, {}, 3, -1e30, 1e30);
      auto fp = Vector(l, "focal_point", p, { 0, 0, 0 }, 3, -1e30, 1e30);
      if (pos == fp)
      {
        Fail(p + ".focal_point", "must differ from the position");
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
      renderer->AddLight(light);
      ++lightCount;
    }
  }

  // --- camera ---
  vtkNew<vtkCamera> camera;
  {
    const json cam = scene.value("camera", json::object());
    CheckKeys(cam, "scene.camera",
      { "position", "focal_point", "view_up", "view_angle", "projection", "parallel_scale" });
    double bounds[6];
    mediumImage->GetBounds(bounds);
    const double centre[3] = { 0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3]),
      0.5 * (bounds[4] + bounds[5]) };
    const double size =
      std::max({ bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4] });
    auto fp = Vector(
      cam, "focal_point", "scene.camera", { centre[0], centre[1], centre[2] }, 3, -1e30, 1e30);
    auto pos = Vector(cam, "position", "scene.camera",
      { centre[0], centre[1] + 0.3 * size, centre[2] + 2.2 * size }, 3, -1e30, 1e30);
    if (pos == fp)
    {
      Fail("scene.camera.position", "must differ from the focal point");
    }
    auto up = Vector(cam, "view_up", "scene.camera", { 0, 1, 0 }, 3, -1e30, 1e30);
    camera->SetFocalPoint(fp.data());
    camera->SetPosition(pos.data());
    camera->SetViewUp(up.data());
    camera->SetViewAngle(Number(cam, "view_angle", "scene.camera", 30.0, 0.1, 179.0));
    const std::string projection =
      String(cam, "projection", "scene.camera", "perspective", { "perspective", "parallel" });
    camera->SetParallelProjection(projection == "parallel");
    camera->SetParallelScale(
      Number(cam, "parallel_scale", "scene.camera", 0.6 * size, 1e-30, 1e30));
  }

  // --- background ---
  {
    const json bg = scene.value("background", json::object());
    CheckKeys(bg, "scene.background", { "color", "environment", "checker", "up", "right" });
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
      renderer->SetEnvironmentMap(ReadImageFile(
        Resolve(base, bg["environment"].get<std::string>()), "scene.background.environment"));
    }
    if (bg.contains("checker"))
    {
      const json& c = bg["checker"];
      const std::string p = "scene.background.checker";
      CheckKeys(c, p, { "squares", "color1", "color2" });
      auto squares = Vector(c, "squares", p, { 16, 8 }, 2, 1, 512);
      renderer->SetEnvironmentMap(Checker(static_cast<int>(squares[0]),
        static_cast<int>(squares[1]), Vector(c, "color1", p, { 0.9, 0.9, 0.9 }, 3, 0, 1e30),
        Vector(c, "color2", p, { 0.1, 0.1, 0.1 }, 3, 0, 1e30)));
    }
    auto up = Vector(bg, "up", "scene.background", { 0, 1, 0 }, 3, -1e30, 1e30);
    auto right = Vector(bg, "right", "scene.background", { 1, 0, 0 }, 3, -1e30, 1e30);
    renderer->SetEnvironmentUp(up[0], up[1], up[2]);
    renderer->SetEnvironmentRight(right[0], right[1], right[2]);
  }

  // --- the render pipeline: plan, light passes, view pass ---
  vtkPhotonTracer* tracer = pipeline->GetPhotonTracer();
  tracer->SetNumberOfPhotons(photons);
  tracer->SetSeed(static_cast<unsigned int>(seed));
  tracer->SetMinimumStep(photonMinStep);
  pipeline->SetOctreeTolerance(octreeTolerance);
  tracer->SetSmoothing(photonSmoothing);
  pipeline->GetLatticeSolver()->SetTolerance(lblTolerance);
  pipeline->GetLatticeSolver()->SetBlockSize(lblBlockSize);
  renderer->SetInputData(mediumImage);
  renderer->SetCamera(camera);
  renderer->SetImageSize(width, height);
  renderer->SetExposure(exposure);
  renderer->SetToneMapping(toneMapping == "clamp"
      ? vtkRefractaImageRenderer::CLAMP
      : (toneMapping == "reinhard" ? vtkRefractaImageRenderer::REINHARD
                                   : vtkRefractaImageRenderer::EXPONENTIAL));
  renderer->SetStepSize(viewStep);
  renderer->SetRayMode(rayMode == "auto"
      ? vtkRefractaViewPass::AUTO
      : (rayMode == "straight" ? vtkRefractaViewPass::STRAIGHT : vtkRefractaViewPass::CURVED));
  renderer->SetTransmittanceCutoff(cutoff);
  {
    StageReporter reporter(pipeline, options.Quiet);
    renderer->Update();
  }
  vtkImageData* result = renderer->GetOutput();
  if (!result || result->GetNumberOfPoints() == 0)
  {
    throw std::runtime_error("the render failed (see the error above)");
  }
  vtkImageData* lighting = pipeline->GetLighting();
  vtkSceneAnalysis* analysis = pipeline->GetSceneAnalysis();
  timings["plan"] = pipeline->GetStageSeconds(vtkRefractaRenderPipeline::PLAN);
  timings["light_pass"] = pipeline->GetStageSeconds(vtkRefractaRenderPipeline::LIGHTING);
  timings["view_pass"] = pipeline->GetStageSeconds(vtkRefractaRenderPipeline::VIEW);
  timings["view_pass_device"] = renderer->GetViewPass()->GetLastSeconds();
  json planReport;
  planReport["summary"] = plan->GetSummary();
  planReport["analysis"] = analysis->GetSummary();
  planReport["tolerance"] = plan->GetTolerance();
  for (int e = 0; e < vtkEffectPlan::NUMBER_OF_EFFECTS; ++e)
  {
    planReport["effects"][vtkEffectPlan::GetEffectName(e)] = { { "enabled", plan->IsEnabled(e) },
      { "estimated_change", plan->GetEstimatedContribution(e) }, { "reason", plan->GetReason(e) } };
  }
  report["plan"] = planReport;
  json lightReport;
  if (lighting)
  {
    lightReport = FieldDataToJson(lighting->GetFieldData());
    lightReport["octree_seconds"] = tracer->GetOctreeSeconds();
    lightReport["generation_seconds"] = tracer->GetGenerationSeconds();
    lightReport["marching_seconds"] = tracer->GetMarchingSeconds();
    lightReport["smoothing_seconds"] = tracer->GetSmoothingSeconds();
    lightReport["curved_rays"] = tracer->GetUsedCurvedRays();
    lightReport["octree"] = tracer->GetUsedOctree();
    lightReport["photon_seconds"] = timings["light_pass"];
    if (plan->IsEnabled(vtkEffectPlan::MULTIPLE_SCATTERING))
    {
      lightReport["multiple_scattering"] = {
        { "iterations", lightReport.value("LatticeBoltzmannIterations", 0.0) },
        { "residual", lightReport.value("LatticeBoltzmannResidual", 0.0) },
        { "converged", lightReport.value("LatticeBoltzmannConverged", 0.0) != 0.0 },
        { "schedule", pipeline->GetLastScheduleInterleaved() ? "interleaved" : "sequential" },
        { "seconds", lightReport.value("ScheduleFinalSolveSeconds", 0.0) }
      };
    }
    else
    {
      lightReport["multiple_scattering"] =
        std::string("off (") + plan->GetReason(vtkEffectPlan::MULTIPLE_SCATTERING) + ")";
    }
  }
  else
  {
    lightReport["skipped"] = lightCount == 0
      ? std::string("no lights")
      : std::string("single scattering ") + plan->GetReason(vtkEffectPlan::SINGLE_SCATTERING);
  }

  // --- outputs ---
  Timer writeTimer;
  {
    vtkNew<vtkImageData> rgb;
    rgb->CopyStructure(result);
    rgb->GetPointData()->SetScalars(result->GetPointData()->GetScalars());
    vtkNew<vtkPNGWriter> writer;
    writer->SetInputData(rgb);
    writer->SetFileName(options.Output.c_str());
    writer->Write();
    if (writer->GetErrorCode() != 0)
    {
      throw std::runtime_error("cannot write '" + options.Output + "'");
    }
  }
  auto writeVti = [](vtkImageData* data, const std::string& file)
  {
    vtkNew<vtkXMLImageDataWriter> writer;
    writer->SetInputData(data);
    writer->SetFileName(file.c_str());
    if (writer->Write() != 1)
    {
      throw std::runtime_error("cannot write '" + file + "'");
    }
  };
  if (!options.Hdr.empty())
  {
    writeVti(result, options.Hdr);
  }
  if (!options.Radiance.empty())
  {
    vtkNew<vtkImageData> volume;
    volume->DeepCopy(mediumImage);
    if (lighting)
    {
      for (int i = 0; i < lighting->GetPointData()->GetNumberOfArrays(); ++i)
      {
        volume->GetPointData()->AddArray(lighting->GetPointData()->GetArray(i));
      }
    }
    writeVti(volume, options.Radiance);
  }
  timings["write"] = writeTimer.Seconds();
  timings["total"] = total.Seconds();

  // --- report ---
  vtkOpenCLContext* context = vtkOpenCLContext::GetDefault();
  report["device"] =
    std::string(context->GetDeviceName()) + " (" + context->GetPlatformName() + ")";
  report["output"] = options.Output;
  report["image"] = { { "width", width }, { "height", height }, { "exposure", exposure },
    { "tone_mapping", toneMapping } };
  report["quality"] = { { "photons", photons }, { "seed", seed }, { "view_step", viewStep },
    { "ray_mode", rayMode }, { "transmittance_cutoff", cutoff },
    { "photon_min_step", photonMinStep }, { "photon_smoothing", photonSmoothing },
    { "multiple_scattering", multipleScattering },
    { "multiple_scattering_tolerance", lblTolerance },
    { "multiple_scattering_block_size", lblBlockSize }, { "preset", preset },
    { "octree_tolerance", octreeTolerance } };
  report["medium"] = mediumReport;
  report["light_pass"] = lightReport;
  report["view_pass"] = { { "curved_rays", renderer->GetViewPass()->GetLastCurved() },
    { "total_steps", renderer->GetViewPass()->GetLastTotalSteps() },
    { "steps_per_pixel", renderer->GetViewPass()->GetLastTotalSteps() / (double(width) * height) },
    { "empty_space_skipping", renderer->GetViewPass()->GetLastSkipping() },
    { "active_cell_fraction", renderer->GetViewPass()->GetLastActiveCellFraction() } };
  report["seconds"] = timings;
  report["scene"] = scene;

  std::cout << "refracta-render: " << width << " x " << height << " -> " << options.Output << " on "
            << report["device"].get<std::string>() << "\n";
  std::cout << "  plan      " << plan->GetSummary() << "\n";
  std::cout << "  quality   preset " << preset << ": " << photons << " photons, photon min step "
            << photonMinStep << ", octree eps " << octreeTolerance << ", lattice tolerance "
            << lblTolerance << ", lattice block " << lblBlockSize << ", view step " << viewStep
            << "\n";
  std::cout << "  medium    " << mediumDims[0] << " x " << mediumDims[1] << " x " << mediumDims[2]
            << " (" << mediumReport["source"].get<std::string>() << "), "
            << timings["medium"].get<double>() << " s\n";
  if (lighting)
  {
    auto e = lightReport.value("EnergyEmitted", json::array());
    auto s = lightReport.value("EnergyScattered", json::array());
    auto a = lightReport.value("EnergyAbsorbed", json::array());
    auto x = lightReport.value("EnergyEscaped", json::array());
    auto r = lightReport.value("EnergyRemaining", json::array());
    std::cout << "  light     " << lightReport.value("NumberOfPhotons", 0.0) << " photons, "
              << lightReport.value("TotalSteps", 0.0) << " steps, "
              << lightReport.value("photon_seconds", 0.0) << " s\n";
    if (lightReport["multiple_scattering"].is_object())
    {
      const json& ms = lightReport["multiple_scattering"];
      std::cout << "  multiple  Lattice-Boltzmann " << ms["iterations"].get<double>()
                << " iterations, residual " << ms["residual"].get<double>()
                << (ms["converged"].get<bool>() ? " (converged), " : " (NOT converged), ")
                << ms["seconds"].get<double>() << " s\n";
    }
    if (e.size() == 3 && s.size() == 3 && a.size() == 3 && x.size() == 3 && r.size() == 3)
    {
      const double em = e[0].get<double>() + e[1].get<double>() + e[2].get<double>();
      const double out = s[0].get<double>() + s[1].get<double>() + s[2].get<double>() +
        a[0].get<double>() + a[1].get<double>() + a[2].get<double>() + x[0].get<double>() +
        x[1].get<double>() + x[2].get<double>() + r[0].get<double>() + r[1].get<double>() +
        r[2].get<double>();
      std::cout << "  energy    emitted " << em << " = scattered+absorbed+escaped+remaining " << out
                << " (relative difference " << (em > 0 ? (out - em) / em : 0.0) << ")\n";
    }
  }
  else
  {
    std::cout << "  light     skipped: " << lightReport["skipped"].get<std::string>() << "\n";
  }
  std::cout << "  view      " << (renderer->GetViewPass()->GetLastCurved() ? "curved" : "straight")
            << " rays, " << renderer->GetViewPass()->GetLastTotalSteps() << " steps, "
            << (renderer->GetViewPass()->GetLastSkipping()
                   ? "empty-space skipping (" +
                     std::to_string(100.0 * renderer->GetViewPass()->GetLastActiveCellFraction()) +
                     "% of macro cells active), "
                   : std::string("no empty space skipped, "))
            << timings["view_pass"].get<double>() << " s\n";
  std::cout << "  total     " << timings["total"].get<double>() << " s\n";
  if (!options.Report.empty())
  {
    std::ofstream out(options.Report);
    out << report.dump(2) << "\n";
    if (!out)
    {
      throw std::runtime_error("cannot write '" + options.Report + "'");
    }
  }
  return 0;
}

// ---------------------------------------------------------------------------------------------
// The device check of earlier versions (kept as --device-check).
bool DeviceCheck()
{
  vtkOpenCLContext* context = vtkOpenCLContext::GetDefault();
  if (!context->Initialize())
  {
    std::cerr << "refracta-render: " << context->GetLastErrorMessage() << "\n";
    return false;
  }
  std::cout << "Refracta device: " << context->GetDeviceName() << " (" << context->GetPlatformName()
            << ", " << context->GetDeviceVersion() << ")\n";
  const double scale = vtkOpenCLContext::ChooseFixedPointScale(1u << 20);
  cl_program program = context->GetProgram({ "refracta_atomics.cl", "selftest.cl" },
    "-DREFRACTA_FIXED_SCALE=" + std::to_string(scale) + "f");
  if (!program)
  {
    return false;
  }
  const unsigned int n = 1u << 20;
  std::vector<float> values(n);
  std::int64_t expected = 0;
  for (unsigned int i = 0; i < n; ++i)
  {
    values[i] = static_cast<float>((i * 2654435761u) % 1000u) / 1000.0f;
    expected += std::llrint(static_cast<double>(values[i]) * scale);
  }
  vtkOpenCLKernel kernel = context->CreateKernel(program, "refracta_atomic_fixed_contention");
  vtkOpenCLBuffer in =
    context->CreateBuffer(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, n * 4, values.data(), "values");
  vtkOpenCLBuffer sum = context->CreateBuffer(CL_MEM_READ_WRITE, 8, nullptr, "sum");
  const unsigned int targets = 1;
  const size_t global = n;
  std::int64_t result = 0;
  if (!kernel || !in || !sum || !context->ZeroBuffer(sum.Get(), 8) ||
    vtkOpenCLSetKernelArgs(kernel.Get(), in.Get(), sum.Get(), targets) != CL_SUCCESS ||
    !context->RunKernel(kernel.Get(), 1, &global, nullptr, "accumulate") ||
    !context->ReadBuffer(sum.Get(), 8, &result) || result != expected)
  {
    std::cerr << "refracta-render: device check FAILED\n";
    return false;
  }
  std::cout << "device check passed\n";
  return true;
}

void PrintUsage(std::ostream& os)
{
  os << "usage: refracta-render [--scene FILE.json] [--output FILE.png] [--hdr FILE.vti]\n"
        "                       [--radiance FILE.vti] [--report FILE.json] [--preview] [--quiet]\n"
        "       refracta-render --print-default-scene | --list-devices | --device-check | --help\n"
        "  Without --scene, renders the embedded default scene (a glass sphere in fog over a\n"
        "  scattering floor, lit by a spot light) to refracta.png. The scene format is documented\n"
        "  in the README. --preview: half the image size and grid resolution, a quarter of the\n"
        "  photons. Each stage is printed as it starts and ends, with a progress bar on a "
        "terminal;\n"
        "  --quiet prints the final report only. The OpenCL device is chosen by\n"
        "  REFRACTA_OPENCL_DEVICE.\n";
}
}

int main(int argc, char* argv[])
{
  Options options;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    auto value = [&](std::string& target)
    {
      if (i + 1 >= argc)
      {
        std::cerr << "refracta-render: option '" << arg << "' needs a value\n";
        std::exit(2);
      }
      target = argv[++i];
    };
    if (arg == "--help" || arg == "-h")
    {
      PrintUsage(std::cout);
      return 0;
    }
    else if (arg == "--list-devices")
    {
      std::cout << vtkOpenCLContext::ListDevices();
      return 0;
    }
    else if (arg == "--device-check")
    {
      return DeviceCheck() ? 0 : 1;
    }
    else if (arg == "--print-default-scene")
    {
      std::cout << DefaultScene << "\n";
      return 0;
    }
    else if (arg == "--preview")
    {
      options.Preview = true;
    }
    else if (arg == "--quiet" || arg == "-q")
    {
      options.Quiet = true;
    }
    else if (arg == "--scene")
    {
      value(options.Scene);
    }
    else if (arg == "--output" || arg == "-o")
    {
      value(options.Output);
    }
    else if (arg == "--hdr")
    {
      value(options.Hdr);
    }
    else if (arg == "--radiance")
    {
      value(options.Radiance);
    }
    else if (arg == "--report")
    {
      value(options.Report);
    }
    else
    {
      std::cerr << "refracta-render: unknown option '" << arg << "'\n";
      PrintUsage(std::cerr);
      return 2;
    }
  }

  json scene;
  std::string base;
  const std::string source = options.Scene.empty() ? "the default scene" : options.Scene;
  try
  {
    if (options.Scene.empty())
    {
      scene = json::parse(DefaultScene);
    }
    else
    {
      std::ifstream in(options.Scene);
      if (!in)
      {
        std::cerr << "refracta-render: cannot read scene file '" << options.Scene << "'\n";
        return 1;
      }
      scene = json::parse(in);
      const size_t slash = options.Scene.find_last_of('/');
      base = slash == std::string::npos ? "." : options.Scene.substr(0, slash);
    }
  }
  catch (const json::parse_error& e)
  {
    std::cerr << "refracta-render: " << source << " is not valid JSON: " << e.what() << "\n";
    return 1;
  }
  if (options.Preview)
  {
    MakePreview(scene);
  }
  vtkOpenCLContext* context = vtkOpenCLContext::GetDefault();
  if (!context->Initialize())
  {
    std::cerr << "refracta-render: " << context->GetLastErrorMessage() << "\n";
    return 1;
  }
  try
  {
    return Render(scene, base, options);
  }
  catch (const SceneError& e)
  {
    std::cerr << "refracta-render: bad scene (" << source << "): " << e.what() << "\n";
    return 1;
  }
  catch (const std::exception& e)
  {
    std::cerr << "refracta-render: rendering " << source << " failed: " << e.what() << "\n";
    return 1;
  }
}
