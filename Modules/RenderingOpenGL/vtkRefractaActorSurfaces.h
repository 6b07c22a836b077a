/**
 * @class   vtkRefractaActorSurfaces
 * @brief   The opaque polydata actors of a vtkRenderer as a vtkRefractaSurfaceSet, so that light
 *          and view rays in the medium meet them.
 *
 * vtkRefractiveVolumeMapper calls Update() on every render. An actor is **taken** when
 * - it is a vtkActor in the renderer's actor collection, visible (GetVisibility()),
 * - its mapper is a vtkPolyDataMapper (or a subclass) whose input is a vtkPolyData with
 *   polygons or strips (verts and lines are no surfaces and are ignored),
 * - it is opaque: property opacity 1 and no translucent geometry
 *   (!HasTranslucentPolygonalGeometry(): no alpha < 1 in its mapped colours or texture),
 * - it is drawn as a surface (property representation VTK_SURFACE).
 * Its placement is the actor's matrix (actor->GetMatrix(): position, orientation, scale, origin
 * and user matrix), its albedo
 * - the mapper's mapped scalar colours (mapper->MapScalars(1.0): RGBA per point or per cell, as
 *   VTK colours it) where the mapper shows scalars (ScalarVisibility on and scalars present;
 *   with InterpolateScalarsBeforeMapping the lookup table is applied per point instead),
 * - otherwise, where the actor has a texture (vtkActor::GetTexture(), its input image) and its
 *   input texture coordinates, the texture sampled there as vtkTexture maps it (its Repeat and
 *   Interpolate) times the property's diffuse colour (vtkRefractaSurfaceMaterial::SetTexture),
 * - otherwise the property's diffuse colour (its Diffuse, Ambient and Specular coefficients are
 *   not used: a surface is Lambertian with that albedo).
 * The surface set bakes the colour per atlas texel (the mean of four samples), so a texture
 * finer than the texels is seen averaged over them.
 *
 * **Not taken** (left to VTK's drawing and composited by depth, see vtkRefractiveVolumeMapper):
 * invisible actors, translucent actors (opacity < 1 or translucent colours/texture), actors drawn
 * as wireframe or points (a cage drawn around a volume hides nothing), actors whose
 * mapper is not a vtkPolyDataMapper (composite datasets, glyph mappers of other kinds, images,
 * other volumes) and any prop that is not a vtkActor (assemblies, image actors). Those visible
 * props with opaque geometry are counted by GetNumberOfForeignProps(). A vtkSkybox is neither:
 * it is the background (drawn at the far plane, seen through the medium as the renderer's
 * environment, see vtkRefractaRendererBackground), not a surface in the scene.
 *
 * Cache: the surface set is rebuilt (its meshes and materials replaced) only when the list of
 * taken actors or the MTime of an actor's mapper, input, property or lookup table changes;
 * moving an actor only modifies its matrix, which the set reads at Build(), so a move re-runs
 * the light passes but never the medium stage. GetNumberOfRebuilds() counts the rebuilds.
 */
#ifndef vtkRefractaActorSurfaces_h
#define vtkRefractaActorSurfaces_h

#include "RefractaRenderingOpenGLModule.h" // for export macro
#include "vtkObject.h"
#include "vtkSmartPointer.h" // for members

#include <vector> // for std::vector

class vtkActor;
class vtkPolyData;
class vtkProp;
class vtkRefractaSurfaceSet;
class vtkRenderer;

class REFRACTARENDERINGOPENGL_EXPORT vtkRefractaActorSurfaces : public vtkObject
{
public:
  static vtkRefractaActorSurfaces* New();
  vtkTypeMacro(vtkRefractaActorSurfaces, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Collects the renderer's actors (`exclude`, the volume being rendered, is skipped) and
   * rebuilds the set where they changed (see the class description).
   */
  void Update(vtkRenderer* renderer, vtkProp* exclude);

  /// The surfaces of the last Update() (never nullptr; empty without taken actors).
  vtkRefractaSurfaceSet* GetSurfaces();

  /// Whether an actor would be taken (the rules of the class description).
  static bool IsTaken(vtkActor* actor);

  /// The actors taken by the last Update().
  int GetNumberOfActors() const { return static_cast<int>(this->Taken.size()); }
  vtkActor* GetActor(int i) const;

  /// Visible props with opaque geometry that the last Update() did not take.
  vtkGetMacro(NumberOfForeignProps, int);

  /// How many times the set's meshes and materials were rebuilt.
  vtkGetMacro(NumberOfRebuilds, int);

protected:
  vtkRefractaActorSurfaces();
  ~vtkRefractaActorSurfaces() override;

private:
  vtkRefractaActorSurfaces(const vtkRefractaActorSurfaces&) = delete;
  void operator=(const vtkRefractaActorSurfaces&) = delete;

  static vtkPolyData* ActorInput(vtkActor* actor);
  static bool IsForeign(vtkProp* prop);
  std::vector<double> Signature() const;
  void Rebuild();

  vtkSmartPointer<vtkRefractaSurfaceSet> Surfaces;
  std::vector<vtkSmartPointer<vtkActor>> Taken;
  std::vector<double> BuiltSignature;
  int NumberOfForeignProps = 0;
  int NumberOfRebuilds = 0;
};

#endif
