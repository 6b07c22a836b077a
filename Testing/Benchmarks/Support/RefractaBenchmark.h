/**
 * @file    RefractaBenchmark.h
 * @brief   What every Refracta benchmark program needs: medians of repeated timings, peak memory,
 *          a table printed to stdout and written as CSV, and log-log plots written as PNG.
 *
 * Benchmarks are programs, not tests: they print medians of several runs and ratios measured in
 * the same run. Plots use VTK's charts in an offscreen render window, so they need an X server
 * with Debian's VTK (run the benchmark under `xvfb-run -a`); without one the PNG is skipped with
 * a message and the table and CSV are still written.
 */
#ifndef RefractaBenchmark_h
#define RefractaBenchmark_h

#include <functional>
#include <string>
#include <vector>

namespace refracta
{
namespace bench
{
/** Median of the values (0 for none). */
double Median(std::vector<double> values);

/** Run `work` `repeats` times and return the median wall time in seconds. */
double MedianSeconds(int repeats, const std::function<void()>& work);

/** Peak resident memory of this process so far, in MiB. */
double PeakMemoryMiB();

/** The items of a comma-separated list ("glass-sphere-in-fog,grin-lens"). */
std::vector<std::string> SplitList(const std::string& text);

/** The integers of a comma-separated list ("32,64,96"); an item that is not a number reads 0. */
std::vector<int> ParseIntList(const std::string& text);

/** A table with named columns: printed aligned, written as CSV. */
class Table
{
public:
  explicit Table(std::vector<std::string> columns);
  /** Add a row; values are formatted with up to 4 significant digits unless given as text. */
  void AddRow(const std::vector<std::string>& cells);
  void Print(const std::string& title) const;
  // Writes the table as CSV (a comma inside a cell becomes ';').
  bool WriteCsv(const std::string& path) const;
  /** Format a number for a cell (4 significant digits, or plain for integers). */
  static std::string Format(double value);

private:
  std::vector<std::string> Columns;
  std::vector<std::vector<std::string>> Rows;
};

/** One curve of a plot. */
struct Series
{
  std::string Name;
  std::vector<double> X;
  std::vector<double> Y;
};

/**
 * Write a log-log (or linear) line plot with markers to a PNG. Returns false (and says why on
 * stderr) when it cannot render, e.g. without an X server.
 */
bool WritePlot(const std::string& path, const std::string& title, const std::string& xLabel,
  const std::string& yLabel, const std::vector<Series>& series, bool logX = true, bool logY = true);
}
}

#endif
