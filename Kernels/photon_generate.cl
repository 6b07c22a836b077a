// photon_generate.cl: photon generation from lights (Sun et al. 2008, section 4.3). Appended
// after photon_trace.cl (refracta_common.cl's random numbers) in the photon program.
//
// photon_generate: one work-item per photon of one light. Photon i takes point i of a 2D
// rank-1 lattice (Roberts' R2 sequence in 32-bit fixed point, rotated by a seed-derived offset:
// low-discrepancy, deterministic) and maps it onto the light's footprint on the proxy box; it is
// written to slot offset + w, where photonStream[offset + w] = offset + i (the host's order):
//   directional light: a rectangle perpendicular to the travel direction covering the box's
//     projection; photon power = E * (rectangle area) / N;
//   point/spot light: a spherical cap of directions (the narrower of the cone around the box's
//     bounding sphere and the cone towards its centre through its farthest corner, or the spot
//     cone when that is narrower, or the whole sphere when the light is inside the box);
//     photon power = I(direction) * (cap solid angle) / N, with I = I0 cos^e(theta) inside a
//     spot's cone and 0 outside.
// Extended lights (extent > 0): a directional light's direction is tilted uniformly over the
// projected disc of angular radius asin(extent); a point/spot light's start is moved uniformly over
// the disc of radius extent through the light, perpendicular to the photon's direction.
// The photon then starts where its ray enters the proxy box (or at the light when the light is
// inside it). A photon that misses the box gets power 0 and is counted as missed by the marcher.

// R2 sequence generators (plastic number) as 32-bit fractions.
#define PHOTON_R2_A1 3242174889u
#define PHOTON_R2_A2 2447445413u

// A uniform point of the unit disc for photon i (its own random stream).
inline float2 photon_unit_disc(uint seed, uint i)
{
  uint state = refracta_rng_seed(seed, i);
  const float r = sqrt(refracta_rng_uniform(&state));
  const float phi = 2.0f * REFRACTA_PI * refracta_rng_uniform(&state);
  return (float2)(r * cos(phi), r * sin(phi));
}

__kernel void photon_generate(__global float4* photonPos, __global float4* photonDir,
  __global float4* photonPower, __global const uint* photonStream, const uint offset,
  const uint count, const int positional,
  const float4 origin, const float4 axis, const float4 basis1, const float4 basis2,
  const float4 spot, const float4 params, const float4 intensity, const float4 boxLo,
  const float4 boxHi, const uint rotation1, const uint rotation2, const float extent,
  const float lead, const float lobe)
{
  const uint w = (uint)get_global_id(0);
  if (w >= count)
  {
    return;
  }
  // Slot offset + w holds lattice point i: the host orders a light's points so that neighbouring
  // slots start close together (vtkPhotonTracer, CoherentPhotonOrder); the point's random stream
  // is offset + i wherever it is marched.
  const uint o = offset + w;
  const uint i = photonStream[o] - offset;
  const float xi1 = (float)((rotation1 + (i + 1u) * PHOTON_R2_A1) >> 8) * (1.0f / 16777216.0f);
  const float xi2 = (float)((rotation2 + (i + 1u) * PHOTON_R2_A2) >> 8) * (1.0f / 16777216.0f);
  float3 start;
  float3 dir;
  float3 power;
  if (!positional)
  {
    // basis1/basis2 carry the rectangle's full edge vectors.
    start = origin.xyz + xi1 * basis1.xyz + xi2 * basis2.xyz;
    dir = axis.xyz;
    if (extent > 0.0f)
    {
      // A disc at infinity of angular radius asin(extent): uniform on its projected disc, i.e.
      // pdf proportional to cos, which keeps the irradiance on a facing plane equal to E.
      const float2 q = extent * photon_unit_disc(rotation1 ^ rotation2, i);
      dir = normalize(sqrt(fmax(0.0f, 1.0f - dot(q, q))) * axis.xyz +
        q.x * normalize(basis1.xyz) + q.y * normalize(basis2.xyz));
    }
    power = intensity.xyz * params.z;
  }
  else
  {
    // params.w = 1 - cos(cap half-angle), computed in double on the host: the cap of a distant
    // light is tiny and 1 - cos would cancel in float.
    const float oneMinusCos = xi1 * params.w;
    const float cosT = 1.0f - oneMinusCos;
    const float sinT = sqrt(fmax(0.0f, oneMinusCos * (2.0f - oneMinusCos)));
    const float phi = 2.0f * REFRACTA_PI * xi2;
    const float3 across = cos(phi) * basis1.xyz + sin(phi) * basis2.xyz;
    dir = normalize(cosT * axis.xyz + sinT * across);
    // A distant light starts its photons `lead` along their rays, short of the box's bounding
    // sphere: origin + lead axis comes from the host in double, and lead (dir - axis) is formed
    // from 1 - cos and sin, which keep their precision, so a light 1e8 away still meets a box
    // of size 1 (from the light's own float position the box was lost in rounding).
    start = origin.xyz + lead * (sinT * across - oneMinusCos * axis.xyz);
    if (extent > 0.0f)
    {
      // A sphere of radius `extent`: rays in direction dir leave it uniformly over its projected
      // disc (radiance I(dir) / (pi r^2)), so start on that disc through the centre.
      const float2 q = extent * photon_unit_disc(rotation1 ^ rotation2, i);
      const float3 helper = fabs(dir.x) < 0.9f ? (float3)(1.0f, 0.0f, 0.0f) : (float3)(0.0f, 1.0f, 0.0f);
      const float3 e1 = normalize(cross(dir, helper));
      start += q.x * e1 + q.y * cross(dir, e1);
    }
    float falloff = 1.0f;
    if (spot.w > -1.5f)
    {
      const float c = dot(dir, spot.xyz);
      falloff = c >= spot.w ? (params.y > 0.0f ? pow(fmax(c, 0.0f), params.y) : 1.0f) : 0.0f;
    }
    power = intensity.xyz * (falloff * params.z);
  }
  float t0;
  float t1;
  const bool inside = all(start >= boxLo.xyz) && all(start <= boxHi.xyz);
  if (!inside)
  {
    if (refracta_intersect_box(start, dir, boxLo.xyz, boxHi.xyz, &t0, &t1) && t1 > t0)
    {
      start += t0 * dir;
    }
    else
    {
      power = (float3)(0.0f);
    }
  }
  photonPos[o] = (float4)(start, 0.0f);
  photonDir[o] = (float4)(dir, 0.0f);
  photonPower[o] = (float4)(power, lobe); // w: S1's lobe of the photon (photon_trace.cl)
}
