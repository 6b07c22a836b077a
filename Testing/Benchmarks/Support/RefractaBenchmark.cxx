#include "RefractaBenchmark.h"

#include "vtkAxis.h"
#include "vtkChartLegend.h"
#include "vtkChartXY.h"
#include "vtkContextScene.h"
#include "vtkContextView.h"
#include "vtkDoubleArray.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkPen.h"
#include "vtkPlot.h"
#include "vtkPlotPoints.h"
#include "vtkRefractaRenderWindowCheck.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkTable.h"
#include "vtkTextProperty.h"
#include "vtkWindowToImageFilter.h"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace refracta
{
namespace bench
{

double Median(std::vector<double> values)
{
  if (values.empty())
  {
    return 0.0;
  }
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

double MedianSeconds(int repeats, const std::function<void()>& work)
{
  std::vector<double> seconds;
  for (int r = 0; r < std::max(repeats, 1); ++r)
  {
    const auto start = std::chrono::steady_clock::now();
    work();
    seconds.push_back(
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  return Median(seconds);
}

std::vector<std::string> SplitList(const std::string& text)
{
  std::vector<std::string> items;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ','))
  {
    items.push_back(item);
  }
  return items;
}

std::vector<int> ParseIntList(const std::string& text)
{
  std::vector<int> values;
  for (const std::string& item : SplitList(text))
  {
    values.push_back(std::atoi(item.c_str()));
  }
  return values;
}

double PeakMemoryMiB()
{
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0; // Linux reports kilobytes
}

Table::Table(std::vector<std::string> columns)
  : Columns(std::move(columns))
{
}

void Table::AddRow(const std::vector<std::string>& cells)
{
  this->Rows.push_back(cells);
  this->Rows.back().resize(this->Columns.size());
}

std::string Table::Format(double value)
{
  std::ostringstream s;
  if (std::isfinite(value) && value == std::floor(value) && std::abs(value) < 1e15)
  {
    s << static_cast<long long>(value);
  }
  else
  {
    s << std::setprecision(4) << value;
  }
  return s.str();
}

void Table::Print(const std::string& title) const
{
  std::vector<size_t> width(this->Columns.size());
  for (size_t c = 0; c < this->Columns.size(); ++c)
  {
    width[c] = this->Columns[c].size();
    for (const auto& row : this->Rows)
    {
      width[c] = std::max(width[c], row[c].size());
    }
  }
  std::cout << "\n" << title << "\n";
  auto line = [&](const std::vector<std::string>& cells)
  {
    std::cout << "|";
    for (size_t c = 0; c < cells.size(); ++c)
    {
      std::cout << " " << std::setw(static_cast<int>(width[c])) << cells[c] << " |";
    }
    std::cout << "\n";
  };
  line(this->Columns);
  std::cout << "|";
  for (size_t w : width)
  {
    std::cout << std::string(w + 2, '-') << "|";
  }
  std::cout << "\n";
  for (const auto& row : this->Rows)
  {
    line(row);
  }
  std::cout.flush();
}

bool Table::WriteCsv(const std::string& path) const
{
  std::ofstream out(path);
  if (!out)
  {
    std::cerr << "cannot write " << path << "\n";
    return false;
  }
  // A comma inside a cell is written as ';': the file stays one cell per field for the plain
  // `awk -F,` of run_benchmarks.sh (no quoting to undo).
  auto line = [&](const std::vector<std::string>& cells)
  {
    for (size_t c = 0; c < cells.size(); ++c)
    {
      std::string cell = cells[c];
      std::replace(cell.begin(), cell.end(), ',', ';');
      out << (c ? "," : "") << cell;
    }
    out << "\n";
  };
  line(this->Columns);
  for (const auto& row : this->Rows)
  {
    line(row);
  }
  return static_cast<bool>(out);
}

bool WritePlot(const std::string& path, const std::string& title, const std::string& xLabel,
  const std::string& yLabel, const std::vector<Series>& series, bool logX, bool logY)
{
  if (!vtkRefractaRenderWindowCheck::CanOpen())
  {
    std::cerr << "skipping plot " << path << ": " << vtkRefractaRenderWindowCheck::GetReason()
              << "\n";
    return false;
  }
  vtkNew<vtkContextView> view;
  view->GetRenderWindow()->SetOffScreenRendering(true);
  view->GetRenderWindow()->SetSize(900, 640);
  view->GetRenderer()->SetBackground(1, 1, 1);
  vtkNew<vtkChartXY> chart;
  view->GetScene()->AddItem(chart);
  chart->SetTitle(title);
  chart->SetShowLegend(true);
  chart->GetAxis(vtkAxis::BOTTOM)->SetTitle(xLabel);
  chart->GetAxis(vtkAxis::LEFT)->SetTitle(yLabel);
  chart->GetAxis(vtkAxis::BOTTOM)->SetLogScale(logX);
  chart->GetAxis(vtkAxis::LEFT)->SetLogScale(logY);
  static const unsigned char palette[][3] = { { 31, 119, 180 }, { 255, 127, 14 }, { 44, 160, 44 },
    { 214, 39, 40 }, { 148, 103, 189 }, { 140, 86, 75 }, { 227, 119, 194 }, { 127, 127, 127 } };
  std::vector<vtkSmartPointer<vtkTable>> tables;
  for (size_t s = 0; s < series.size(); ++s)
  {
    auto table = vtkSmartPointer<vtkTable>::New();
    vtkNew<vtkDoubleArray> x, y;
    x->SetName("x");
    y->SetName(series[s].Name.c_str());
    for (size_t i = 0; i < std::min(series[s].X.size(), series[s].Y.size()); ++i)
    {
      // Log axes cannot show non-positive values; drop them rather than distort the plot.
      if ((!logX || series[s].X[i] > 0) && (!logY || series[s].Y[i] > 0))
      {
        x->InsertNextValue(series[s].X[i]);
        y->InsertNextValue(series[s].Y[i]);
      }
    }
    table->AddColumn(x);
    table->AddColumn(y);
    tables.push_back(table);
    vtkPlot* line = chart->AddPlot(vtkChart::LINE);
    line->SetInputData(table, 0, 1);
    const unsigned char* c = palette[s % 8];
    line->SetColor(c[0], c[1], c[2], 255);
    line->SetWidth(2.0);
    if (auto* points = vtkPlotPoints::SafeDownCast(line))
    {
      points->SetMarkerStyle(vtkPlotPoints::CIRCLE);
    }
  }
  view->GetRenderWindow()->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(view->GetRenderWindow());
  grab->Update();
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(path.c_str());
  writer->SetInputConnection(grab->GetOutputPort());
  writer->Write();
  return true;
}
}
}
