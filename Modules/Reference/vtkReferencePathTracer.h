/**
 * Internal to RefractaReference (a private header: not wrapped, not installed). The path tracer
 * of the reference renderer: delta tracking of view paths, emission, the background,
 * Henyey-Greenstein scattering and diffuse surface reflection with Russian roulette, and at every
 * vertex (medium or surface) a one-sample MIS connection (the vertex's own distribution mixed
 * with the emitters': light cones and, when it illuminates, the environment) whose transmittance
 * is estimated by ratio tracking, surfaces occluding. Paths fly straight outside the medium's box
 * (where they meet surfaces, lights and the box) and curved inside it.
 */
#ifndef vtkReferencePathTracer_h
#define vtkReferencePathTracer_h

#include "vtkReferenceEnvironment.h"
#include "vtkReferenceIntegrator.h"
#include "vtkReferenceLights.h"
#include "vtkReferenceMath.h"
#include "vtkReferenceMedium.h"
#include "vtkReferenceSampling.h"

#include <vector>

namespace refracta
{
namespace reference
{
class Walk;

// Everything a path needs.
struct Scene
{
  Medium M;
  std::vector<Light> Lights;
  Surfaces Surf;
  Environment Env;       // the background: colour or map
  bool EnvLight = false; // the background illuminates (and can be sampled: not black)
  int MaxDepth = -1;
  int RouletteDepth = 8;
  int MaxVertices = 100000;
  // Dielectric interfaces one path may meet before it is dropped (and counted as truncated): a
  // ray trapped by total internal reflection in a closed glass body ends here.
  int MaxInterfaces = 1000;
  Tracer T;      // view rays (surfaces tested, no light spheres)
  Tracer TLight; // connection rays (light spheres and surfaces tested)

  // Background radiance seen along the grid-local direction dLocal: the environment map when one
  // is set, else the uniform background colour.
  Vec3 BackgroundRadiance(const Vec3& dLocal) const;

  // Radiance arriving along a ray that escaped (straight, nothing in the way): every directional
  // disc containing d, plus the background when it illuminates.
  Vec3 EscapedRadiance(const Vec3& d) const;

  // What a straight flight outside the box from x along the unit d meets first.
  enum class Outside
  {
    Entered, // the box (only when enterBox)
    Surface, // a surface (hit)
    Light,   // a light sphere (only when lights; its index in light)
    Escaped  // nothing
  };
  // Moves x to the event's point.
  Outside FlyOutside(
    Vec3& x, const Vec3& d, bool enterBox, bool lights, int& light, SurfaceHit& hit) const;

  // Light arriving at x along the (curved in the box, straight outside) ray leaving x in
  // direction w, without any scattering or reflection on the way, times the transmittance to the
  // light, estimated by ratio tracking (the tentative-collision weights (1 - sigma_t / majorant)
  // multiply; Russian roulette once the weight is small). A surface in the way occludes. Only the
  // channel `ch` matters for the transmittance (all three when grey).
  Vec3 Connect(const Vec3& x, const Vec3& w, int ch, Rng& rng, bool& truncated) const;

  // Emitters for next-event estimation: the lights, then the environment when it illuminates.
  int NumEmitters() const { return static_cast<int>(Lights.size()) + (EnvLight ? 1 : 0); }
  // A grid-local direction from x towards a uniformly chosen emitter (its cone, or the
  // environment's luminance distribution).
  Vec3 SampleEmitter(const Vec3& x, Rng& rng) const;
  // Solid-angle pdf of SampleEmitter at the unit direction w.
  double EmitterPdf(const Vec3& x, const Vec3& w) const;

  // Accounts for a scattering or reflection event of albedo `albedo` at `depth` events so far:
  // false when the path ends there (no emitters, zero albedo, MaxDepth, Russian roulette, or
  // MaxVertices, which sets `truncated`); else multiplies beta by albedo (and 1 / survival) and
  // counts the event.
  bool Scatter(
    int& depth, Vec3& beta, const Vec3& albedo, int ch, bool grey, Rng& rng, bool& truncated) const;

  // The light a diffuse surface at x (unit normal n facing the arriving path) reflects towards
  // the path, per unit beta: one-sample MIS of 0.5 cosine + 0.5 emitters.
  Vec3 SurfaceDirect(const Vec3& x, const Vec3& n, int ch, Rng& rng, bool& truncated) const;

  // The light a medium vertex at x scatters into -dir, per unit beta (phase g): one-sample MIS of
  // 0.5 HG + 0.5 emitters.
  Vec3 MediumDirect(
    const Vec3& x, const Vec3& dir, double g, int ch, Rng& rng, bool& truncated) const;

  // A view path's stop at an opaque surface (after Walk::Stop::Surface): the event counted
  // (Scatter), the light reaching it by next-event estimation added to `result` (times beta and
  // `mask`), then a cosine-weighted bounce. False when the path ends there.
  bool ViewSurfaceVertex(Walk& walk, int& depth, Vec3& beta, Vec3& result, const Vec3& mask, int ch,
    bool grey, Rng& rng, bool& truncated) const;

  // One path from a view ray. channel < 0: grey medium, RGB carried together; else only that
  // channel is estimated (returned in that component). `truncated` is set when the path hit a
  // safety limit.
  //
  // At every scattering vertex and surface hit the light that reaches the vertex without a further
  // collision or reflection is estimated by one connection ray (MediumDirect, SurfaceDirect); the
  // path itself continues in an HG or cosine-weighted direction and only its later vertices
  // contribute (light it reaches unscattered was already counted by the connection).
  Vec3 Trace(Vec3 origin, Vec3 dir, int channel, Rng& rng, bool& truncated) const;
};
} // namespace reference
} // namespace refracta

#endif
