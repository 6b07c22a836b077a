// Benchmark of vtkMeshVoxelizer: a ~100k-triangle deformed sphere (star-shaped, so it cannot
// self-intersect) voxelized into 128^3 and 256^3. Prints, per grid, the median time of each stage
// (validation, inside test, supersampling, materials, smoothing, gradient) over several runs, the
// number of supersampled voxels, the volume error against the mesh's exact volume, and the peak
// resident memory; at the smallest grid it also runs full supersampling (every voxel) to measure
// the near-surface optimisation's gain in the same run. Writes the table as CSV.
//
// Usage: BenchmarkVoxelize [--sizes 128,256] [--runs 3] [--theta 316] [--phi 160]
//                          [--csv voxelize_benchmark.csv] [--no-full]
#include "RefractaBenchmark.h"

#include "vtkImageData.h"
#include "vtkMassProperties.h"
#include "vtkMediumMaterial.h"
#include "vtkMeshVoxelizer.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

namespace
{
// Radially displaced sphere: r = R (1 + 0.1 sin(5 nx) cos(4 ny) sin(3 nz + 1)).
vtkSmartPointer<vtkPolyData> MakeMesh(int theta, int phi)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(1.0);
  sphere->SetThetaResolution(theta);
  sphere->SetPhiResolution(phi);
  sphere->Update();
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->DeepCopy(sphere->GetOutput());
  vtkPoints* points = mesh->GetPoints();
  for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
  {
    double p[3];
    points->GetPoint(i, p);
    const double r = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    const double n[3] = { p[0] / r, p[1] / r, p[2] / r };
    const double f = 1.0 + 0.1 * std::sin(5 * n[0]) * std::cos(4 * n[1]) * std::sin(3 * n[2] + 1);
    points->SetPoint(i, f * p[0], f * p[1], f * p[2]);
  }
  return mesh;
}
} // namespace

