/**
 * Internal to RefractaReference (a private header: not wrapped, not installed). The flight of
 * one path through the reference scene, shared by the path tracer's view paths and the photon
 * mapper's photon and view walks, so that all three move through the scene the same way:
 * straight outside the medium's box (meeting surfaces and the box), delta-tracked and curved
 * inside it (meeting surfaces), and through glass: at a dielectric surface one Fresnel choice
 * (Surfaces::Interface; the probability is the weight, so the path's throughput is unchanged and
 * nothing is returned to the owner). Inside a glass body (a dielectric surface with an inside
 * medium, Physics.md "Glass bodies") the path is tracked in the body's homogeneous medium, not
 * the grid's (Body; Local() gives the owner the medium at a collision). Next() stops at what the
 * owner decides about: an opaque
 * surface hit, a tentative collision in the medium, the path's escape, or its end at a safety
 * limit.
 */
#ifndef vtkReferenceWalk_h
#define vtkReferenceWalk_h

#include "vtkReferencePathTracer.h"

namespace refracta
{
namespace reference
{
class Walk
{
public:
  enum class Stop
  {
    Escaped,   // flew off outside the box along D from X, nothing in the way
    Surface,   // met the opaque surface Hit at X, arriving along D
    Collision, // a tentative collision at Ray.X (direction Ray.Dir) under the majorant Majorant
    Ended      // a safety limit (stuck integrator, too many interfaces): `truncated` is set
  };

  // A path from x along the unit d, through `scene`, its curved flights integrated by `tracer`.
  Walk(const Scene& scene, const Tracer& tracer, const Vec3& x, const Vec3& d);

  // Flies on to the next stop; `ch` the channel whose extinction drives the delta tracking.
  Stop Next(int ch, Rng& rng, bool& truncated);

  // After Surface: the hit's unit normal on the side the path arrives from (surfaces are
  // two-sided).
  Vec3 FacingNormal() const;

  // After Surface: leaves the surface (unit normal n on the side the path goes to) along the
  // unit direction `dir`.
  void LeaveSurface(const Vec3& n, const Vec3& dir);

  // After Collision: goes on from the collision point along the unit direction `dir`.
  void ScatterInto(const Vec3& dir);

  // The medium at the collision point: the body's inside a glass body, else the grid's.
  struct Local
  {
    Vec3 Sigma, Albedo, Emission;
    double G = 0, N = 1;
    bool Emits = false; // whether Emission may be nonzero
  };
  Local Here() const;

  Vec3 X, D;         // the path's point and direction outside the integrator (see Stop)
  SurfaceHit Hit;    // after Surface
  RayState Ray;      // the integrator's state in the box (after Collision: its point)
  double Majorant{}; // after Collision
  int Body = -1;     // the glass body the path is in (Surfaces::BodyMedium), or -1: the grid
  // Where the medium has extinction, tentative collisions come at a rate of at least this
  // (1 / world length; default 0: the medium's majorants). For owners that use every tentative
  // collision with ratio-tracking weights (the photon mapper's gathering view rays).
  double MinimumMajorant = 0;

private:
  // Whether the path at X along D starts inside the box (then the integrator starts there).
  void Restart();
  // Inside a glass body: moves the ray by an optical length tau of the body's sigma_t.
  Event AdvanceInBody(double tau, int ch, int& light);
  // One Fresnel choice at the glass `hit` (X, D updated); false (truncated) past MaxInterfaces.
  bool CrossInterface(const SurfaceHit& hit, Rng& rng, bool& truncated);

  const Scene& S;
  const Tracer& T;
  bool InBox = false;
  bool MayEnter = true; // false after leaving the convex box along a straight ray
  int Interfaces = 0;   // dielectric interfaces met
};
} // namespace reference
} // namespace refracta

#endif
