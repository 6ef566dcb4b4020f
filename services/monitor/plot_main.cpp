// pena-link-plot: a small line/point chart as PNG for docs/link-experiments.md, drawn with
// OpenCV (no plotting dependency). Input: a CSV with the header "series,x,y"; one colour per
// series in order of first appearance. Exits 1 with a message naming file and line on bad input.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "pena/io/input_error.hpp"

namespace {

struct Series {
  std::string name;
  std::vector<cv::Point2d> points;
};

struct PlotOptions {
  std::string title, xlabel, ylabel;
  double xmax = 0.0, ymax = 0.0;  // 0: from the data
  bool points = false;            // dots instead of lines
  int width_px = 1000, height_px = 420;
};

std::vector<Series> ReadSeries(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw pena::io::InputError(path, 0, "cannot open");
  std::string line;
  std::getline(in, line);
  if (line.rfind("series,x,y", 0) != 0)
    throw pena::io::InputError(path, 1, "header must be series,x,y");
  std::vector<Series> series;
  std::map<std::string, std::size_t> index;
  for (std::size_t number = 2; std::getline(in, line); ++number) {
    if (line.empty()) continue;
    std::istringstream fields(line);
    std::string name, x, y;
    if (!std::getline(fields, name, ',') || !std::getline(fields, x, ',') ||
        !std::getline(fields, y, ',')) {
      throw pena::io::InputError(path, number, "expected series,x,y");
    }
    try {
      auto [it, inserted] = index.try_emplace(name, series.size());
      if (inserted) series.push_back({name, {}});
      series[it->second].points.emplace_back(std::stod(x), std::stod(y));
    } catch (const std::logic_error&) {
      throw pena::io::InputError(path, number, "x and y must be numbers");
    }
  }
  return series;
}

std::string Label(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

// A round tick step giving about 6 ticks over [0, max].
double TickStep(double max_value) {
  const double raw = max_value / 6.0;
  const double decade = std::pow(10.0, std::floor(std::log10(raw)));
  for (const double factor : {1.0, 2.0, 5.0, 10.0}) {
    if (raw <= factor * decade) return factor * decade;
  }
  return 10.0 * decade;
}

// The chart's frame: data ranges, plot area and the world -> pixel mapping.
struct Frame {
  double xmax = 1.0, ymax = 1.0;
  cv::Rect area;
  cv::Point ToPixel(cv::Point2d p) const {
    return {area.x + static_cast<int>(std::lround(std::clamp(p.x / xmax, 0.0, 1.0) * area.width)),
            area.y + area.height -
                static_cast<int>(std::lround(std::clamp(p.y / ymax, 0.0, 1.0) * area.height))};
  }
};

Frame MakeFrame(const std::vector<Series>& series, const PlotOptions& o) {
  Frame frame;
  double xmax = o.xmax, ymax = o.ymax;
  for (const Series& s : series) {
    for (const cv::Point2d& p : s.points) {
      if (o.xmax <= 0.0) xmax = std::max(xmax, p.x);
      if (o.ymax <= 0.0) ymax = std::max(ymax, p.y);
    }
  }
  frame.xmax = xmax > 0.0 ? xmax : 1.0;
  frame.ymax = ymax > 0.0 ? ymax * (o.ymax > 0.0 ? 1.0 : 1.05) : 1.0;
  const int left = 70, right = 290, top = 50, bottom = 50;
  frame.area = cv::Rect(left, top, o.width_px - left - right, o.height_px - top - bottom);
  return frame;
}

// Grid lines, tick labels, box, title and axis labels.
void DrawAxes(cv::Mat& image, const Frame& f, const PlotOptions& o) {
  const cv::Scalar grey(200, 200, 200), black(0, 0, 0);
  for (double x = 0.0; x <= f.xmax * 1.0001; x += TickStep(f.xmax)) {
    cv::line(image, f.ToPixel({x, 0}), f.ToPixel({x, f.ymax}), grey, 1);
    cv::putText(image, Label(x), f.ToPixel({x, 0}) + cv::Point(-10, 18), cv::FONT_HERSHEY_SIMPLEX,
                0.4, black);
  }
  for (double y = 0.0; y <= f.ymax * 1.0001; y += TickStep(f.ymax)) {
    cv::line(image, f.ToPixel({0, y}), f.ToPixel({f.xmax, y}), grey, 1);
    cv::putText(image, Label(y), f.ToPixel({0, y}) + cv::Point(-50, 4), cv::FONT_HERSHEY_SIMPLEX,
                0.4, black);
  }
  cv::rectangle(image, f.area, black, 1);
  cv::putText(image, o.title, {8, 20}, cv::FONT_HERSHEY_SIMPLEX, 0.55, black, 1, cv::LINE_AA);
  cv::putText(image, o.xlabel, {f.area.x + f.area.width / 2 - 40, o.height_px - 12},
              cv::FONT_HERSHEY_SIMPLEX, 0.45, black, 1, cv::LINE_AA);
  cv::putText(image, o.ylabel, {8, f.area.y - 10}, cv::FONT_HERSHEY_SIMPLEX, 0.45, black, 1,
              cv::LINE_AA);
}

cv::Mat Draw(const std::vector<Series>& series, const PlotOptions& o) {
  const std::vector<cv::Scalar> colours{{200, 90, 20}, {0, 140, 255},  {60, 160, 40},
                                        {40, 40, 220}, {160, 60, 150}, {150, 150, 0},
                                        {90, 90, 90},  {0, 200, 200}};
  const Frame f = MakeFrame(series, o);
  cv::Mat image(o.height_px, o.width_px, CV_8UC3, cv::Scalar(255, 255, 255));
  DrawAxes(image, f, o);
  for (std::size_t i = 0; i < series.size(); ++i) {
    const cv::Scalar& colour = colours[i % colours.size()];
    const std::vector<cv::Point2d>& points = series[i].points;
    for (std::size_t k = 0; k < points.size(); ++k) {
      if (o.points) {
        cv::circle(image, f.ToPixel(points[k]), 2, colour, cv::FILLED);
      } else if (k > 0) {
        cv::line(image, f.ToPixel(points[k - 1]), f.ToPixel(points[k]), colour, 2, cv::LINE_AA);
      }
    }
    const cv::Point key(f.area.x + f.area.width + 15, f.area.y + 20 + 22 * static_cast<int>(i));
    cv::line(image, key, key + cv::Point(25, 0), colour, 3);
    cv::putText(image, series[i].name, key + cv::Point(32, 5), cv::FONT_HERSHEY_SIMPLEX, 0.45,
                cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  }
  return image;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("pena-link-plot: a chart PNG from a series,x,y CSV");
  PlotOptions options;
  std::string input, output;
  app.add_option("--in", input, "CSV with header series,x,y")->required();
  app.add_option("--out", output, "PNG to write")->required();
  app.add_option("--title", options.title, "Chart title");
  app.add_option("--xlabel", options.xlabel, "x axis label");
  app.add_option("--ylabel", options.ylabel, "y axis label");
  app.add_option("--xmax", options.xmax, "x axis end (0: from the data)");
  app.add_option("--ymax", options.ymax,
                 "y axis end; larger values are drawn at the top (0: data)");
  app.add_flag("--points", options.points, "Draw dots instead of lines");
  CLI11_PARSE(app, argc, argv);
  try {
    const cv::Mat image = Draw(ReadSeries(input), options);
    if (!cv::imwrite(output, image)) throw std::runtime_error(output + ": cannot write the PNG");
  } catch (const std::exception& error) {
    std::cerr << "pena-link-plot: " << error.what() << '\n';
    return 1;
  }
  return 0;
}
