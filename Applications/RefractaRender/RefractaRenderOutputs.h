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

/// Throws, naming the file, when the folder of one of `files` (empty names skipped) does not
/// exist or cannot be written: checked before the render, which it would otherwise waste (and
/// VTK's writers would say "Ran out of disk space" first).
void CheckOutputFolders(const std::vector<std::string>& files);
}

#endif
