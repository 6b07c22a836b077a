#include "vtkRefractiveVolumeMapper.h"

#include "vtkAbstractMapper.h"
#include "vtkCamera.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkEffectPlan.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLatticeBoltzmannSolver.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMatrix4x4.h"
#include "vtkMediumValidator.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPlane.h"
#include "vtkPlaneCollection.h"
#include "vtkPointData.h"
#include "vtkProp3D.h"
#include "vtkPropCollection.h"
#include "vtkRefractaActorSurfaces.h"
#include "vtkRefractaBVH.h"
#include "vtkRefractaMedium.h"
#include "vtkRefractaRendererBackground.h"
#include "vtkRefractaSettings.h"
#include "vtkRefractaSurfaceSet.h"
#include "vtkRefractaViewPass.h"
#include "vtkRefractiveVolumeMapperCompositing.h"
#include "vtkRefractiveVolumeMapperInternals.h"
#include "vtkRenderer.h"
#include "vtkTimeStamp.h"
#include "vtkTransferFunctionMedium.h"
#include "vtkVolume.h"
#include "vtkVolumeCollection.h"
#include "vtkVolumeProperty.h"
#include "vtk_glew.h"

#include "vtkPhotonTracer.h"
#include "vtkRefractaRenderPipeline.h"
#include "vtkSceneAnalysis.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <sstream>
#include <vector>

vtkStandardNewMacro(vtkRefractiveVolumeMapper);
vtkRefractaCxxSetClampMacro(vtkRefractiveVolumeMapper, Anisotropy, -0.9999, 0.9999);
vtkRefractaCxxSetClampMacro(vtkRefractiveVolumeMapper, EmissionScale, 0.0, 1e30);
vtkRefractaCxxSetClampMacro(vtkRefractiveVolumeMapper, Exposure, 0.0, 1e30);

namespace
{
// Whether the voxel at data point `p` is kept by the cropping regions (VTK's 27 regions: index
// i + 3 j + 9 k, each of i, j, k 0 below the lower plane, 1 between, 2 above; bit set = kept).
bool KeptByCropping(const double p[3], const double planes[6], int flags)
{
  int region = 0;
  for (int a = 2; a >= 0; --a)
  {
    const int side = p[a] < planes[2 * a] ? 0 : (p[a] > planes[2 * a + 1] ? 2 : 1);
    region = region * 3 + side;
  }
  return (flags >> region) & 1;
}

// The medium with every voxel that the clipping planes (world coordinates, through the prop's
// data -> world matrix) or the cropping regions (data coordinates) remove set to empty space:
// each array at its vtkRefractaMedium default (vacuum: n = 1, no extinction, no emission) and
// occupancy 0. The removed part is gone for the light passes too, as if cut away.
vtkSmartPointer<vtkImageData> CutAway(vtkImageData* medium, vtkPlaneCollection* planes,
  vtkMatrix4x4* dataToWorld, bool cropping, const double cropPlanes[6], int cropFlags)
{
  auto cut = vtkSmartPointer<vtkImageData>::New();
  cut->DeepCopy(medium);
  vtkPointData* pd = cut->GetPointData();
  if (!pd->GetArray(vtkRefractaMedium::GetArrayName(vtkRefractaMedium::OCCUPANCY)))
  {
    vtkNew<vtkFloatArray> occupancy;
    occupancy->SetName(vtkRefractaMedium::GetArrayName(vtkRefractaMedium::OCCUPANCY));
    occupancy->SetNumberOfTuples(cut->GetNumberOfPoints());
    occupancy->Fill(1.0);
    pd->AddArray(occupancy);
  }
  for (vtkIdType id = 0; id < cut->GetNumberOfPoints(); ++id)
  {
    double p[4] = { 0, 0, 0, 1 }, world[4];
    cut->GetPoint(id, p);
    bool kept = !cropping || KeptByCropping(p, cropPlanes, cropFlags);
    if (kept && planes)
    {
      dataToWorld->MultiplyPoint(p, world);
      for (int w = 0; w < 3; ++w)
      {
        world[w] /= world[3];
      }
      vtkCollectionSimpleIterator it;
      planes->InitTraversal(it);
      while (vtkPlane* plane = planes->GetNextPlane(it))
      {
        kept = kept && plane->EvaluateFunction(world) >= 0.0; // the normal points to what stays
      }
    }
    if (kept)
    {
      continue;
    }
    for (int a = 0; a < vtkRefractaMedium::NUMBER_OF_ARRAYS; ++a)
    {
      if (vtkDataArray* array = pd->GetArray(vtkRefractaMedium::GetArrayName(a)))
      {
        const double value =
          a == vtkRefractaMedium::OCCUPANCY ? 0.0 : vtkRefractaMedium::GetDefaultValue(a);
        for (int c = 0; c < array->GetNumberOfComponents(); ++c)
        {
          array->SetComponent(id, c, value);
        }
      }
    }
  }
  return cut;
}

// Everything the pixels' path-length limits and kinds depend on besides the depth buffer, the
// surfaces and the medium's box: the rays (eye, pixel axes, grid placement) and the projection
// that turns depth into points. Camera moves, a shared mapper drawing another viewport and
// vtkRenderLargeImage's tiles change it while the depth buffer (all background) may not.
std::vector<double> ViewSignature(
  vtkRenderer* renderer, vtkCamera* camera, const vtkRefractaViewPass::RayFrame& frame)
{
  std::vector<double> view;
  for (const double* part : { frame.Eye, frame.U, frame.V, frame.W })
  {
    view.insert(view.end(), part, part + 3);
  }
  view.push_back(frame.Parallel ? 1.0 : 0.0);
  for (const auto& row : frame.WorldToLocal)
  {
    view.insert(view.end(), row, row + 4);
  }
  vtkMatrix4x4* projection =
    camera->GetCompositeProjectionTransformMatrix(renderer->GetTiledAspectRatio(), -1, 1);
  view.insert(view.end(), projection->GetData(), projection->GetData() + 16);
  return view;
}
}

