#include "vtkReferencePhotonMapper.h"

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkReferencePhotonMap.h"
#include "vtkReferenceView.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <vector>

vtkStandardNewMacro(vtkReferencePhotonMapper);

namespace
{
using refracta::reference::Medium;
using refracta::reference::Mix64;
using refracta::reference::Photon;
using refracta::reference::PhotonGrid;
using refracta::reference::PhotonScene;
using refracta::reference::Rng;
using refracta::reference::Scene;
using refracta::reference::Vec3;
using refracta::reference::View;

constexpr int PhotonBlock = 4096; // photons per parallel work item (fixed: determinism)

// Seed of pass `pass`'s photon streams (kind 0) or view streams (kind 1).
uint64_t PassSeed(uint64_t seed, int pass, int kind)
{
  return Mix64(seed ^ Mix64(0x5350504dULL + 2 * static_cast<uint64_t>(pass) + kind));
}

// Per pixel and channel mean over the passes, and the standard error from the spread of the
// stream means (-1 with fewer than 2 streams).
void Estimate(const std::vector<std::vector<double>>& streamSum, const std::vector<int>& count,
  std::vector<double>& mean, std::vector<double>& stderrs)
{
  const size_t n = mean.size();
  int used = 0, total = 0;
  for (int c : count)
  {
    used += c > 0 ? 1 : 0;
    total += c;
  }
  for (size_t v = 0; v < n; ++v)
  {
    double s = 0;
    for (size_t k = 0; k < streamSum.size(); ++k)
    {
      s += streamSum[k][v];
    }
    mean[v] = s / total;
    if (used < 2)
    {
      stderrs[v] = -1;
      continue;
    }
    double var = 0;
    for (size_t k = 0; k < streamSum.size(); ++k)
    {
      if (count[k] > 0)
      {
        const double e = streamSum[k][v] / count[k] - mean[v];
        var += e * e;
      }
    }
    stderrs[v] = std::sqrt(var / (used * (used - 1.0)));
  }
}

// Relative RMS standard error over the pixels whose mean is positive (summed channels).
double RelativeError(const std::vector<double>& mean, const std::vector<double>& stderrs)
{
  double se2 = 0, mu = 0;
  size_t n = 0;
  for (size_t p = 0; p + 2 < mean.size(); p += 3)
  {
    const double m = mean[p] + mean[p + 1] + mean[p + 2];
    if (m > 0 && stderrs[p] >= 0)
    {
      const double e = stderrs[p] + stderrs[p + 1] + stderrs[p + 2];
      se2 += e * e;
      mu += m;
      ++n;
    }
  }
  return n > 0 && mu > 0 ? std::sqrt(se2 / n) / (mu / n) : -1;
}
} // namespace

//------------------------------------------------------------------------------
vtkReferencePhotonMapper::vtkReferencePhotonMapper()
{
  this->SamplesPerPixel = 1;
}

vtkReferencePhotonMapper::~vtkReferencePhotonMapper() = default;

double vtkReferencePhotonMapper::PassRadius(double r1, double alpha, int pass)
{
  // r_i^3 = r_1^3 prod_{j=1}^{i-1} (j + alpha) / (j + 1).
  double r3 = r1 * r1 * r1;
  for (int j = 1; j < pass; ++j)
  {
    r3 *= (j + alpha) / (j + 1);
  }
  return std::cbrt(r3);
}

