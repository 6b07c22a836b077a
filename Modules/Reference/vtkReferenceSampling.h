/**
 * Internal to RefractaReference (a private header: not wrapped, not installed). Random numbers
 * and the directions the reference path tracer draws: the per pixel random stream, the
 * Henyey-Greenstein phase function and its sampling, and uniform cones towards lights.
 */
#ifndef vtkReferenceSampling_h
#define vtkReferenceSampling_h

#include "vtkReferenceMath.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace refracta
{
namespace reference
{
/// SplitMix64's finaliser.
inline uint64_t Mix64(uint64_t z)
{
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

/// SplitMix64 stream per pixel (each pixel's stream seeded from the seed and the pixel index
/// through the same mixer), 53-bit uniform doubles in [0, 1).
struct Rng
{
  uint64_t State;
  Rng(uint64_t seed, uint64_t stream)
    : State(Mix64(Mix64(seed + 0x9e3779b97f4a7c15ULL) ^ (stream * 0xd1b54a32d192ed03ULL)))
  {
  }
  double Uniform()
  {
    this->State += 0x9e3779b97f4a7c15ULL;
    return static_cast<double>(Mix64(this->State) >> 11) * (1.0 / 9007199254740992.0);
  }
};

/// Henyey-Greenstein phase function (per steradian) of 1 - cos theta.
inline double HGPhase(double g, double oneMinusCos)
{
  // (1 + g^2 - 2 g c) written as a sum of non-negative terms (see refracta_common.cl).
  const double omc = std::min(std::max(oneMinusCos, 0.0), 2.0);
  const double denom =
    g >= 0 ? (1 - g) * (1 - g) + 2 * g * omc : (1 + g) * (1 + g) - 2 * g * (2.0 - omc);
  const double d = std::max(denom, 1e-300);
  return (1 - g) * (1 + g) / (4 * Pi * d * std::sqrt(d));
}

/// A direction drawn from HG around the unit travel direction `in` with the uniform numbers u1
/// (for cos theta) and u2 (for the azimuth).
inline Vec3 SampleHG(double g, const Vec3& in, double u1, double u2)
{
  double cosT, sinT;
  if (std::abs(g) < 1e-5)
  {
    cosT = 1 - 2 * u1;
    sinT = std::sqrt(std::max(0.0, 1 - cosT * cosT));
  }
  else
  {
    // Inverse CDF: 1 - cos = (s^2 - (1-g)^2) / (2g) with s = (1 - g^2) / (1 - g + 2 g u1); the
    // factored form (s - 1 + g)(s + 1 - g) keeps precision when the distribution is sharply
    // peaked.
    const double s = (1 - g * g) / (1 - g + 2 * g * u1);
    double omc = (s - 1 + g) * (s + 1 - g) / (2 * g);
    omc = std::min(std::max(omc, 0.0), 2.0);
    cosT = 1 - omc;
    sinT = std::sqrt(std::max(0.0, omc * (2 - omc)));
  }
  const double phi = 2 * Pi * u2;
  Vec3 t, b;
  Basis(in, t, b);
  return Normalized((sinT * std::cos(phi)) * t + (sinT * std::sin(phi)) * b + cosT * in);
}

/// Uniform direction in the cone of half-angle theta_max around `axis`; omcMax = 1 -
/// cos(theta_max).
inline Vec3 SampleCone(const Vec3& axis, double omcMax, double u1, double u2)
{
  const double omc = u1 * omcMax;
  const double cosT = 1 - omc;
  const double sinT = std::sqrt(std::max(0.0, omc * (2 - omc)));
  const double phi = 2 * Pi * u2;
  Vec3 t, b;
  Basis(axis, t, b);
  return Normalized((sinT * std::cos(phi)) * t + (sinT * std::sin(phi)) * b + cosT * axis);
}
/// Cosine-weighted direction about the unit normal n (pdf cos / pi).
inline Vec3 SampleCosine(const Vec3& n, double u1, double u2)
{
  const double r = std::sqrt(u1), phi = 2 * Pi * u2;
  Vec3 t, b;
  Basis(n, t, b);
  return Normalized(
    (r * std::cos(phi)) * t + (r * std::sin(phi)) * b + std::sqrt(std::max(0.0, 1 - u1)) * n);
}
} // namespace reference
} // namespace refracta

#endif
