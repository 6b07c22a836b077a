// photon_environment.cl: photons emitted by the environment (the sky lights the scene).
// Appended after photon_generate.cl (R2 constants, photon_unit_disc) in the photon program.
//
// photon_generate_environment: one work-item per photon of the environment. Photon i takes point
// i of the rotated R2 lattice, (xi1, xi2), and inverts the host's luminance x solid-angle CDFs:
// xi2 picks the row (marginal) and xi1 the texel within it (that row's conditional CDF); what is
// left of each number inside its bin places the direction in the texel, uniformly in solid angle
// (u uniform, sin(latitude) uniform). So pdf(w) = luminance(texel) / S, S = sum over texels of
// luminance x solid angle. The direction to the sky w = x right + y up + z front with
// y = sin(latitude), (x, z) = cos(latitude) (sin, cos)(2 pi (u - 1/2)) (vtkRefractaEnvironmentMap);
// the photon travels along -w from a uniform point of the disc of radius R perpendicular to w,
// centred at centre + R w, which covers the emission sphere (centre, R). Its power is
// L(texel) pi R^2 / (N pdf) = L(texel) x powerScale / luminance(texel), powerScale =
// pi R^2 S / N in device units (texels[k].w holds the luminance). Then, as photon_generate, it
// starts where it enters the box, or carries power 0 (missed) when it does not meet the box.

// The first index k of the non-decreasing cdf[0 .. n-1] with cdf[k] > xi (n - 1 at most):
// bins of zero weight (cdf[k] == cdf[k - 1]) are never chosen.
inline uint photon_environment_search(__global const float* cdf, uint n, float xi)
{
  uint lo = 0u;
  uint hi = n - 1u;
  while (lo < hi)
  {
    const uint mid = (lo + hi) / 2u;
    if (cdf[mid] > xi)
    {
      hi = mid;
    }
    else
    {
      lo = mid + 1u;
    }
  }
  return lo;
}

// Where xi lies inside bin k of cdf, in [0, 1].
inline float photon_environment_remainder(__global const float* cdf, uint k, float xi)
{
  const float below = k > 0u ? cdf[k - 1u] : 0.0f;
  return clamp((xi - below) / fmax(cdf[k] - below, 1e-30f), 0.0f, 1.0f);
}

__kernel void photon_generate_environment(__global float4* photonPos, __global float4* photonDir,
  __global float4* photonPower, const uint offset, const uint count,
  __global const float4* texels, __global const float* marginal,
  __global const float* conditional, const int width, const int height, const float4 right,
  const float4 up, const float4 front, const float4 sphere, const float powerScale,
  const float4 boxLo, const float4 boxHi, const uint rotation1, const uint rotation2,
  const float lobe)
{
  const uint i = (uint)get_global_id(0);
  if (i >= count)
  {
    return;
  }
  const float xi1 = (float)((rotation1 + (i + 1u) * PHOTON_R2_A1) >> 8) * (1.0f / 16777216.0f);
  const float xi2 = (float)((rotation2 + (i + 1u) * PHOTON_R2_A2) >> 8) * (1.0f / 16777216.0f);
  const uint row = photon_environment_search(marginal, (uint)height, xi2);
  const float fv = photon_environment_remainder(marginal, row, xi2);
  __global const float* rowCdf = conditional + (size_t)row * (uint)width;
  const uint col = photon_environment_search(rowCdf, (uint)width, xi1);
  const float fu = photon_environment_remainder(rowCdf, col, xi1);

  // sin(latitude) at the row's edges: latitude = pi (v - 1/2), so sin = -cos(pi v).
  const float s0 = -cospi((float)row / (float)height);
  const float s1 = -cospi((float)(row + 1u) / (float)height);
  const float y = mix(s0, s1, fv);
  const float rxz = sqrt(fmax(0.0f, 1.0f - y * y));
  const float azimuth = 2.0f * REFRACTA_PI * (((float)col + fu) / (float)width - 0.5f);
  const float3 toSky =
    normalize(rxz * sin(azimuth) * right.xyz + y * up.xyz + rxz * cos(azimuth) * front.xyz);
  const float3 dir = -toSky;

  const float2 q = sphere.w * photon_unit_disc(rotation1 ^ rotation2, i);
  const float3 helper =
    fabs(dir.x) < 0.9f ? (float3)(1.0f, 0.0f, 0.0f) : (float3)(0.0f, 1.0f, 0.0f);
  const float3 e1 = normalize(cross(dir, helper));
  float3 start = sphere.xyz + sphere.w * toSky + q.x * e1 + q.y * cross(dir, e1);

  const float4 texel = texels[(size_t)row * (uint)width + col];
  float3 power = texel.w > 0.0f ? texel.xyz * (powerScale / texel.w) : (float3)(0.0f);
  float t0;
  float t1;
  if (refracta_intersect_box(start, dir, boxLo.xyz, boxHi.xyz, &t0, &t1) && t1 > t0 && t0 >= 0.0f)
  {
    start += t0 * dir;
  }
  else
  {
    power = (float3)(0.0f);
  }
  const uint o = offset + i;
  photonPos[o] = (float4)(start, 0.0f);
  photonDir[o] = (float4)(dir, 0.0f);
  photonPower[o] = (float4)(power, lobe); // w: S1's lobe of the photon (photon_trace.cl)
}
