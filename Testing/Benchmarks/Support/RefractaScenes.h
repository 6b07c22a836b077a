/**
 * @file    RefractaScenes.h
 * @brief   Procedural benchmark and test scenes: media built voxel by voxel (no meshes needed),
 *          with the light and camera each scene is meant to be seen with.
 *
 * Every scene lives in the unit cube [0, 1]^3 sampled at n^3 voxel centres (spacing 1 / n, origin
 * at half a voxel) and carries every medium array, RefractiveIndexGradient included (central
 * differences), so it can go straight into any pass or the reference renderer.
 *
 * - GlassSphereInFog: n = 1.5 sphere (radius 0.25, boundary smoothed by tanh over ~1.5 voxels) in
 *   a thin scattering fog, lit by a spot light from above: the sphere focuses a caustic below it.
 * - HeterogeneousCloud: a scattering cloud with smooth procedural density (sigma_t up to 12,
 *   albedo 0.95, g = 0.6), lit by a directional light.
 * - GrinLens: a gradient-index cylinder along z with n(r) = 1.6 (1 - 0.5 A r^2), in a faint fog,
 *   lit by a directional light along z: parallel rays converge without any sharp interface.
 *
 * Each scene names a region of interest (a world box) where its characteristic effect shows: the
 * caustic below the sphere, the lit core of the cloud, the converging beam leaving the lens, the
 * glowing dense cube.
 * - DenseObject: a cube of sigma_t = 60 with albedo 0.99 in vacuum, lit by a point light: optical
 *   depth 24 across, where multiple scattering dominates.
 */
#ifndef RefractaScenes_h
#define RefractaScenes_h

#include "vtkSmartPointer.h"

#include <string>
#include <vector>

class vtkCamera;
class vtkImageData;
class vtkLight;
class vtkPolyData;

namespace refracta
{
namespace scenes
{
struct Scene
{
  std::string Name;
  vtkSmartPointer<vtkImageData> Medium;
  std::vector<vtkSmartPointer<vtkLight>> Lights;
  vtkSmartPointer<vtkCamera> Camera;
  double Background[3] = { 0.0, 0.0, 0.0 };
  /** World box (xmin, xmax, ymin, ymax, zmin, zmax) holding the scene's feature of interest. */
  double RegionOfInterest[6] = { 0.0, 1.0, 0.0, 1.0, 0.0, 1.0 };
  /**
   * Extent of the lights, for both the pipeline and the reference renderer: radius of point and
   * spot lights (world units) and angular radius of directional lights (degrees). Refracted
   * light from a delta light reaches a point along isolated paths that unbiased Monte Carlo
   * almost never finds; a light of some size makes the reference converge.
   */
  double LightRadius = 0.0;
  double LightAngularRadius = 0.5;
  /** What that region holds (e.g. "caustic"). */
  std::string RegionName = "whole medium";
};

Scene GlassSphereInFog(int n);
Scene HeterogeneousCloud(int n);
Scene GrinLens(int n);
Scene DenseObject(int n);

/**
 * A point light (radius 0.02) at the centre of a homogeneous fog (sigma_t 4, albedo 0.95/0.95/0.9,
 * optical radius 2): the concentrated source that draws the lattice's ray effects (issue 14).
 */
Scene LampInFog(int n);

/** All four scenes at resolution n. */
std::vector<Scene> AllScenes(int n);

/** Scenes run only when named (BenchmarkAccuracyTime --scenes): LampInFog. */
std::vector<Scene> ExtraScenes(int n);

/**
 * The illumination-network paper's particle cloud (papers/002): n particles uniformly in the unit
 * ball, radius n^(-1/3) (volume fraction 1), extinction such that the cloud has 20 collisions
 * across its diameter, albedo 0.9, g 0 (the arrays of vtkRefractaParticleMedium). Seeded.
 */
vtkSmartPointer<vtkPolyData> ParticleCloud(int n);

/**
 * How the particle cloud is seen and lit in the benchmark and the test that render it: a delta
 * directional light travelling along `ParticleLightTravel` (intensity 1) and a camera at distance
 * ~4 (view angle 36). No medium (the caller deposits the particles).
 */
Scene ParticleCloudView();
extern const double ParticleLightTravel[3];

/** Recompute RefractiveIndexGradient of a medium by central differences (world units). */
void ComputeIndexGradient(vtkImageData* medium);
}
}

#endif
