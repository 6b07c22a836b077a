#include "RefractaSceneMedium.h"

#include "vtkCellData.h"
#include "vtkColorTransferFunction.h"
#include "vtkCubeSource.h"
#include "vtkImageAlgorithm.h"
#include "vtkImageData.h"
#include "vtkJPEGReader.h"
#include "vtkMediumMaterial.h"
#include "vtkMediumValidator.h"
#include "vtkMeshVoxelizer.h"
#include "vtkMetaImageReader.h"
#include "vtkNew.h"
#include "vtkNrrdReader.h"
#include "vtkOBJReader.h"
#include "vtkPLYReader.h"
#include "vtkPNGReader.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkRefractaErrorCapture.h"
#include "vtkRefractaMedium.h"
#include "vtkSTLReader.h"
#include "vtkSphereSource.h"
#include "vtkTransferFunctionMedium.h"
#include "vtkTriangleFilter.h"
#include "vtkVolumeProperty.h"
#include "vtkXMLImageDataReader.h"
#include "vtkXMLPolyDataReader.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <map>
#include <stdexcept>
#include <vector>

namespace RefractaRender
{
namespace
{
// ---------------------------------------------------------------------------------------------
// Runs `filter`; an empty output throws FilterError with the filter's own message, said once
// (without VTK's executive dump).
vtkSmartPointer<vtkImageData> UpdateOrThrow(vtkImageAlgorithm* filter, const std::string& step)
{
  vtkNew<vtkRefractaErrorCapture> error;
  error->Observe(filter);
  filter->Update();
  vtkImageData* image = filter->GetOutput();
  if (!image || image->GetNumberOfPoints() == 0)
  {
    throw FilterError(step, error->GetText());
  }
  return image;
}

// ---------------------------------------------------------------------------------------------
// Files: a reader chosen by the file's extension.
using ReaderFactory = vtkSmartPointer<vtkAlgorithm> (*)(const std::string&);
using ReaderTable = std::map<std::string, ReaderFactory>;

template <typename Reader>
vtkSmartPointer<vtkAlgorithm> NewReader(const std::string& file)
{
  auto reader = vtkSmartPointer<Reader>::New();
  reader->SetFileName(file.c_str());
  return reader;
}

const ReaderTable MeshReaders = { { "ply", &NewReader<vtkPLYReader> },
  { "stl", &NewReader<vtkSTLReader> }, { "obj", &NewReader<vtkOBJReader> },
  { "vtp", &NewReader<vtkXMLPolyDataReader> } };

const ReaderTable ImageReaders = { { "vti", &NewReader<vtkXMLImageDataReader> },
  { "mha", &NewReader<vtkMetaImageReader> }, { "mhd", &NewReader<vtkMetaImageReader> },
  { "nrrd", &NewReader<vtkNrrdReader> }, { "nhdr", &NewReader<vtkNrrdReader> },
  { "png", &NewReader<vtkPNGReader> }, { "jpg", &NewReader<vtkJPEGReader> },
  { "jpeg", &NewReader<vtkJPEGReader> } };

// Runs the reader `readers` has for the file's extension; failures name the scene key `path`
// and, for an unknown extension, the `supported` ones.
vtkSmartPointer<vtkAlgorithm> ReadFile(const ReaderTable& readers, const std::string& file,
  const std::string& path, const std::string& supported)
{
  if (!std::ifstream(file).good())
  {
    Fail(path, "cannot read '" + file + "'");
  }
  const auto it = readers.find(Extension(file));
  if (it == readers.end())
  {
    Fail(path, "'" + file + "' has an unsupported extension (use " + supported + ")");
  }
  vtkSmartPointer<vtkAlgorithm> reader = it->second(file);
  vtkNew<vtkRefractaErrorCapture> error;
  error->Observe(reader);
  reader->Update();
  if (error->HasError())
  {
    Fail(path, "'" + file + "' could not be read: " + error->GetText());
  }
  return reader;
}

// ---------------------------------------------------------------------------------------------
// Meshes and their materials.
vtkSmartPointer<vtkMediumMaterial> ReadMaterial(const json& m, const std::string& path)
{
  CheckKeys(m, path, { "refractive_index", "extinction", "albedo", "anisotropy", "emission" });
  auto material = vtkSmartPointer<vtkMediumMaterial>::New();
  material->SetRefractiveIndex(
    Number(m, "refractive_index", path, 1.0, 1.0, vtkRefractaMedium::MaximumRefractiveIndex));
  auto e = Vector(m, "extinction", path, { 0, 0, 0 }, 3, 0.0, 1e9);
  material->SetExtinction(e.data());
  auto a = Vector(m, "albedo", path, { 0, 0, 0 }, 3, 0.0, 1.0);
  material->SetAlbedo(a.data());
  material->SetAnisotropy(Number(m, "anisotropy", path, 0.0, -0.9999, 0.9999));
  auto em = Vector(m, "emission", path, { 0, 0, 0 }, 3, 0.0, 1e9);
  material->SetEmission(em.data());
  return material;
}
}

// ---------------------------------------------------------------------------------------------
// Mesh descriptions shared by the medium's meshes and the surfaces.
vtkSmartPointer<vtkPolyData> ReadSphere(const json& s, const std::string& p)
{
  CheckKeys(s, p, { "center", "radius", "resolution" });
  auto c = Vector(s, "center", p, { 0, 0, 0 }, 3, -1e30, 1e30);
  vtkNew<vtkSphereSource> source;
  source->SetCenter(c.data());
  source->SetRadius(Number(s, "radius", p, 1.0, 1e-30, 1e30));
  const int res = Integer(s, "resolution", p, 64, 8, 1024);
  source->SetThetaResolution(res);
  source->SetPhiResolution(res / 2);
  source->Update();
  return source->GetOutput();
}

vtkSmartPointer<vtkPolyData> ReadBox(const json& b, const std::string& p)
{
  CheckKeys(b, p, { "bounds" });
  if (!b.contains("bounds"))
  {
    Fail(p + ".bounds", "missing (xmin, xmax, ymin, ymax, zmin, zmax)");
  }
  auto bounds = Bounds(b, "bounds", p);
  vtkNew<vtkCubeSource> cube;
  cube->SetBounds(bounds.data());
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputConnection(cube->GetOutputPort());
  triangles->Update();
  return triangles->GetOutput();
}

vtkSmartPointer<vtkPolyData> ReadMeshFile(
  const json& name, const std::string& p, const std::string& base)
{
  if (!name.is_string())
  {
    Fail(p, "must be a file name");
  }
  const std::string file = Resolve(base, name.get<std::string>());
  auto reader = ReadFile(MeshReaders, file, p, ".ply, .stl, .obj or .vtp");
  vtkSmartPointer<vtkPolyData> poly = vtkPolyData::SafeDownCast(reader->GetOutputDataObject(0));
  if (!poly || poly->GetNumberOfPolys() + poly->GetNumberOfStrips() == 0)
  {
    Fail(p, "'" + file + "' holds no polygons");
  }
  // A medium's mesh and a surface's alike (the voxelizer would refuse it without the key path).
  vtkPoints* points = poly->GetPoints();
  for (vtkIdType i = 0; points && i < points->GetNumberOfPoints(); ++i)
  {
    double x[3];
    points->GetPoint(i, x);
    if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2]))
    {
      Fail(
        p, "'" + file + "' has a non-finite vertex coordinate (point " + std::to_string(i) + ")");
    }
  }
  return poly;
}