//------------------------------------------------------------------------------
vtkRefractiveVolumeMapper::vtkRefractiveVolumeMapper()
  : Internal(new Internals)
{
  Internals& in = *this->Internal;
  in.MappingError->Observe(in.Mapping);
  this->Internal->Pipeline->GetPhotonTracer()->SetNumberOfPhotons(1 << 18);
  // A drop-in for VTK's volume mappers: the renderer's lights are read as VTK's shading reads
  // them (see vtkRefractaRenderPipeline::SetLightUnits).
  this->Internal->Pipeline->SetLightUnits(vtkRefractaRenderPipeline::VTK_LIGHT_UNITS);
  this->Internal->Pipeline->SetEventOwner(this);
}

vtkRefractiveVolumeMapper::~vtkRefractiveVolumeMapper()
{
  this->Internal->Pipeline->SetEventOwner(nullptr);
}

//------------------------------------------------------------------------------
void vtkRefractiveVolumeMapper::ReportOnce(const std::string& message)
{
  if (message != this->Internal->LastMessage)
  {
    vtkErrorMacro(<< message);
    this->Internal->LastMessage = message;
  }
}

//------------------------------------------------------------------------------
bool vtkRefractiveVolumeMapper::UpdateMedium(vtkVolume* volume)
{
  Internals& in = *this->Internal;
  if (vtkAlgorithm* producer = this->GetInputAlgorithm())
  {
    producer->Update();
  }
  vtkImageData* input = vtkImageData::SafeDownCast(this->GetInput());
  if (!input)
  {
    this->ReportOnce("The input must be a vtkImageData (a Refracta medium or a scalar image).");
    return false;
  }
  bool isMedium = false;
  for (int id = 0; id < vtkRefractaMedium::NUMBER_OF_ARRAYS; ++id)
  {
    isMedium = isMedium || input->GetPointData()->GetArray(vtkRefractaMedium::GetArrayName(id));
  }
  if (isMedium)
  {
    this->CutAwayClippedRegions(input, volume);
    return true;
  }

  // A scalar image: through the volume property, with the array this mapper selects (as
  // vtkGPUVolumeRayCastMapper does: SelectScalarArray / ScalarMode).
  vtkDataArray* scalars = nullptr;
  int cellFlag = 0;
  scalars = vtkAbstractMapper::GetScalars(
    input, this->ScalarMode, this->ArrayAccessMode, this->ArrayId, this->ArrayName, cellFlag);
  if (!scalars)
  {
    std::ostringstream message;
    message << "The input has no ";
    if (this->ScalarMode == VTK_SCALAR_MODE_USE_POINT_FIELD_DATA ||
      this->ScalarMode == VTK_SCALAR_MODE_USE_CELL_FIELD_DATA)
    {
      message << "array "
              << (this->ArrayAccessMode == VTK_GET_ARRAY_BY_NAME
                     ? std::string("'") + this->ArrayName + "'"
                     : std::to_string(this->ArrayId))
              << " in its "
              << (this->ScalarMode == VTK_SCALAR_MODE_USE_POINT_FIELD_DATA ? "point" : "cell")
              << " data";
    }
    else
    {
      message << "scalars";
    }
    message << " to map and none of the Refracta medium arrays (RefractiveIndex, Extinction, "
               "Albedo, ...); select an existing point array with SelectScalarArray().";
    this->ReportOnce(message.str());
    return false;
  }
  // Cell scalars are values at the cells' centres, as VTK's own volume mappers read them.
  const int association =
    cellFlag ? vtkDataObject::FIELD_ASSOCIATION_CELLS : vtkDataObject::FIELD_ASSOCIATION_POINTS;
  if (scalars->GetName() && *scalars->GetName())
  {
    in.Mapping->SetInputData(input);
    in.Mapping->SetInputArrayToProcess(0, 0, 0, association, scalars->GetName());
  }
  else
  {
    // Selected by index and unnamed: made the active scalars of a copy (the input's own active
    // scalars may be another array).
    if (input != in.UnnamedFrom || scalars != in.UnnamedArray ||
      std::max(input->GetMTime(), scalars->GetMTime()) > in.UnnamedTime.GetMTime())
    {
      in.Unnamed->ShallowCopy(input);
      (cellFlag ? static_cast<vtkDataSetAttributes*>(in.Unnamed->GetCellData())
                : in.Unnamed->GetPointData())
        ->SetScalars(scalars);
      in.UnnamedFrom = input;
      in.UnnamedArray = scalars;
      in.UnnamedTime.Modified();
    }
    in.Mapping->SetInputData(in.Unnamed);
    in.Mapping->SetInputArrayToProcess(0, 0, 0, association, vtkDataSetAttributes::SCALARS);
  }
  in.Mapping->SetVolumeProperty(volume->GetProperty());
  in.Mapping->SetRefractiveIndexFunction(in.IndexFunction);
  in.Mapping->SetAnisotropy(this->Anisotropy);
  in.Mapping->SetEmissionScale(this->EmissionScale);
  in.MappingError->Clear();
  in.Mapping->Update();
  if (in.Mapping->GetOutput()->GetNumberOfPoints() == 0)
  {
    this->ReportOnce("Mapping the scalar input through the volume property failed: " +
      (in.MappingError->HasError() ? in.MappingError->GetText()
                                   : std::string("no medium came out")));
    return false;
  }
  this->CutAwayClippedRegions(in.Mapping->GetOutput(), volume);
  return true;
}

