// What the progress and abort tests share (RefractaTransport.ProgressAbort and
// RefractaRendering.ImageRendererProgress): an observer that records ProgressEvent values and
// aborts its algorithm at the first value above a threshold, and the check that a run's progress
// is monotone, within [0, 1], ends at 1 and has at least 8 distinct values.
#ifndef ProgressTestUtilities_h
#define ProgressTestUtilities_h

#include "vtkAlgorithm.h"
#include "vtkCommand.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <set>
#include <vector>

namespace refracta_test
{
using Clock = std::chrono::steady_clock;

// Records the progress values; calls AbortExecuteOn() at the first value above AbortAbove.
class ProgressLog : public vtkCommand
{
public:
  static ProgressLog* New() { return new ProgressLog; }
  void Execute(vtkObject* caller, unsigned long, void* data) override
  {
    const double p = *static_cast<double*>(data);
    this->Values.push_back(p);
    if (!this->Aborted && p > this->AbortAbove)
    {
      this->Aborted = true;
      this->AbortTime = Clock::now();
      static_cast<vtkAlgorithm*>(caller)->AbortExecuteOn();
    }
  }
  void Reset(double abortAbove)
  {
    this->Values.clear();
    this->Aborted = false;
    this->AbortAbove = abortAbove;
  }
  std::vector<double> Values;
  double AbortAbove = 2.0; // > 1: never abort
  bool Aborted = false;
  Clock::time_point AbortTime;
};

inline void ExpectGoodProgress(const std::vector<double>& values, const char* what)
{
  ASSERT_FALSE(values.empty()) << what;
  std::set<double> distinct;
  for (size_t i = 0; i < values.size(); ++i)
  {
    EXPECT_GE(values[i], 0.0) << what;
    EXPECT_LE(values[i], 1.0) << what;
    if (i > 0)
    {
      EXPECT_GE(values[i], values[i - 1]) << what << ": progress went back at event " << i;
    }
    distinct.insert(values[i]);
  }
  EXPECT_EQ(values.back(), 1.0) << what;
  EXPECT_GE(distinct.size(), 8u) << what;
  std::printf(
    "%s: %zu progress events, %zu distinct values\n", what, values.size(), distinct.size());
}
}

#endif