namespace
{
vtkSmartPointer<vtkPolyData> ReadMesh(
  const json& mesh, const std::string& path, const std::string& base)
{
  int kinds = mesh.contains("file") + mesh.contains("sphere") + mesh.contains("box");
  if (kinds != 1)
  {
    Fail(path, "needs exactly one of 'file', 'sphere' or 'box'");
  }
  if (mesh.contains("sphere"))
  {
    return ReadSphere(mesh["sphere"], path + ".sphere");
  }
  if (mesh.contains("box"))
  {
    return ReadBox(mesh["box"], path + ".box");
  }
  return ReadMeshFile(mesh["file"], path + ".file", base);
}

// "meshes": the meshes voxelized on "grid" inside the "surrounding" material.
SceneMedium VoxelizeMeshes(const json& medium, const std::string& base)
{
  const json& meshes = medium["meshes"];
  if (!meshes.is_array() || meshes.empty())
  {
    Fail("scene.medium.meshes", "must be a non-empty array of meshes");
  }
  vtkNew<vtkMeshVoxelizer> voxelizer;
  const json grid = medium.value("grid", json::object());
  CheckKeys(grid, "scene.medium.grid",
    { "dimensions", "bounds", "padding", "supersampling", "smoothing_window", "interfaces" });
  const auto dims = IntegerVector(grid, "dimensions", "scene.medium.grid", { 64, 64, 64 }, 3, 1, 2048);
  voxelizer->SetDimensions(dims[0], dims[1], dims[2]);
  if (grid.contains("bounds"))
  {
    voxelizer->SetBounds(Bounds(grid, "bounds", "scene.medium.grid").data());
  }
  voxelizer->SetPadding(Number(grid, "padding", "scene.medium.grid", 0.0, 0.0, 1e30));
  voxelizer->SetSupersampling(Integer(grid, "supersampling", "scene.medium.grid", 4, 1, 16));
  const int window = Integer(grid, "smoothing_window", "scene.medium.grid", 9, 1, 63);
  if (window % 2 == 0)
  {
    Fail("scene.medium.grid.smoothing_window", "must be odd (a window centred on its voxel)");
  }
  voxelizer->SetSmoothingWindow(window);
  // "exact": the meshes are exact dielectric interfaces (Snell and Fresnel at the triangles);
  // "smoothed": the paper's Gaussian-smoothed index field (smoothing_window).
  const std::string interfaces =
    String(grid, "interfaces", "scene.medium.grid", "exact", { "exact", "smoothed" });
  voxelizer->SetInterfaceMode(interfaces == "exact" ? vtkMeshVoxelizer::EXACT_INTERFACES
                                                    : vtkMeshVoxelizer::SMOOTHED_INDEX);
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
    // The voxelizer's messages name the mesh as the scene file does.
    const json* file = meshes[i].contains("file") ? &meshes[i]["file"] : nullptr;
    voxelizer->SetMeshName(static_cast<int>(i),
      file && file->is_string() ? path + " ('" + file->get<std::string>() + "')" : path);
  }
  SceneMedium out;
  out.Image = UpdateOrThrow(voxelizer, "voxelizing the meshes");
  json stages = json::object();
  for (int s = 0; s < vtkMeshVoxelizer::NUMBER_OF_STAGES; ++s)
  {
    stages[vtkMeshVoxelizer::GetStageName(s)] = voxelizer->GetStageTime(s);
  }
  out.Report["voxelizer_stage_seconds"] = stages;
  out.Report["source"] = "meshes";
  out.Report["interfaces"] = voxelizer->GetWroteInterfaces() ? "exact" : "smoothed";
  return out;
}

