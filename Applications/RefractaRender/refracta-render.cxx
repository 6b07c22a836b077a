// refracta-render: Refracta's command-line renderer.
//
//   refracta-render                          render the embedded default scene to refracta.png
//   refracta-render --scene FILE.json        render a scene described in JSON (SceneFile.md)
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
//
// The scene is read by RefractaSceneJson (strict JSON access), RefractaSceneSettings (image,
// quality, effects), RefractaSceneMedium (the medium) and RefractaSceneView (lights, camera,
// background); RefractaRenderReport reports the render and RefractaRenderOutputs writes it.
#include "RefractaDeviceCheck.h"
#include "RefractaRenderOutputs.h"
#include "RefractaRenderReport.h"
#include "RefractaScene.h"
#include "RefractaSceneJson.h"
#include "RefractaSceneMedium.h"
#include "RefractaSceneSettings.h"
#include "RefractaSceneSurfaces.h"

#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkOpenCLContext.h"
#include "vtkRefractaImageRenderer.h"
#include "vtkRefractaRenderPipeline.h"
#include "vtkRefractaSurfaceSet.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <new>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

using namespace RefractaRender;

namespace
{
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
    // A quarter of what the block asks for, its preset's photons included.
    quality["photons"] = std::max(4096, RequestedPhotons(quality) / 4);
  }
  if (scene.contains("medium") && scene["medium"].is_object() && scene["medium"].contains("grid") &&
    scene["medium"]["grid"].is_object() && scene["medium"]["grid"].contains("dimensions") &&
    scene["medium"]["grid"]["dimensions"].is_array())
  {
    for (auto& d : scene["medium"]["grid"]["dimensions"])
    {
      // 64 and 64.0 alike (the scene reader takes both as integers).
      if (IsInteger(d) && std::abs(d.get<double>()) < 1e9)
      {
        d = std::max(8, static_cast<int>(d.get<double>()) / 2);
      }
    }
  }
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
  bool ProfileKernels = false;
};

// Renders a scene; throws SceneError for bad scenes, std::runtime_error for failed stages.
int Render(const json& scene, const std::string& base, const Options& options)
{
  CheckOutputs(
    { { "--output", options.Output, ".png" }, { "--hdr", options.Hdr, ".vti" },
      { "--radiance", options.Radiance, ".vti" }, { "--report", options.Report, ".json" } },
    options.Scene);
  Timer total;
  json seconds = json::object();
  // One render pipeline does the work (vtkRefractaRenderPipeline, through the image renderer
  // that tone-maps its image); the scene configures both.
  vtkNew<vtkRefractaImageRenderer> renderer;
  vtkRefractaRenderPipeline* pipeline = renderer->GetPipeline();
  const Scene read = ReadScene(scene, base, renderer, options.Quiet);
  const RenderSettings& settings = read.Settings;
  const SceneMedium& medium = read.Medium;
  const int lightCount = read.LightCount;
  seconds["surfaces"] = read.SurfacesSeconds;
  seconds["medium"] = read.MediumSeconds;

  // The render: plan, light passes, view pass, each stage printed as it runs.
  {
    StageReporter reporter(pipeline, options.Quiet);
    renderer->Update();
  }
  vtkImageData* result = renderer->GetOutput();
  if (!result || result->GetNumberOfPoints() == 0)
  {
    throw std::runtime_error("the render failed (see the error above)");
  }
  AddStageSeconds(renderer, seconds);

  // The outputs. A failed write (a full disk) removes what this render wrote: no truncated
  // file and no partial set of results is left.
  Timer writeTimer;
  std::vector<std::string> written;
  auto write = [&written](const std::string& file, const std::function<void()>& writer)
  {
    written.push_back(file);
    try
    {
      writer();
    }
    catch (...)
    {
      RemoveOutputs(written);
      throw;
    }
  };
  write(options.Output, [&] { WritePng(result, options.Output); });
  if (!options.Hdr.empty())
  {
    write(options.Hdr, [&] { WriteVti(result, options.Hdr); });
  }
  if (!options.Radiance.empty())
  {
    write(options.Radiance,
      [&] { WriteRadianceVolume(medium.Image, pipeline->GetLighting(), options.Radiance); });
  }
  seconds["write"] = writeTimer.Seconds();
  seconds["total"] = total.Seconds();

  // The report: printed in short, written in full with --report.
  vtkOpenCLContext* context = vtkOpenCLContext::GetDefault();
  json report;
  report["plan"] = PlanReport(pipeline);
  report["device"] =
    std::string(context->GetDeviceName()) + " (" + context->GetPlatformName() + ")";
  report["output"] = options.Output;
  report["image"] = ImageReport(settings);
  report["quality"] = QualityReport(settings);
  report["medium"] = medium.Report;
  report["surfaces"] = SurfacesReport(read.Surfaces, pipeline->GetSceneSurfaces());
  report["light_pass"] = LightPassReport(pipeline, lightCount);
  report["view_pass"] = ViewPassReport(renderer);
  report["seconds"] = seconds;
  if (context->GetProfileKernels())
  {
    report["kernels"] = KernelProfileReport(context);
  }
  report["scene"] = scene;
  PrintSummary(report);
  if (!options.Report.empty())
  {
    write(options.Report, [&] { WriteReport(report, options.Report); });
  }
  return 0;
}

