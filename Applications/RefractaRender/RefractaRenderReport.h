// What refracta-render tells about a render: the stages as they run (StageReporter), the JSON
// report (plan, light pass, view pass, seconds) and the summary printed from it at the end.
#ifndef RefractaRenderReport_h
#define RefractaRenderReport_h

#include "RefractaSceneJson.h"

#include "vtkCallbackCommand.h"
#include "vtkNew.h"

#include <chrono>
#include <string>
#include <vector>

class vtkFieldData;
class vtkOpenCLContext;
class vtkRefractaImageRenderer;
class vtkRefractaRenderPipeline;

namespace RefractaRender
{
/// Wall-clock seconds since construction.
struct Timer
{
  std::chrono::steady_clock::time_point Start = std::chrono::steady_clock::now();
  double Seconds() const
  {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - this->Start).count();
  }
};

/// While it lives, prints each stage of the render pipeline as it starts and ends (with its
/// seconds) and, on a terminal, a progress bar; silent with `quiet`.
class StageReporter
{
public:
  StageReporter(vtkRefractaRenderPipeline* pipeline, bool quiet);
  ~StageReporter();
  StageReporter(const StageReporter&) = delete;
  StageReporter& operator=(const StageReporter&) = delete;

private:
  static void OnEvent(vtkObject*, unsigned long event, void* client, void* call);
  void Line(const std::string& text);
  void Bar(double fraction);

  vtkRefractaRenderPipeline* Pipeline;
  bool Terminal;
  int Drawn = -1;
  Timer Stage;
  vtkNew<vtkCallbackCommand> Command;
  std::vector<unsigned long> Tags;
};

/// The first tuple of each named array of `fd`: a number, or an array of its components.
json FieldDataToJson(vtkFieldData* fd);

/// Adds the seconds of the pipeline's stages ("plan", "light_pass", "view_pass",
/// "view_pass_device") to `seconds`.
void AddStageSeconds(vtkRefractaImageRenderer* renderer, json& seconds);

/// The report's "plan": summary, scene analysis, tolerance and each effect's decision.
json PlanReport(vtkRefractaRenderPipeline* pipeline);

/// The report's "light_pass": the lighting's field data (counts, energy balance), the tracer's
/// seconds and the multiple-scattering solve, or why the pass was skipped.
json LightPassReport(vtkRefractaRenderPipeline* pipeline, int lightCount);

/// The report's "view_pass": rays, steps and empty-space skipping.
json ViewPassReport(vtkRefractaImageRenderer* renderer);

/// The report's "kernels" (with --profile-kernels): per kernel label, the launches and device
/// seconds from the context's OpenCL profiling events, longest first.
json KernelProfileReport(vtkOpenCLContext* context);

/// Prints the short summary of a finished render from its report (and the kernel table when the
/// report has one).
void PrintSummary(const json& report);
}

#endif
