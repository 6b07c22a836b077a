// Private to the ParaView adapters: the one check of an input's data type that every adapter
// taking a vtkImageData makes, so that a wrong type is reported once, in the adapter's words.
// (VTK's own check, from FillInputPortInformation, runs in every pipeline pass and so repeats
// its message three times per update in ParaView.)
#ifndef vtkRefractaPluginInputCheck_h
#define vtkRefractaPluginInputCheck_h

#include "vtkDataObject.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <string>

namespace refracta_plugin
{
/**
 * Empty when input `port` connection 0 holds a vtkImageData (or nothing yet); else a message
 * naming the type found and what would be valid.
 */
inline std::string CheckImageInput(
  vtkInformationVector** inputVector, int port, const char* filterLabel, const char* valid)
{
  vtkInformation* info = inputVector[port]->GetInformationObject(0);
  vtkDataObject* data = info ? info->Get(vtkDataObject::DATA_OBJECT()) : nullptr;
  if (!data || vtkImageData::SafeDownCast(data))
  {
    return std::string();
  }
  return std::string("The input of ") + filterLabel + " is a " + data->GetClassName() +
    "; it needs " + valid + ".";
}

/**
 * After a wrong input type was reported: an empty whole extent on output 0, so the pipeline
 * goes on quietly to an empty output (returning 0 would add the executive's own messages).
 */
inline int EmptyInformation(vtkInformationVector* outputVector)
{
  static const int empty[6] = { 0, -1, 0, -1, 0, -1 };
  outputVector->GetInformationObject(0)->Set(
    vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), empty, 6);
  return 1;
}

/**
 * RequestUpdateExtent of a filter that works on its input's whole grid: asks input `port` for
 * its whole extent (nothing for a wrong type, which has none). Returns 1.
 */
inline int RequestWholeExtent(vtkInformationVector** inputVector, int port)
{
  vtkInformation* inInfo = inputVector[port]->GetInformationObject(0);
  if (inInfo && inInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(),
      inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()), 6);
  }
  return 1;
}
}

#endif