bool vtkReferencePhotonMapper::CheckSettings()
{
  if (!(this->Alpha >= 0.5 && this->Alpha < 1))
  {
    vtkErrorMacro("Alpha is " << this->Alpha
                              << "; the radius reduction parameter must be in [0.5, 1) (default "
                                 "2/3).");
    return false;
  }
  if (this->Passes < 1)
  {
    vtkErrorMacro("Passes is " << this->Passes << "; it must be >= 1.");
    return false;
  }
  if (this->PhotonsPerPass < 1)
  {
    vtkErrorMacro("PhotonsPerPass is " << this->PhotonsPerPass << "; it must be >= 1.");
    return false;
  }
  if (this->Streams < 1)
  {
    vtkErrorMacro("Streams is " << this->Streams << "; it must be >= 1.");
    return false;
  }
  if (!(this->GatherSpacing >= 0) || !std::isfinite(this->GatherSpacing))
  {
    vtkErrorMacro("GatherSpacing is "
      << this->GatherSpacing
      << "; it must be finite and >= 0 (units of the pass's radius; 0 gathers at the first "
         "real collision only).");
    return false;
  }
  if (!(this->InitialRadius > 0) || !std::isfinite(this->InitialRadius))
  {
    vtkErrorMacro("InitialRadius is "
      << this->InitialRadius
      << "; it must be finite and > 0 (units of the smallest voxel spacing; default 2).");
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
int vtkReferencePhotonMapper::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  const auto start = std::chrono::steady_clock::now();
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  vtkImageData* medium = vtkImageData::GetData(inputVector[0], 0);
  if (!output)
  {
    vtkErrorMacro("No output image.");
    return 0;
  }
  output->Initialize();
  if (!this->CheckSettings())
  {
    return 0;
  }
  Scene scene;
  View view;
  if (!this->BuildScene(medium, scene, view))
  {
    return 0;
  }
  PhotonScene photons;
  photons.S = &scene;
  photons.Bound();
  const Medium& m = scene.M;
  const int W = view.Width, H = view.Height;
  const int64_t numPixels = static_cast<int64_t>(W) * H;
  const int passes = this->Passes, spp = this->SamplesPerPixel;
  const int streams = std::min(this->Streams, passes);
  const int64_t perPass = this->PhotonsPerPass;
  const double r1 = this->InitialRadius * std::min(m.S[0], std::min(m.S[1], m.S[2]));
  const bool grey = m.Grey, jitter = this->PixelJitter;
  const uint64_t seed = this->Seed;

  std::vector<std::vector<double>> streamSum(streams, std::vector<double>(3 * numPixels, 0.0));
  std::vector<int> count(streams, 0);
  std::vector<double> mean(3 * numPixels), stderrs(3 * numPixels);
  std::vector<double> checkPasses, checkSeconds, checkError;
  std::atomic<int64_t> truncated(0), nonFinite(0);
  int64_t stored = 0;
  double radius = r1;
  int nextCheckpoint = streams;
  // Without emitters there is nothing to emit (the image is emission and background only).
  const int64_t blocks = scene.NumEmitters() > 0 ? (perPass + PhotonBlock - 1) / PhotonBlock : 0;
  std::vector<std::vector<Photon>> blockPhotons(blocks);

  int pass = 1;
  for (; pass <= passes && !this->GetAbortExecute(); ++pass)
  {
    radius = PassRadius(r1, this->Alpha, pass);
    const double gatherRate = this->GatherSpacing > 0 ? 1 / (this->GatherSpacing * radius) : 0;
    // Photons, in blocks of fixed size so that the stored order does not depend on threads.
    const uint64_t photonSeed = PassSeed(seed, pass, 0);
    vtkSMPTools::For(0, blocks, 1,
      [&](vtkIdType b0, vtkIdType b1)
      {
        int64_t localTrunc = 0;
        for (vtkIdType b = b0; b < b1; ++b)
        {
          std::vector<Photon>& out = blockPhotons[b];
          out.clear();
          const int64_t p1 = std::min<int64_t>(perPass, (b + 1) * PhotonBlock);
          for (int64_t p = b * PhotonBlock; p < p1; ++p)
          {
            Rng rng(photonSeed, static_cast<uint64_t>(p));
            bool trunc = false;
            photons.EmitAndTrace(rng, static_cast<double>(perPass), out, trunc);
            localTrunc += trunc ? 1 : 0;
          }
        }
        truncated += localTrunc;
      });
    std::vector<Photon> all;
    size_t total = 0;
    for (const auto& b : blockPhotons)
    {
      total += b.size();
    }
    all.reserve(total);
    for (const auto& b : blockPhotons)
    {
      all.insert(all.end(), b.begin(), b.end());
    }
    stored += static_cast<int64_t>(total);
    PhotonGrid grid;
    grid.Build(std::move(all), m.Lo, radius);

    // View rays: one stream per pixel and pass.
    std::vector<double>& sum = streamSum[(pass - 1) % streams];
    const uint64_t viewSeed = PassSeed(seed, pass, 1);
    vtkSMPTools::For(0, numPixels, 16,
      [&](vtkIdType begin, vtkIdType end)
      {
        int64_t localTrunc = 0, localNonFinite = 0;
        for (vtkIdType p = begin; p < end; ++p)
        {
          const int i = static_cast<int>(p % W), j = static_cast<int>(p / W);
          Rng rng(viewSeed, static_cast<uint64_t>(p));
          Vec3 acc(0.0);
          for (int s = 0; s < spp; ++s)
          {
            const double jx = jitter ? rng.Uniform() : 0.5, jy = jitter ? rng.Uniform() : 0.5;
            Vec3 o, d;
            view.Ray(i, j, jx, jy, o, d);
            Vec3 val(0.0);
            bool trunc = false;
            if (grey)
            {
              val = photons.ViewSample(o, d, -1, grid, radius, gatherRate, rng, trunc);
            }
            else
            {
              for (int c = 0; c < 3; ++c)
              {
                val += photons.ViewSample(o, d, c, grid, radius, gatherRate, rng, trunc);
              }
            }
            localTrunc += trunc ? 1 : 0;
            if (!std::isfinite(val.x) || !std::isfinite(val.y) || !std::isfinite(val.z))
            {
              ++localNonFinite;
              val = Vec3(0.0);
            }
            acc += val;
          }
          for (int c = 0; c < 3; ++c)
          {
            sum[3 * p + c] += acc[c] / spp;
          }
        }
        truncated += localTrunc;
        nonFinite += localNonFinite;
      });
    ++count[(pass - 1) % streams];
    if (pass == nextCheckpoint || pass == passes)
    {
      Estimate(streamSum, count, mean, stderrs);
      checkPasses.push_back(pass);
      checkSeconds.push_back(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      checkError.push_back(RelativeError(mean, stderrs));
      while (nextCheckpoint <= pass)
      {
        nextCheckpoint *= 2;
      }
    }
    this->UpdateProgress(static_cast<double>(pass) / passes);
  }
  const int done = pass - 1;
  if (done < 1)
  {
    vtkErrorMacro("Aborted before the first pass finished.");
    return 0;
  }
  Estimate(streamSum, count, mean, stderrs);
  this->WriteImage(output, W, H, mean, stderrs);

  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  AddFieldValue(output, "SamplesPerPixel", spp, true);
  AddFieldValue(output, "Passes", done, true);
  AddFieldValue(output, "PhotonsPerPass", static_cast<double>(perPass), true);
  AddFieldValue(output, "Streams", streams, true);
  AddFieldValue(output, "Alpha", this->Alpha, false);
  AddFieldValue(output, "GatherSpacing", this->GatherSpacing, false);
  AddFieldValue(output, "InitialRadius", r1, false);
  AddFieldValue(output, "FinalRadius", radius, false);
  AddFieldValue(output, "StoredPhotons", static_cast<double>(stored), false);
  AddFieldValue(output, "RenderSeconds", seconds, false);
  AddFieldValue(output, "Seed", static_cast<double>(this->Seed), false);
  AddFieldValue(output, "TruncatedPaths", static_cast<double>(truncated.load()), false);
  AddFieldValue(output, "NonFiniteSamples", static_cast<double>(nonFinite.load()), false);
  AddFieldValue(output, "LightRadius", this->LightRadius, false);
  auto addArray = [output](const char* name, const std::vector<double>& values)
  {
    vtkNew<vtkDoubleArray> a;
    a->SetName(name);
    for (double v : values)
    {
      a->InsertNextValue(v);
    }
    output->GetFieldData()->AddArray(a);
  };
  addArray("CheckpointPasses", checkPasses);
  addArray("CheckpointSeconds", checkSeconds);
  addArray("CheckpointError", checkError);
  return 1;
}

//------------------------------------------------------------------------------
void vtkReferencePhotonMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Passes: " << this->Passes << "\n";
  os << indent << "PhotonsPerPass: " << this->PhotonsPerPass << "\n";
  os << indent << "InitialRadius: " << this->InitialRadius << "\n";
  os << indent << "Alpha: " << this->Alpha << "\n";
  os << indent << "Streams: " << this->Streams << "\n";
  os << indent << "GatherSpacing: " << this->GatherSpacing << "\n";
}