int main(int argc, char* argv[])
{
  std::vector<int> sizes = { 128, 256 };
  int runs = 3, theta = 316, phi = 160;
  bool full = true;
  std::string csv = "voxelize_benchmark.csv";
  for (int a = 1; a < argc; ++a)
  {
    const std::string arg = argv[a];
    auto next = [&]() { return a + 1 < argc ? std::string(argv[++a]) : std::string(); };
    if (arg == "--sizes")
      sizes = refracta::bench::ParseIntList(next());
    else if (arg == "--runs")
      runs = std::max(1, std::atoi(next().c_str()));
    else if (arg == "--theta")
      theta = std::atoi(next().c_str());
    else if (arg == "--phi")
      phi = std::atoi(next().c_str());
    else if (arg == "--csv")
      csv = next();
    else if (arg == "--no-full")
      full = false;
    else
    {
      std::cerr << "unknown argument " << arg << "\n";
      return 2;
    }
  }

  auto mesh = MakeMesh(theta, phi);
  vtkNew<vtkMassProperties> mass;
  mass->SetInputData(mesh);
  mass->Update();
  const double meshVolume = mass->GetVolume();
  std::cout << "mesh: " << mesh->GetNumberOfPolys() << " triangles, " << mesh->GetNumberOfPoints()
            << " points, volume " << meshVolume << "; SMP backend " << vtkSMPTools::GetBackend()
            << ", " << vtkSMPTools::GetEstimatedNumberOfThreads() << " threads; median of " << runs
            << " runs\n";

  vtkNew<vtkMediumMaterial> glass;
  glass->SetRefractiveIndex(1.5);
  glass->SetExtinction(0.1, 0.2, 0.3);
  glass->SetAlbedo(0.9, 0.9, 0.9);

  std::vector<std::string> columns = { "grid", "supersampling" };
  for (int s = 0; s < vtkMeshVoxelizer::NUMBER_OF_STAGES; ++s)
  {
    columns.push_back(std::string(vtkMeshVoxelizer::GetStageName(s)) + "_s");
  }
  for (const char* c : { "total_s", "supersampled_voxels", "volume_rel_err", "output_MiB",
         "peak_MiB", "time_vs_near_surface", "supersampling_vs_near_surface" })
  {
    columns.push_back(c);
  }
  refracta::bench::Table table(columns);

  for (size_t si = 0; si < sizes.size(); ++si)
  {
    const int n = sizes[si];
    double surfaceTotal = 0.0, surfaceSuper = 0.0;
    for (int mode = 0; mode < 2; ++mode)
    {
      const bool surfaceOnly = mode == 0;
      if (!surfaceOnly && !(full && si == 0))
      {
        continue; // full supersampling only at the smallest grid (it is the slow reference)
      }
      std::vector<std::vector<double>> stageTimes(vtkMeshVoxelizer::NUMBER_OF_STAGES);
      std::vector<double> totals;
      vtkIdType supersampled = 0;
      double volumeError = 0.0, outputMiB = 0.0;
      for (int r = 0; r < runs; ++r)
      {
        vtkNew<vtkMeshVoxelizer> vox;
        vox->AddInputData(mesh);
        vox->SetMaterial(0, glass);
        vox->SetDimensions(n, n, n);
        vox->SetPadding(0.1);
        vox->SetSupersampleSurfaceOnly(surfaceOnly);
        const auto t0 = std::chrono::steady_clock::now();
        vox->Update();
        totals.push_back(
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        for (int s = 0; s < vtkMeshVoxelizer::NUMBER_OF_STAGES; ++s)
        {
          stageTimes[s].push_back(vox->GetStageTime(s));
        }
        supersampled = vox->GetNumberOfSupersampledVoxels();
        vtkImageData* out = vox->GetOutput();
        if (out->GetNumberOfPoints() == 0)
        {
          std::cerr << "voxelization failed\n";
          return 1;
        }
        auto* occ = out->GetPointData()->GetArray("Occupancy");
        double sum = 0.0;
        for (vtkIdType v = 0; v < occ->GetNumberOfTuples(); ++v)
        {
          sum += occ->GetTuple1(v);
        }
        const double* sp = out->GetSpacing();
        volumeError = sum * sp[0] * sp[1] * sp[2] / meshVolume - 1.0;
        outputMiB = out->GetActualMemorySize() / 1024.0;
      }
      const double total = refracta::bench::Median(totals);
      const double super =
        refracta::bench::Median(stageTimes[vtkMeshVoxelizer::STAGE_SUPERSAMPLING]);
      if (surfaceOnly)
      {
        surfaceTotal = total;
        surfaceSuper = super;
      }
      std::vector<std::string> row = { std::to_string(n) + "^3",
        surfaceOnly ? "near-surface" : "every voxel" };
      for (int s = 0; s < vtkMeshVoxelizer::NUMBER_OF_STAGES; ++s)
      {
        row.push_back(refracta::bench::Table::Format(refracta::bench::Median(stageTimes[s])));
      }
      row.push_back(refracta::bench::Table::Format(total));
      row.push_back(std::to_string(supersampled));
      row.push_back(refracta::bench::Table::Format(volumeError));
      row.push_back(refracta::bench::Table::Format(outputMiB));
      row.push_back(refracta::bench::Table::Format(refracta::bench::PeakMemoryMiB()));
      row.push_back(surfaceOnly ? "1" : refracta::bench::Table::Format(total / surfaceTotal));
      row.push_back(surfaceOnly ? "1" : refracta::bench::Table::Format(super / surfaceSuper));
      table.AddRow(row);
    }
  }
  table.Print("vtkMeshVoxelizer, " + std::to_string(mesh->GetNumberOfPolys()) +
    "-triangle mesh (median seconds per stage; *_vs_near_surface: this row / the near-surface "
    "row)");
  if (!table.WriteCsv(csv))
  {
    std::cerr << "could not write " << csv << "\n";
    return 1;
  }
  std::cout << "CSV: " << csv << "\n";
  return 0;
}
