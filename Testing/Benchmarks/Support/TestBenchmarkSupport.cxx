// The benchmark helpers compute medians correctly, write a CSV that reads back, and (with an X
// server) write a non-empty PNG plot.
#include "RefractaBenchmark.h"

#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>

int main(int argc, char* argv[])
{
  using namespace refracta::bench;
  const std::string dir = argc > 1 ? argv[1] : ".";
  int failures = 0;
  auto check = [&](bool ok, const char* what)
  {
    if (!ok)
    {
      std::cerr << "FAIL: " << what << "\n";
      ++failures;
    }
  };
  check(Median({ 3, 1, 2 }) == 2, "odd median");
  check(Median({ 4, 1, 3, 2 }) == 2.5, "even median");
  check(Median({}) == 0, "empty median");
  int calls = 0;
  const double seconds = MedianSeconds(5, [&] { ++calls; });
  check(calls == 5 && seconds >= 0, "MedianSeconds runs the work each time");
  check(PeakMemoryMiB() > 1.0, "peak memory is reported");

  Table table({ "photons", "seconds" });
  table.AddRow({ Table::Format(65536), Table::Format(0.012345678) });
  table.Print("smoke");
  const std::string csv = dir + "/benchmark-support.csv";
  check(table.WriteCsv(csv), "CSV written");
  std::ifstream in(csv);
  std::string header, row;
  std::getline(in, header);
  std::getline(in, row);
  check(header == "photons,seconds" && row == "65536,0.01235", "CSV content");

  if (std::getenv("DISPLAY"))
  {
    const std::string png = dir + "/benchmark-support.png";
    std::remove(png.c_str());
    check(
      WritePlot(png, "smoke", "time (s)", "error", { { "a", { 1, 10, 100 }, { 1, 0.1, 0.01 } } }),
      "plot rendered");
    std::ifstream p(png, std::ios::binary | std::ios::ate);
    check(p && p.tellg() > 1000, "PNG written");
  }
  std::cout << (failures ? "benchmark support FAILED" : "benchmark support passed") << "\n";
  return failures ? 1 : 0;
}