//------------------------------------------------------------------------------
void vtkRefractiveVolumeMapper::CutAwayClippedRegions(vtkImageData* medium, vtkVolume* volume)
{
  Internals& in = *this->Internal;
  vtkPlaneCollection* planes = this->ClippingPlanes;
  const bool clipping = planes && planes->GetNumberOfItems() > 0;
  if (!clipping && !this->Cropping)
  {
    in.Medium = medium;
    in.Uncut = nullptr;
    return;
  }
  // Re-cut only when the medium, the planes, the cropping settings or the placement changed.
  const vtkMTimeType cutTime = in.CutTime.GetMTime();
  std::vector<double> cropping(this->CroppingRegionPlanes, this->CroppingRegionPlanes + 6);
  cropping.push_back(this->Cropping);
  cropping.push_back(this->CroppingRegionFlags);
  bool changed = medium != in.Uncut || !in.Medium || medium->GetMTime() > cutTime ||
    cropping != in.CutCropping || volume->GetMatrix()->GetMTime() > cutTime;
  if (clipping)
  {
    changed = changed || planes->GetMTime() > cutTime;
    vtkCollectionSimpleIterator it;
    planes->InitTraversal(it);
    while (vtkPlane* plane = planes->GetNextPlane(it))
    {
      changed = changed || plane->GetMTime() > cutTime;
    }
  }
  if (changed)
  {
    in.Medium = CutAway(medium, clipping ? planes : nullptr, volume->GetMatrix(),
      this->Cropping != 0, this->CroppingRegionPlanes, this->CroppingRegionFlags);
    in.Uncut = medium;
    in.CutCropping = cropping;
    in.CutTime.Modified();
  }
}

