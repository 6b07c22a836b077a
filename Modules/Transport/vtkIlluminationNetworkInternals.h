// Host-side geometry of vtkIlluminationNetwork (vtkIlluminationNetworkGeometry.cxx): the particle
// arrays, the sample directions and their rotation, the line bundles that give the visibility
// network and the attenuation of the direct light, the phase matrices and the E array.
#ifndef vtkIlluminationNetworkInternals_h
#define vtkIlluminationNetworkInternals_h

#include "vtkType.h"

#include <array>
#include <string>
#include <vector>

class vtkPointSet;

namespace vtkIlluminationNetworkGeometry
{
/** The particles' positions and per-particle coefficients in the layouts the kernels read. */
struct Particles
{
  vtkIdType N = 0;
  std::vector<double> Position;  // 3N
  std::vector<double> Radius;    // N
  std::vector<float> Opacity;    // 3N, alpha = 1 - exp(-sigma_t 4 r / 3)
  std::vector<float> Albedo;     // 3N
  std::vector<float> Anisotropy; // N
  std::vector<float> Emission;   // 3N, Le * 4 r / 3 (radiance added along every line)
  double Center[3] = { 0, 0, 0 };
  double BoundingRadius = 0;
  double MeanRadius = 0;
};

/** Reads a validated particle set (vtkRefractaParticleMedium::Validate) into `out`. */
void ReadParticles(vtkPointSet* input, Particles& out);

/** D directions of a spherical Fibonacci set, unit vectors, 3D doubles. */
std::vector<double> FibonacciDirections(int d);

/** A uniformly random rotation (row-major 3x3) for rotation number `index` of stream `seed`. */
std::array<double, 9> RandomRotation(unsigned int seed, unsigned int index);

/** The directions turned by a rotation. */
std::vector<double> Rotate(const std::vector<double>& directions, const std::array<double, 9>& r);

/**
 * The visibility network: visible[p * D + i] is the particle before p on its line of direction i
 * (the one light travelling along omega_i reaches p from), or -1; hasNext[q * D + i] is 1 where a
 * particle follows q on that line. Lines are pixels of side `pixel` on the plane perpendicular to
 * omega_i.
 */
void BuildVisibility(const Particles& particles, const std::vector<double>& directions,
  double pixel, std::vector<int>& visible, std::vector<unsigned char>& hasNext);

/**
 * Phase classes: particles with equal g share one D x D matrix; more than 64 distinct values are
 * quantised to 64 levels of g. phase[(k * D + d) * D + i] = P(omega_d . omega_i) normalised so that
 * each row sums to 1.
 */
void BuildPhase(const Particles& particles, const std::vector<double>& directions,
  std::vector<int>& phaseClass, std::vector<float>& phase);

/** One light, as vtkIlluminationNetwork describes it. */
struct Light
{
  int Type = 0; // vtkIlluminationNetwork::LightTypes
  double Position[3] = { 0, 0, 0 };
  double Direction[3] = { 0, 0, -1 };
  double Intensity[3] = { 0, 0, 0 };
};

/**
 * Irradiance of the light at each particle (3N), attenuated by the particles in front of it along
 * a line bundle from the light, and the unit direction the light travels at each particle (3N).
 */
void DirectIrradiance(const Particles& particles, const Light& light, double pixel,
  std::vector<double>& irradiance, std::vector<double>& travel);

/**
 * The E array (N x D x 3): emission plus the reflection of the direct light from the sample
 * direction closest to the light's travel direction, as in the paper.
 */
void BuildEmitted(const Particles& particles, const std::vector<double>& directions,
  const std::vector<int>& phaseClass, const std::vector<float>& phase,
  const std::vector<double>& irradiance, const std::vector<double>& travel,
  std::vector<float>& emitted);

/** For each direction of `to`, the index of the closest direction of `from`. */
std::vector<int> NearestDirections(const std::vector<double>& from, const std::vector<double>& to);
}

#endif
// VTK-HeaderTest-Exclude: vtkIlluminationNetworkInternals.h
