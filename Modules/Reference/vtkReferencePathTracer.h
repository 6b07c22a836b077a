/**
 * Internal to RefractaReference (a private header: not wrapped, not installed). The path tracer
 * of the reference renderer: delta tracking of view paths, emission, the background,
 * Henyey-Greenstein scattering with Russian roulette, and at every scattering vertex a one-sample
 * MIS (HG + light cone) connection whose transmittance is estimated by ratio tracking.
 */
#ifndef vtkReferencePathTracer_h
#define vtkReferencePathTracer_h

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
// Everything a path needs.
struct Scene
{
  Medium M;
  std::vector<Light> Lights;
  Vec3 Background = Vec3(0.0);
  // Environment map (linear RGB, row major, bottom row first).
  std::vector<double> Env;
  int EnvW = 0, EnvH = 0;
  double EnvUp[3] = { 0, 1, 0 }, EnvRight[3] = { 1, 0, 0 }; // world
  int MaxDepth = -1;
  int RouletteDepth = 8;
  int MaxVertices = 100000;
  Tracer T;      // view rays (no light spheres)
  Tracer TLight; // scattered rays (light spheres tested)

  // Background radiance seen along the grid-local direction dLocal: the environment map when one
  // is set, else the uniform background colour.
  Vec3 BackgroundRadiance(const Vec3& dLocal) const;

  // Radiance arriving from lights along a ray that left the box at x with direction d
  // (straight from here on): the first light sphere in the way, else every directional disc
  // containing d.
  Vec3 EscapedLightRadiance(const Vec3& x, const Vec3& d) const;

  // Light arriving at x (inside the box) along the curved ray leaving x in direction w, times the
  // transmittance to the light, estimated by ratio tracking (the tentative-collision weights
  // (1 - sigma_t / majorant) multiply; Russian roulette once the weight is small). Only the
  // channel `ch` matters for the transmittance (all three when grey).
  Vec3 Connect(const Vec3& x, const Vec3& w, int ch, Rng& rng, bool& truncated) const;

  // One path from a view ray. channel < 0: grey medium, RGB carried together; else only that
  // channel is estimated (returned in that component). `truncated` is set when the path hit a
  // safety limit.
  //
  // At every scattering vertex the light that reaches the vertex without a further collision is
  // estimated by one connection ray whose direction is drawn from the one-sample MIS mixture
  // 0.5 HG + 0.5 (cone of a uniformly chosen light), weighted HG / mixture, its transmittance by
  // ratio tracking; the path itself continues in an HG direction and only its later collisions
  // contribute (light it reaches unscattered was already counted by the connection).
  Vec3 Trace(Vec3 origin, Vec3 dir, int channel, Rng& rng, bool& truncated) const;
};
} // namespace reference
} // namespace refracta

#endif