//------------------------------------------------------------------------------
void vtkRefractiveVolumeMapper::WarnAboutUnsupportedModes(vtkRenderer* renderer, vtkVolume* volume)
{
  Internals& in = *this->Internal;
  // This mapper replaces the pixels its medium covers (the view pass's radiance holds what is
  // seen through it) and writes no depth, so two volumes in one renderer cannot composite: the
  // one drawn later erases or ignores the other, by the order of the renderer's props.
  const char* other = nullptr;
  vtkVolumeCollection* volumes = renderer->GetVolumes();
  vtkCollectionSimpleIterator it;
  volumes->InitTraversal(it);
  while (vtkVolume* v = volumes->GetNextVolume(it))
  {
    // A prop that draws through this very mapper is this volume (ParaView's vtkPVLODVolume
    // hands the mapper an internal vtkVolume of its own).
    if (v != volume && v->GetVisibility() && v->GetMapper() && v->GetMapper() != this)
    {
      other = v->GetMapper()->GetClassName();
    }
  }
  if (other && !in.OtherVolumesWarned)
  {
    vtkWarningMacro("The renderer draws another visible volume (mapper "
      << other
      << ") besides this one. vtkRefractiveVolumeMapper replaces the pixels its medium covers and "
         "writes no depth, so where the two overlap one erases or hides the other, depending on "
         "the order VTK draws them. Put the media in one vtkImageData (vtkImageAppend, or "
         "resample them onto one grid), or draw the other volume in another renderer layer.");
  }
  in.OtherVolumesWarned = other != nullptr;
  // Translucent geometry is drawn by VTK before the volumes and written over where the medium
  // covers a pixel (this mapper composites by depth with opaque geometry only).
  const char* translucent = nullptr;
  vtkPropCollection* props = renderer->GetViewProps();
  props->InitTraversal(it);
  while (vtkProp* prop = props->GetNextProp(it))
  {
    // 3D props only: 2D overlays are drawn after the volume, over it.
    if (vtkProp3D::SafeDownCast(prop) && !vtkVolume::SafeDownCast(prop) && prop->GetVisibility() &&
      prop->HasTranslucentPolygonalGeometry())
    {
      translucent = prop->GetClassName();
    }
  }
  if (translucent && !in.TranslucentPropsWarned)
  {
    vtkWarningMacro("The renderer draws translucent geometry (a "
      << translucent
      << " with opacity below 1 or translucent colours). vtkRefractiveVolumeMapper composites "
         "with opaque geometry only: where the medium covers a pixel, translucent geometry is not "
         "seen. Make it opaque (it then becomes a surface the light and the view rays meet), or "
         "draw it in another renderer layer.");
  }
  in.TranslucentPropsWarned = translucent != nullptr;
  if (this->BlendMode != vtkVolumeMapper::COMPOSITE_BLEND && !in.BlendModeWarned)
  {
    vtkWarningMacro("BlendMode " << this->BlendMode
                                 << " is not physically based light transport: "
                                    "vtkRefractiveVolumeMapper renders COMPOSITE_BLEND only and "
                                    "ignores this setting (use vtkGPUVolumeRayCastMapper for "
                                    "maximum/minimum/average intensity projections).");
    in.BlendModeWarned = true;
  }
  if (this->BlendMode == vtkVolumeMapper::COMPOSITE_BLEND)
  {
    in.BlendModeWarned = false;
  }
}

