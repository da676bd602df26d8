#include "gphr/driver/FieldPictures.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "gphr/core/Error.hpp"
#include "gphr/driver/FieldModels.hpp"
#include "gphr/driver/Gnuplot.hpp"
#include "gphr/driver/XdmfWriter.hpp"
#include "gphr/core/Method.hpp"

namespace gphr {

namespace {

// Whole states on rank 0, one at a time by one Import: the pictures' only gathered states.
class RootGather {
 public:
  explicit RootGather(const RCP<const Map>& map)
      : rank0_(map->getComm()->getRank() == 0),
        root_(rcp(new Map(map->getGlobalNumElements(), rank0_ ? map->getGlobalNumElements() : 0, 0, map->getComm()))),
        import_(map, root_),
        buffer_(root_) {}
  std::vector<double> operator()(const Vector& y) {
    buffer_.doImport(y, import_, Tpetra::INSERT);
    if (!rank0_) return {};
    const auto v = buffer_.getLocalViewHost(Tpetra::Access::ReadOnly);
    return std::vector<double>(v.data(), v.data() + v.extent(0));
  }

 private:
  bool rank0_;
  RCP<const Map> root_;
  Import import_;
  Vector buffer_;
};

// The pictured field at each grid point of a gathered state y (minus `ref` for a difference): the
// first component, or the modulus of a complex field (NLS |u|, and |u - u_fom| for a difference).
std::vector<double> pictured(const SceneGrid& grid, const std::vector<double>& y, const std::vector<double>* ref) {
  const size_t n = static_cast<size_t>(grid.numPoints());
  std::vector<double> out(y.empty() ? 0 : n);
  for (size_t i = 0; i < out.size(); ++i) {
    const double a = y[i] - (ref ? (*ref)[i] : 0.0);
    out[i] = grid.complexField ? std::hypot(a, y[n + i] - (ref ? (*ref)[n + i] : 0.0)) : a;
  }
  return out;
}

// A run as a panel names it: its label, and the step from which it left the full model's range.
std::string runTitle(const ModelRun& r) {
  return r.label() + (r.unboundedAt >= 0 ? ", unbounded from step " + std::to_string(r.unboundedAt) : "");
}

std::string timeText(double t) {
  char b[64];
  std::snprintf(b, sizeof b, "t = %.4g", t);
  return b;
}

// 2-D: a column per time of output.fieldTimes; a row for the full model, then per picked run a row
// of its field and one of its difference.
FieldPicture surfacePicture(const std::vector<double>& fieldTimes, const FomResult& fom, const FieldOutput& out) {
  const SceneGrid& g = *out.grid;
  FieldPicture p;
  p.file = "fields.png";
  p.cols = g.points[0], p.rows = g.points[1];
  p.x0 = g.origin[0], p.dx = g.spacing[0], p.y0 = g.origin[1], p.dy = g.spacing[1];
  const auto steps = nearestSaved(fom.savedTimes, fieldTimes);
  p.layoutCols = static_cast<int>(steps.size());
  p.layoutRows = 1 + 2 * static_cast<int>(out.runs.size());
  p.panels.resize(static_cast<size_t>(p.layoutRows * p.layoutCols));
  RootGather gather(fom.trajectory->getMap());
  for (size_t c = 0; c < steps.size(); ++c) {
    const size_t j = steps[c];
    const std::string when = ", " + timeText(fom.savedTimes[j]);
    const auto y = gather(*fom.trajectory->getVector(j));
    p.panels[c] = {method::kFom + when, pictured(g, y, nullptr)};
    for (size_t r = 0; r < out.runs.size(); ++r) {
      const auto yr = gather(*out.runs[r].kept->states[j]);
      const std::string label = runTitle(*out.runs[r].run);
      p.panels[(1 + 2 * r) * steps.size() + c] = {label + when, pictured(g, yr, nullptr)};
      FieldPanel difference{label + when, pictured(g, yr, &y), true};
      // At t = 0 every model starts from the full model's state: its all-white panel says why.
      if (std::all_of(difference.values.begin(), difference.values.end(), [](double v) { return v == 0.0; }))
        difference.title += " (difference exactly 0)";
      p.panels[(2 + 2 * r) * steps.size() + c] = std::move(difference);
    }
  }
  return p;
}

// 1-D: x across, t up; the full model and each picked run in the first row, each run's difference
// below it. Only the equally spaced saved times are drawn (an image needs a uniform grid): a last
// state off the saveEvery grid is left out.
FieldPicture spaceTimePicture(const FomResult& fom, const FieldOutput& out) {
  const SceneGrid& g = *out.grid;
  const auto& t = fom.savedTimes;
  FieldPicture p;
  p.file = "spacetime.png";
  p.yLabel = "t";
  p.cols = g.points[0], p.x0 = g.origin[0], p.dx = g.spacing[0], p.y0 = t.front();
  p.dy = t.size() > 1 ? t[1] - t[0] : 1.0;
  size_t count = 1;
  while (count < t.size() && std::abs(t[count] - (t[0] + count * p.dy)) <= 1e-9 * std::abs(t.back())) ++count;
  p.rows = static_cast<long>(count);
  const size_t runs = out.runs.size();
  p.layoutCols = 1 + static_cast<int>(runs);
  p.layoutRows = runs > 0 ? 2 : 1;
  p.panels.resize(static_cast<size_t>(p.layoutRows * p.layoutCols));
  p.panels[0].title = method::kFom;
  for (size_t r = 0; r < runs; ++r) {
    p.panels[1 + r].title = p.panels[2 + runs + r].title = runTitle(*out.runs[r].run);
    p.panels[2 + runs + r].difference = true;
  }
  if (runs > 0) p.panels[1 + runs].blank = true;  // under the full model
  RootGather gather(fom.trajectory->getMap());
  auto append = [](FieldPanel& panel, const std::vector<double>& v) { panel.values.insert(panel.values.end(), v.begin(), v.end()); };
  for (size_t j = 0; j < count; ++j) {
    const auto y = gather(*fom.trajectory->getVector(j));
    append(p.panels[0], pictured(g, y, nullptr));
    for (size_t r = 0; r < runs; ++r) {
      const auto yr = gather(*out.runs[r].kept->states[j]);
      append(p.panels[1 + r], pictured(g, yr, nullptr));
      append(p.panels[2 + runs + r], pictured(g, yr, &y));
    }
  }
  return p;
}

// The colour ranges: the fields share one, the differences another, symmetric about 0 (from 0
// for a modulus of a difference, which is never negative).
void colourRanges(const FieldPicture& p, double range[2], double& diffMax) {
  range[0] = INFINITY, range[1] = -INFINITY, diffMax = 0.0;
  for (const auto& panel : p.panels)
    for (double v : panel.values) {
      if (panel.difference) diffMax = std::max(diffMax, std::abs(v));
      else range[0] = std::min(range[0], v), range[1] = std::max(range[1], v);
    }
  if (!(range[1] > range[0])) range[1] = range[0] + 1.0;  // a constant field
  if (!(diffMax > 0.0)) diffMax = 1e-300;
}

}  // namespace

FieldPicture fieldPicture(const std::vector<double>& fieldTimes, const FomResult& fom, const FieldOutput& out) {
  if (!out.grid) return {};
  FieldPicture none;
  if (out.grid->points.size() > 2) none.note = "no field picture: fields.png draws 1-D and 2-D grids";
  else if (out.grid->numPoints() > kMaxPicturePoints)
    none.note = detail::concat("no fields.png: a grid of ", out.grid->numPoints(), " points is more than the ",
                               kMaxPicturePoints, " drawn (rank 0 gathers the states it draws); fields.xdmf shows it");
  if (!none.note.empty()) return none;
  FieldPicture p = out.grid->points.size() == 2 ? surfacePicture(fieldTimes, fom, out) : spaceTimePicture(fom, out);
  // a complex field is named by its first component's name after "re_" (re_u: u)
  const std::string& first = out.grid->components[0];
  p.modulus = out.grid->complexField;
  p.field = p.modulus && first.rfind("re_", 0) == 0 ? first.substr(3) : first;
  return p;
}

bool drawFieldPicture(const FieldPicture& p, const std::string& png) {
  const std::string dat = png + ".dat", script = png + ".gp";
  {
    std::ofstream os(dat);
    os.precision(8);
    for (const auto& panel : p.panels) {
      if (panel.blank) continue;
      for (long r = 0; r < p.rows; ++r) {
        for (long c = 0; c < p.cols; ++c) os << (c ? " " : "") << panel.values[static_cast<size_t>(r * p.cols + c)];
        os << "\n";
      }
      os << "\n\n";
    }
  }
  const bool surface = p.yLabel == "y", modulus = p.modulus;
  const std::string value = modulus ? "|" + p.field + "|" : p.field,
                    difference = modulus ? "|" + p.field + " - " + p.field + "_fom|" : p.field + " - " + p.field + "_fom";
  double range[2], diffMax;
  colourRanges(p, range, diffMax);
  std::ostringstream gp;
  gp.precision(17);
  gp << "set terminal pngcairo size " << (surface ? 330 : 420) * p.layoutCols << ","
     << (surface ? 300 : 360) * p.layoutRows << " noenhanced font ',9'\nset output " << gnuplotQuoted(png) << "\n"
     << "set multiplot layout " << p.layoutRows << "," << p.layoutCols << "\nset autoscale fix\n"
     << "set xlabel 'x'\nset ylabel '" << p.yLabel << "'\n" << (surface ? "set size ratio -1\n" : "");
  int index = 0;
  for (const auto& panel : p.panels) {
    if (panel.blank) {
      gp << "set multiplot next\n";
      continue;
    }
    if (panel.difference)
      gp << (modulus ? "set palette defined (0 'white', 1 '#b2182b')\n"
                     : "set palette defined (-1 '#2166ac', 0 'white', 1 '#b2182b')\n")
         << "set cbrange [" << (modulus ? 0.0 : -diffMax) << ":" << diffMax << "]\n";
    else
      gp << "set palette defined (0 '#440154', 1 '#3b528b', 2 '#21918c', 3 '#5ec962', 4 '#fde725')\nset cbrange ["
         << range[0] << ":" << range[1] << "]\n";
    gp << "set title '" << (panel.difference ? difference : value) << ": " << panel.title << "'\n"
       << "plot " << gnuplotQuoted(dat) << " index " << index++ << " matrix using (" << p.x0 << " + $1 * " << p.dx << "):(" << p.y0
       << " + $2 * " << p.dy << "):3 with image notitle\n";
  }
  gp << "unset multiplot\n";
  std::ofstream(script) << gp.str();
  const bool drawn = runGnuplot(script, {png});
  std::remove(dat.c_str());
  return drawn;
}

}  // namespace gphr