// ---------------------------------------------------------------------------------------------
// A volume mapped through transfer functions.

// tf[key]: an array of points [scalar, value...] of `width` numbers each (empty where absent).
std::vector<std::vector<double>> TransferPoints(
  const json& tf, const char* key, const std::string& p, size_t width)
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
    out.push_back(Vector(
      wrapper, "point", p + "." + key + "[" + std::to_string(i) + "]", {}, width, -1e30, 1e30));
  }
  return out;
}

vtkSmartPointer<vtkImageData> MapThroughTransferFunctions(const json& volume, vtkImageData* input)
{
  const json& tf = volume["transfer_function"];
  const std::string p = "scene.medium.volume.transfer_function";
  CheckKeys(tf, p,
    { "opacity", "color", "unit_distance", "refractive_index", "anisotropy", "emission_scale" });
  vtkNew<vtkPiecewiseFunction> opacity;
  auto op = TransferPoints(tf, "opacity", p, 2);
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
  auto cp = TransferPoints(tf, "color", p, 4);
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
  // A point array, else a cell array (values at the cells' centres).
  vtkDataArray* mapped = input->GetPointData()->GetScalars();
  if (volume.contains("array"))
  {
    const std::string name = String(volume, "array", "scene.medium.volume", "");
    mapped = input->GetPointData()->GetArray(name.c_str());
    const bool point = mapped != nullptr;
    mapped = point ? mapped : input->GetCellData()->GetArray(name.c_str());
    if (!mapped)
    {
      Fail("scene.medium.volume.array", "the file has no point or cell array '" + name + "'");
    }
    mapping->SetInputArrayToProcess(0, 0, 0,
      point ? vtkDataObject::FIELD_ASSOCIATION_POINTS : vtkDataObject::FIELD_ASSOCIATION_CELLS,
      name.c_str());
  }
  else if (!mapped && input->GetCellData()->GetScalars())
  {
    mapped = input->GetCellData()->GetScalars();
    mapping->SetInputArrayToProcess(
      0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_CELLS, vtkDataSetAttributes::SCALARS);
  }
  // The scene gives one set of transfer functions: the layouts of several components (one
  // function per component, or colour and opacity components) have no keys here.
  if (mapped && mapped->GetNumberOfComponents() != 1)
  {
    Fail("scene.medium.volume.array",
      std::string("the array '") + (mapped->GetName() ? mapped->GetName() : "(active scalars)") +
        "' has " + std::to_string(mapped->GetNumberOfComponents()) +
        " components; a scene's transfer_function maps one-component arrays (extract a component "
        "or the magnitude into an array of its own first)");
  }
  mapping->SetVolumeProperty(property);
  auto ri = TransferPoints(tf, "refractive_index", p, 2);
  vtkNew<vtkPiecewiseFunction> index;
  for (auto& q : ri)
  {
    if (!(q[1] >= 1 && q[1] <= vtkRefractaMedium::MaximumRefractiveIndex))
    {
      Fail(p + ".refractive_index", "indices must be in [1, 100]");
    }
    index->AddPoint(q[0], q[1]);
  }
  if (!ri.empty())
  {
    mapping->SetRefractiveIndexFunction(index);
  }
  mapping->SetAnisotropy(Number(tf, "anisotropy", p, 0.0, -0.9999, 0.9999));
  mapping->SetEmissionScale(Number(tf, "emission_scale", p, 0.0, 0.0, 1e30));
  return UpdateOrThrow(mapping, "mapping the volume through its transfer functions");
}