//------------------------------------------------------------------------------
std::vector<float> vtkRefractiveVolumeMapper::DepthToPathLengths(vtkRenderer* renderer,
  vtkCamera* camera, const vtkRefractaViewPass::RayFrame& frame, int width, int height,
  const std::vector<float>& depth)
{
  const size_t pixels = static_cast<size_t>(width) * height;
  vtkMatrix4x4* projection =
    camera->GetCompositeProjectionTransformMatrix(renderer->GetTiledAspectRatio(), -1, 1);
  vtkNew<vtkMatrix4x4> inverse;
  vtkMatrix4x4::Invert(projection, inverse);
  std::vector<float> limits(pixels, std::numeric_limits<float>::infinity());
  const double* w = frame.W;
  const double wLength = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
  for (int j = 0; j < height; ++j)
  {
    for (int i = 0; i < width; ++i)
    {
      const size_t p = i + static_cast<size_t>(width) * j;
      if (depth[p] >= 1.0f)
      {
        continue; // nothing drawn there: the ray runs to the background
      }
      const double sx = 2.0 * (i + 0.5) / width - 1.0, sy = 2.0 * (j + 0.5) / height - 1.0;
      double ndc[4] = { sx, sy, 2.0 * depth[p] - 1.0, 1.0 }, world[4];
      inverse->MultiplyPoint(ndc, world);
      double local[3];
      for (int r = 0; r < 3; ++r)
      {
        local[r] = (frame.WorldToLocal[r][0] * world[0] + frame.WorldToLocal[r][1] * world[1] +
                     frame.WorldToLocal[r][2] * world[2]) /
            world[3] +
          frame.WorldToLocal[r][3];
      }
      double distance = 0;
      if (frame.Parallel)
      {
        for (int r = 0; r < 3; ++r)
        {
          const double origin = frame.Eye[r] + sx * frame.U[r] + sy * frame.V[r];
          distance += (local[r] - origin) * w[r] / wLength;
        }
      }
      else
      {
        distance = std::sqrt(vtkMath::Distance2BetweenPoints(local, frame.Eye));
      }
      limits[p] = static_cast<float>(std::max(distance, 0.0));
    }
  }
  return limits;
}

