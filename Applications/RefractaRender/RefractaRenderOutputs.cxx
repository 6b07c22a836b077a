#include "RefractaRenderOutputs.h"

#include "RefractaSceneMedium.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkPointData.h"
#include "vtkXMLImageDataWriter.h"

#include <cstdio>
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

namespace
{
// The folder of `file` ("." without one).
std::string Folder(const std::string& file)
{
  const size_t slash = file.find_last_of('/');
  return slash == std::string::npos ? "." : (slash == 0 ? "/" : file.substr(0, slash));
}

// Whether two output names are one file: the same name in the same folder (out/a.vti and
// ./out/a.vti), the folders compared by identity.
bool SameFile(const std::string& a, const std::string& b)
{
  const size_t sa = a.find_last_of('/'), sb = b.find_last_of('/');
  const std::string nameA = sa == std::string::npos ? a : a.substr(sa + 1);
  const std::string nameB = sb == std::string::npos ? b : b.substr(sb + 1);
  struct stat fa, fb;
  return nameA == nameB && stat(Folder(a).c_str(), &fa) == 0 && stat(Folder(b).c_str(), &fb) == 0 &&
    fa.st_dev == fb.st_dev && fa.st_ino == fb.st_ino;
}
}

void CheckOutputs(const std::vector<OutputFile>& outputs, const std::string& sceneFile)
{
  struct stat scene;
  const bool haveScene = !sceneFile.empty() && stat(sceneFile.c_str(), &scene) == 0;
  for (size_t i = 0; i < outputs.size(); ++i)
  {
    const std::string& file = outputs[i].File;
    if (file.empty())
    {
      continue;
    }
    const std::string what = outputs[i].Option + " '" + file + "'";
    const std::string& suffix = outputs[i].Suffix;
    if ("." + Extension(file) != suffix)
    {
      throw std::runtime_error(what + ": the file name must end in " + suffix + " (its format)");
    }
    const std::string folder = Folder(file);
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
    if (stat(file.c_str(), &info) == 0)
    {
      if (!S_ISREG(info.st_mode))
      {
        throw std::runtime_error("cannot write " + what + ": it exists and is " +
          (S_ISDIR(info.st_mode) ? "a folder" : "not a regular file"));
      }
      if (haveScene && info.st_dev == scene.st_dev && info.st_ino == scene.st_ino)
      {
        throw std::runtime_error(what + " is the scene file: it would be overwritten");
      }
      if (access(file.c_str(), W_OK) != 0)
      {
        throw std::runtime_error("cannot write " + what + ": the file is not writable");
      }
    }
    for (size_t j = 0; j < i; ++j)
    {
      if (SameFile(outputs[j].File, file))
      {
        throw std::runtime_error(
          what + " is also the file of " + outputs[j].Option + ": give each output its own file");
      }
    }
  }
}

void RemoveOutputs(const std::vector<std::string>& written)
{
  for (const std::string& file : written)
  {
    std::remove(file.c_str());
  }
}
}
