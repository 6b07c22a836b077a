#include "RefractaRenderOutputs.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkPointData.h"
#include "vtkXMLImageDataWriter.h"

#include <fstream>
#include <stdexcept>

#include <sys/stat.h>
#include <unistd.h>

namespace RefractaRender
{
void WritePng(vtkImageData* image, const std::string& file)
{
  vtkNew<vtkImageData> rgb;
  rgb->CopyStructure(image);
  rgb->GetPointData()->SetScalars(image->GetPointData()->GetScalars());
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputData(rgb);
  writer->SetFileName(file.c_str());
  writer->Write();
  if (writer->GetErrorCode() != 0)
  {
    throw std::runtime_error("cannot write '" + file + "'");
  }
}

void WriteVti(vtkImageData* data, const std::string& file)
{
  vtkNew<vtkXMLImageDataWriter> writer;
  writer->SetInputData(data);
  writer->SetFileName(file.c_str());
  // Write() returns 1 also when the file could not be opened; the error code says it.
  if (writer->Write() != 1 || writer->GetErrorCode() != 0)
  {
    throw std::runtime_error("cannot write '" + file + "'");
  }
}

void WriteRadianceVolume(vtkImageData* medium, vtkImageData* lighting, const std::string& file)
{
  vtkNew<vtkImageData> volume;
  volume->DeepCopy(medium);
  if (lighting)
  {
    for (int i = 0; i < lighting->GetPointData()->GetNumberOfArrays(); ++i)
    {
      volume->GetPointData()->AddArray(lighting->GetPointData()->GetArray(i));
    }
  }
  WriteVti(volume, file);
}

void WriteReport(const json& report, const std::string& file)
{
  std::ofstream out(file);
  out << report.dump(2) << "\n";
  if (!out)
  {
    throw std::runtime_error("cannot write '" + file + "'");
  }
}

void CheckOutputFolders(const std::vector<std::string>& files)
{
  for (const std::string& file : files)
  {
    if (file.empty())
    {
      continue;
    }
    const size_t slash = file.find_last_of('/');
    const std::string folder =
      slash == std::string::npos ? "." : (slash == 0 ? "/" : file.substr(0, slash));
    struct stat info;
    if (stat(folder.c_str(), &info) != 0 || !S_ISDIR(info.st_mode))
    {
      throw std::runtime_error(
        "cannot write '" + file + "': the folder '" + folder + "' does not exist");
    }
    if (access(folder.c_str(), W_OK) != 0)
    {
      throw std::runtime_error(
        "cannot write '" + file + "': the folder '" + folder + "' is not writable");
    }
  }
}
}