//------------------------------------------------------------------------------
void vtkRefractiveVolumeMapper::Render(vtkRenderer* renderer, vtkVolume* volume)
{
  Internals& in = *this->Internal;
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(renderer->GetRenderWindow());
  if (!window)
  {
    this->ReportOnce(std::string("vtkRefractiveVolumeMapper draws into an OpenGL render window; "
                                 "got ") +
      (renderer->GetRenderWindow() ? renderer->GetRenderWindow()->GetClassName() : "none"));
    return;
  }
  this->WarnAboutUnsupportedModes(renderer, volume);
  if (!this->UpdateMedium(volume))
  {
    return;
  }

  int width, height, x0, y0;
  renderer->GetTiledSizeAndOrigin(&width, &height, &x0, &y0);
  if (width < 1 || height < 1)
  {
    return;
  }
  vtkCamera* camera = renderer->GetActiveCamera();
  const size_t pixels = static_cast<size_t>(width) * height;

  // Depth of the opaque geometry drawn so far -> path-length limits and the pixels' kinds; the
  // conversion runs only when the depth buffer, the view (ViewSignature), the surfaces or the
  // medium's active box changed.
  std::vector<float> depth(pixels, 1.0f);
  window->GetZbufferData(x0, y0, x0 + width - 1, y0 + height - 1, depth.data());
  vtkRefractaViewPass::RayFrame frame;
  if (!vtkRefractaViewPass::ComputeRayFrame(
        camera, in.Medium, volume->GetMatrix(), width, height, frame))
  {
    this->ReportOnce(vtkRefractaViewPass::GetRayFrameProblem(camera, volume->GetMatrix()));
    return;
  }
  // The renderer's opaque actors as surfaces (rebuilt only where they changed).
  vtkRefractaSurfaceSet* surfaces = nullptr;
  if (this->ActorSurfaces)
  {
    in.Actors->Update(renderer, volume);
    surfaces = in.Actors->GetNumberOfActors() > 0 ? in.Actors->GetSurfaces() : nullptr;
  }
  const bool boxChanged = this->UpdateActiveBox();
  const bool surfacesChanged = surfaces != in.ClassifiedWith ||
    (surfaces && surfaces->GetMTime() > in.ClassifiedTime.GetMTime());
  std::vector<double> view = ViewSignature(renderer, camera, frame);
  if (boxChanged || surfacesChanged || depth != in.Depth || in.Limits.size() != pixels ||
    in.ClassifiedEverywhere != this->ShadeActorsEverywhere || view != in.ClassifiedView)
  {
    in.Limits = this->DepthToPathLengths(renderer, camera, frame, width, height, depth);
    in.Depth = std::move(depth);
    this->ClassifyPixels(renderer, camera, frame, surfaces, width, height);
    in.ClassifiedWith = surfaces;
    in.ClassifiedEverywhere = this->ShadeActorsEverywhere;
    in.ClassifiedView = std::move(view);
    in.ClassifiedTime.Modified();
  }

  vtkRefractaRenderPipeline* pipeline = in.Pipeline;
  pipeline->SetMedium(in.Medium);
  pipeline->SetLights(renderer->GetLights());
  pipeline->SetCamera(camera);
  pipeline->SetPropMatrix(volume->GetMatrix());
  pipeline->SetSurfaces(surfaces);
  in.Background->Apply(renderer, camera, pipeline->GetViewPass());
  if (!pipeline->Render(width, height, in.Limits.data()))
  {
    return;
  }
  in.LastMessage.clear();
  this->Composite(window, x0, y0, width, height);
}

//------------------------------------------------------------------------------
bool vtkRefractiveVolumeMapper::UpdateActiveBox()
{
  Internals& in = *this->Internal;
  if (in.ActiveBoxMedium == in.Medium && in.Medium->GetMTime() <= in.ActiveBoxTime)
  {
    return false;
  }
  in.ActiveBox = vtkRefractiveVolumeMapperDetail::ActiveBox(in.Medium, 2.0);
  in.ActiveBoxMedium = in.Medium;
  in.ActiveBoxTime = in.Medium->GetMTime();
  return true;
}

//------------------------------------------------------------------------------
void vtkRefractiveVolumeMapper::ClassifyPixels(vtkRenderer* renderer, vtkCamera* camera,
  const vtkRefractaViewPass::RayFrame& frame, vtkRefractaSurfaceSet* surfaces, int width,
  int height)
{
  using namespace vtkRefractiveVolumeMapperDetail;
  Internals& in = *this->Internal;
  // Depth drawn by a taken actor is the pipeline's own surface: no limit there (the view ray
  // meets the surface itself, bent or not). Without foreign props every drawn depth is ours;
  // with them, the BVH tells which pixels' depth is a surface of the set.
  const bool foreignProps = in.Actors->GetNumberOfForeignProps() > 0 || !surfaces;
  vtkRefractaBVH* bvh = nullptr;
  std::unique_ptr<DepthRays> rays;
  if (surfaces && foreignProps && surfaces->Build())
  {
    bvh = surfaces->GetBVH();
    rays.reset(new DepthRays(renderer, camera));
  }
  in.Kinds.assign(static_cast<size_t>(width) * height, CLEAR);
  for (int j = 0; j < height; ++j)
  {
    for (int i = 0; i < width; ++i)
    {
      const size_t p = i + static_cast<size_t>(width) * j;
      const bool surface = std::isfinite(in.Limits[p]) &&
        (!foreignProps || (bvh && rays->HitsSurface(bvh, i, j, width, height, in.Depth[p])));
      if (surface)
      {
        in.Limits[p] = std::numeric_limits<float>::infinity();
      }
      if (std::isfinite(in.Limits[p]))
      {
        in.Kinds[p] = FOREIGN;
      }
      else if ((surface && this->ShadeActorsEverywhere) ||
        RayCrossesBox(frame, i, j, width, height, in.ActiveBox, in.Limits[p]))
      {
        in.Kinds[p] = COVERED;
      }
    }
  }
}

