// The medium of a refracta-render scene ("scene.medium"): meshes voxelized with their materials
// (vtkMeshVoxelizer), or a volume file, taken as it is when it holds Refracta's arrays or mapped
// through transfer functions (vtkTransferFunctionMedium). Also the mesh, image and file helpers
// the rest of the scene uses (the surfaces read their meshes here too).
#ifndef RefractaSceneMedium_h
#define RefractaSceneMedium_h

#include "RefractaSceneJson.h"

#include "vtkImageData.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <string>

namespace RefractaRender
{
/// A medium ready to render and its part of the report ("source", "dimensions", voxelizer
/// stage seconds).
struct SceneMedium
{
  vtkSmartPointer<vtkImageData> Image;
  json Report;
};

/// A filter that refused to build the medium; what() is "<step> failed: <the filter's own
/// message>", the message captured from the filter (vtkRefractaErrorCapture) instead of printed.
struct FilterError : std::runtime_error
{
  FilterError(const std::string& step, const std::string& reason)
    : std::runtime_error(step + " failed: " + (reason.empty() ? "no medium came out" : reason))
    , Reason(reason)
  {
  }
  std::string Reason; ///< the filter's message; empty when it failed without one
};

/// Builds the medium "scene.medium" describes; file names are relative to `base`. Throws
/// SceneError for a bad description, FilterError where a filter fails.
SceneMedium ReadMedium(const json& scene, const std::string& base);

/// A triangulated sphere from {"center", "radius", "resolution"} (theta resolution; phi half
/// of it). Used by the medium's meshes and by the surfaces.
vtkSmartPointer<vtkPolyData> ReadSphere(const json& sphere, const std::string& path);

/// A triangulated axis-aligned box from {"bounds"} (required).
vtkSmartPointer<vtkPolyData> ReadBox(const json& box, const std::string& path);

/// Reads a mesh file (.ply, .stl, .obj, .vtp; `name` relative to `base`) that holds polygons;
/// failures name the scene key `path`.
vtkSmartPointer<vtkPolyData> ReadMeshFile(
  const json& name, const std::string& path, const std::string& base);

/// Reads an image or volume file (.vti, .mha, .mhd, .nrrd, .nhdr, .png, .jpg); failures name
/// the scene key `path`.
vtkSmartPointer<vtkImageData> ReadImageFile(const std::string& file, const std::string& path);

/// The extension of `file` in lower case, without the dot ("" without one).
std::string Extension(const std::string& file);

/// `file` relative to the folder `base` (unchanged where absolute or where base is empty).
std::string Resolve(const std::string& base, const std::string& file);
}

#endif