void PrintUsage(std::ostream& os)
{
  os << "usage: refracta-render [--scene FILE.json] [--output FILE.png] [--hdr FILE.vti]\n"
        "                       [--radiance FILE.vti] [--report FILE.json] [--preview] [--quiet]\n"
        "                       [--profile-kernels]\n"
        "       refracta-render --print-default-scene | --list-devices | --device-check | --help\n"
        "  Without --scene, renders the embedded default scene (a glass sphere in fog over a\n"
        "  checkered floor, lit by a spot light) to refracta.png. The scene format is documented\n"
        "  in Documentation/SceneFile.md. --preview: half the image size and grid resolution, a\n"
        "  quarter of the photons (of the preset's, with a quality preset). Each stage is\n"
        "  printed as it starts and ends, with a progress bar on a terminal;\n"
        "  --quiet prints the final report only. --profile-kernels adds each OpenCL kernel's\n"
        "  launches and device time to the report (also REFRACTA_PROFILE_KERNELS=1).\n"
        "  The OpenCL device is chosen by\n"
        "  REFRACTA_OPENCL_DEVICE.\n";
}

// Reads the command line into `options`; returns -1 to go on and render, otherwise the exit
// status (after --help, --list-devices, --device-check, --print-default-scene or a bad option).
int ParseOptions(int argc, char* argv[], Options& options)
{
  const std::map<std::string, std::string Options::*> values = { { "--scene", &Options::Scene },
    { "--output", &Options::Output }, { "-o", &Options::Output }, { "--hdr", &Options::Hdr },
    { "--radiance", &Options::Radiance }, { "--report", &Options::Report } };
  const std::map<std::string, bool Options::*> flags = { { "--preview", &Options::Preview },
    { "--quiet", &Options::Quiet }, { "-q", &Options::Quiet },
    { "--profile-kernels", &Options::ProfileKernels } };
  std::vector<std::string Options::*> given; // member pointers have == but no order
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
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
      std::cout << DefaultSceneJson << "\n";
      return 0;
    }
    else if (flags.count(arg))
    {
      options.*flags.at(arg) = true;
    }
    else if (values.count(arg))
    {
      // "--output --quiet" wrote an image named --quiet; "--scene a --scene b" rendered b.
      const std::string value = i + 1 < argc ? argv[i + 1] : "";
      const bool isOption =
        values.count(value) || flags.count(value) || value.rfind("--", 0) == 0 || value == "-h";
      if (value.empty() || isOption)
      {
        std::cerr << "refracta-render: option '" << arg << "' needs a value"
                  << (value.empty() ? std::string() : ", got the option '" + value + "'") << "\n";
        return 2;
      }
      if (std::find(given.begin(), given.end(), values.at(arg)) != given.end())
      {
        std::cerr << "refracta-render: option '" << arg << "' is given twice\n";
        return 2;
      }
      given.push_back(values.at(arg));
      options.*values.at(arg) = value;
      ++i;
    }
    else
    {
      std::cerr << "refracta-render: unknown option '" << arg << "'\n";
      PrintUsage(std::cerr);
      return 2;
    }
  }
  return -1;
}