//------------------------------------------------------------------------------
void vtkRefractiveVolumeMapper::Composite(
  vtkOpenGLRenderWindow* window, int x0, int y0, int width, int height)
{
  Internals& in = *this->Internal;
  vtkRefractaRenderPipeline* pipeline = in.Pipeline;
  const std::vector<float>& image = pipeline->GetImage();
  const std::vector<float>& transmittanceImage = pipeline->GetTransmittance();
  // The background seen through the medium is VTK's background, not the scene's light: kept out
  // of the exposure (vtkRefractiveVolumeMapperCompositing.h).
  const std::vector<float>& backgroundPart = pipeline->GetBackgroundPart();
  double exposureValue = this->Exposure;
  if (this->AutomaticExposure)
  {
    const int recomputed = pipeline->GetNumberOfPlanRuns() + pipeline->GetNumberOfLightPassRuns();
    if (recomputed != in.MeteredAt)
    {
      in.MeteredExposure = vtkRefractiveVolumeMapperDetail::MeterExposure(
        image, transmittanceImage, backgroundPart, in.Kinds);
      in.MeteredAt = recomputed;
    }
    exposureValue *= in.MeteredExposure;
  }
  this->LastExposure = exposureValue;

  // Per-channel compositing in two blended draws: first dst *= M (blend ZERO, SRC_COLOR), then
  // dst += A (blend ONE, ONE), M and A per pixel kind (vtkRefractiveVolumeMapperCompositing.h).
  // Where the frame's pixel is what shows behind the medium, VTK's own drawing of it is used,
  // unbent (vtkRefractaRendererBackground::GetLastShowsFramePixels).
  const bool unbentBackground = in.Background->GetLastShowsFramePixels();
  std::vector<float> multiply, add;
  vtkRefractiveVolumeMapperDetail::CompositingImages(image, transmittanceImage, backgroundPart,
    in.Kinds, static_cast<float>(exposureValue), unbentBackground ? &in.Depth : nullptr, multiply,
    add);
  vtkOpenGLState* state = window->GetState();
  vtkOpenGLState::ScopedglBlendFuncSeparate blendSaver(state);
  vtkOpenGLState::ScopedglEnableDisable blendEnable(state, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable depthEnable(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglDepthMask depthMask(state);
  state->vtkglEnable(GL_BLEND);
  state->vtkglDisable(GL_DEPTH_TEST);
  state->vtkglDepthMask(GL_FALSE);
  state->vtkglBlendFuncSeparate(GL_ZERO, GL_SRC_COLOR, GL_ZERO, GL_ONE);
  window->DrawPixels(x0, y0, x0 + width - 1, y0 + height - 1, 4, VTK_FLOAT, multiply.data());
  state->vtkglBlendFuncSeparate(GL_ONE, GL_ONE, GL_ZERO, GL_ONE);
  window->DrawPixels(x0, y0, x0 + width - 1, y0 + height - 1, 4, VTK_FLOAT, add.data());
}

//------------------------------------------------------------------------------
void vtkRefractiveVolumeMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "RefractiveIndexFunction: " << this->Internal->IndexFunction.Get() << "\n";
  os << indent << "Anisotropy: " << this->Anisotropy << "\n";
  os << indent << "EmissionScale: " << this->EmissionScale << "\n";
  os << indent << "Exposure: " << this->Exposure << "\n";
  os << indent << "AutomaticExposure: " << this->AutomaticExposure << "\n";
  os << indent << "LastExposure: " << this->LastExposure << "\n";
  os << indent << "ActorSurfaces: " << this->ActorSurfaces << "\n";
  os << indent << "ShadeActorsEverywhere: " << this->ShadeActorsEverywhere << "\n";
  os << indent << "BackgroundIlluminates: " << this->Internal->Pipeline->GetBackgroundIlluminates()
     << "\n";
  os << indent << "Pipeline:\n";
  this->Internal->Pipeline->PrintSelf(os, indent.GetNextIndent());
}
