// The files refracta-render writes: the tone-mapped PNG, the HDR image and the medium with its
// lighting (.vti), and the JSON report. Each throws std::runtime_error naming a file it cannot
// write.
#ifndef RefractaRenderOutputs_h
#define RefractaRenderOutputs_h

#include "RefractaSceneJson.h"

#include <string>
#include <vector>

class vtkImageData;

namespace RefractaRender
{
/// Writes the 8-bit RGB scalars of the rendered image as a PNG.
void WritePng(vtkImageData* image, const std::string& file);

/// Writes an image (the HDR render, a volume) as VTK XML image data.
void WriteVti(vtkImageData* data, const std::string& file);

/// Writes the medium with the arrays of the lighting (where there is one) added.
void WriteRadianceVolume(vtkImageData* medium, vtkImageData* lighting, const std::string& file);

/// Writes the report as indented JSON.
void WriteReport(const json& report, const std::string& file);

/// One output file of a render: the option that names it, the file (empty: not asked for) and
/// the suffix its format needs (".png", ".vti", ".json").
struct OutputFile
{
  std::string Option;
  std::string File;
  std::string Suffix;
};

/// Throws, naming the option and the file, when an output cannot or must not be written: its
/// name lacks its format's suffix (a PNG named .jpg), its folder does not exist or cannot be
/// written, it is a folder or another non-regular file (/dev/full), it is the scene file
/// `sceneFile`, or two outputs name the same file. Checked before the render, which it would
/// otherwise waste (and VTK's writers would say "Ran out of disk space" first).
void CheckOutputs(const std::vector<OutputFile>& outputs, const std::string& sceneFile);

/// Deletes the files named in `written` (after an output failed: no partial
/// set of results, and no truncated file, is left behind).
void RemoveOutputs(const std::vector<std::string>& written);
}

#endif