struct SceneShapeError : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

// The deepest nesting a scene file may have (a scene needs 5 levels): deeper JSON is refused
// while it is read, before it costs seconds and gigabytes (a 50 MB file of nested arrays took
// 7.7 s and 1.9 GB to be refused afterwards).
constexpr int MaximumSceneDepth = 64;

// JSON with every object's keys distinct (nlohmann keeps the last of two equal keys, which would
// drop the first block of a scene without a word) and at most MaximumSceneDepth deep. Throws
// SceneShapeError saying which.
json ParseSceneJson(std::istream& in)
{
  std::vector<std::set<std::string>> keys; // one set per open object
  return json::parse(in,
    [&keys](int depth, json::parse_event_t event, json& parsed)
    {
      if (depth > MaximumSceneDepth)
      {
        throw SceneShapeError(
          "it nests deeper than " + std::to_string(MaximumSceneDepth) + " levels");
      }
      if (event == json::parse_event_t::object_start)
      {
        keys.emplace_back();
      }
      else if (event == json::parse_event_t::object_end && !keys.empty())
      {
        keys.pop_back();
      }
      else if (event == json::parse_event_t::key && !keys.empty() &&
        !keys.back().insert(parsed.get<std::string>()).second)
      {
        throw SceneShapeError(
          "the key '" + parsed.get<std::string>() + "' appears twice in one object");
      }
      return true;
    });
}

// Reads the scene (the default one without --scene) and the folder its file names are relative
// to; false, with the reason printed, where it cannot.
bool LoadScene(const Options& options, json& scene, std::string& base)
{
  try
  {
    if (options.Scene.empty())
    {
      scene = json::parse(DefaultSceneJson);
      return true;
    }
    std::ifstream in(options.Scene);
    if (!in)
    {
      std::cerr << "refracta-render: cannot read scene file '" << options.Scene << "'\n";
      return false;
    }
    scene = ParseSceneJson(in);
    const size_t slash = options.Scene.find_last_of('/');
    base = slash == std::string::npos ? "." : options.Scene.substr(0, slash);
    return true;
  }
  catch (const json::exception& e)
  {
    // parse_error, and out_of_range for a number beyond a double (1e999).
    const std::string source = options.Scene.empty() ? "the default scene" : options.Scene;
    std::cerr << "refracta-render: " << source << " is not valid JSON: " << e.what() << "\n";
    return false;
  }
  catch (const SceneShapeError& e)
  {
    std::cerr << "refracta-render: " << options.Scene << " is not a valid scene: " << e.what()
              << "\n";
    return false;
  }
  catch (const std::exception& e)
  {
    // The stream's own failures (a folder named as the scene: "Is a directory").
    std::cerr << "refracta-render: cannot read scene file '" << options.Scene << "': " << e.what()
              << "\n";
    return false;
  }
}
}

int main(int argc, char* argv[])
{
  Options options;
  const int status = ParseOptions(argc, argv, options);
  if (status >= 0)
  {
    return status;
  }
  json scene;
  std::string base;
  if (!LoadScene(options, scene, base))
  {
    return 1;
  }
  if (options.Preview)
  {
    MakePreview(scene);
  }
  vtkOpenCLContext* context = vtkOpenCLContext::GetDefault();
  if (options.ProfileKernels)
  {
    context->ProfileKernelsOn();
  }
  if (!context->Initialize())
  {
    std::cerr << "refracta-render: " << context->GetLastErrorMessage() << "\n";
    return 1;
  }
  const std::string source = options.Scene.empty() ? "the default scene" : options.Scene;
  try
  {
    return Render(scene, base, options);
  }
  catch (const SceneError& e)
  {
    std::cerr << "refracta-render: bad scene (" << source << "): " << e.what() << "\n";
    return 1;
  }
  catch (const std::bad_alloc&)
  {
    std::cerr << "refracta-render: rendering " << source
              << " failed: out of memory. Lower what sizes the render: image.width and "
                 "image.height, medium.grid.dimensions, quality.photons.\n";
    return 1;
  }
  catch (const std::exception& e)
  {
    std::cerr << "refracta-render: rendering " << source << " failed: " << e.what() << "\n";
    return 1;
  }
}