// "volume": a file with Refracta's arrays, or any volume with a "transfer_function".
SceneMedium ReadVolume(const json& medium, const std::string& base)
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
  const std::string file = Resolve(base, volume["file"].get<std::string>());
  auto input = ReadImageFile(file, "scene.medium.volume.file");
  SceneMedium out;
  vtkNew<vtkMediumValidator> validator;
  if (volume.contains("transfer_function"))
  {
    out.Image = MapThroughTransferFunctions(volume, input);
    // The mapped medium keeps the file's grid: a bad spacing or direction is the file's.
    if (!validator->Validate(out.Image))
    {
      Fail("scene.medium.volume.file", "'" + file + "': " + validator->GetErrorMessage());
    }
    out.Report["source"] = "volume with transfer functions";
    return out;
  }
  if (volume.contains("array"))
  {
    Fail("scene.medium.volume.array", "only used with a transfer_function");
  }
  if (!validator->Validate(input))
  {
    Fail("scene.medium.volume.file",
      "'" + file + "' is not a Refracta medium and no transfer_function is given: " +
        validator->GetErrorMessage());
  }
  out.Image = input;
  out.Report["source"] = "volume with Refracta arrays";
  return out;
}
}

// ---------------------------------------------------------------------------------------------
SceneMedium ReadMedium(const json& scene, const std::string& base)
{
  if (!scene.contains("medium"))
  {
    Fail("scene.medium", "missing (give 'meshes' or 'volume')");
  }
  const json& medium = scene["medium"];
  CheckKeys(medium, "scene.medium", { "grid", "surrounding", "meshes", "volume" });
  if (medium.contains("meshes") == medium.contains("volume"))
  {
    Fail("scene.medium", "needs exactly one of 'meshes' or 'volume'");
  }
  SceneMedium out =
    medium.contains("meshes") ? VoxelizeMeshes(medium, base) : ReadVolume(medium, base);
  int dims[3];
  out.Image->GetDimensions(dims);
  out.Report["dimensions"] = { dims[0], dims[1], dims[2] };
  return out;
}

vtkSmartPointer<vtkImageData> ReadImageFile(const std::string& file, const std::string& path)
{
  auto reader = ReadFile(ImageReaders, file, path, ".vti, .mha, .mhd, .nrrd, .nhdr, .png or .jpg");
  auto image = vtkSmartPointer<vtkImageData>::New();
  if (auto* out = vtkImageData::SafeDownCast(reader->GetOutputDataObject(0)))
  {
    image->ShallowCopy(out);
  }
  if (image->GetNumberOfPoints() == 0 ||
    image->GetPointData()->GetNumberOfArrays() + image->GetCellData()->GetNumberOfArrays() == 0)
  {
    Fail(path, "'" + file + "' could not be read as an image (no points or no data arrays)");
  }
  return image;
}

std::string Extension(const std::string& file)
{
  const size_t dot = file.find_last_of('.');
  std::string ext = dot == std::string::npos ? "" : file.substr(dot + 1);
  std::transform(
    ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

std::string Resolve(const std::string& base, const std::string& file)
{
  if (file.empty() || file[0] == '/' || base.empty())
  {
    return file;
  }
  return base + "/" + file;
}
}
