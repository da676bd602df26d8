#pragma once
/// @file
/// The field pictures of `gphr run` (gnuplot): fields.png for a 2-D grid, the picked field (first
/// component, or a complex field's modulus) of the full model and of each picked run at a few times
/// (output.fieldTimes) on one colour scale, each run's pointwise difference to the full model on a
/// symmetric one; spacetime.png for a 1-D grid, the field over x and t, the same panels. Only
/// these pictures gather whole states onto rank 0, one at a time, and only for grids of at most
/// kMaxPicturePoints points.
#include <string>
#include <vector>

#include "gphr/driver/FieldOutput.hpp"

namespace gphr {

/// The largest grid drawn: rank 0 holds (1 + 2 picked runs) x (output.fieldTimes) fields of this
/// many points and gnuplot their text (512^2: 2 MB a field).
constexpr GO kMaxPicturePoints = 512 * 512;

/// One panel: a field on a uniform grid of `cols` x `rows` values (x fastest).
struct FieldPanel {
  std::string title;          ///< the model, and the time in fields.png
  std::vector<double> values; ///< rows x cols, row-major
  bool difference = false;    ///< a difference to the full model (its own scale)
  bool blank = false;         ///< an empty cell of the layout
};

/// The panels of a run's field picture, laid out in `layoutRows` rows of `layoutCols`, with
/// the axes' origin and spacing (y: the second direction, or t for a 1-D grid).
struct FieldPicture {
  std::string file;  ///< fields.png, spacetime.png, or empty: no picture (`note` says why, if anything)
  std::string note;  ///< a line for stderr when the grid cannot be drawn
  std::vector<FieldPanel> panels;  ///< row by row of the layout
  int layoutRows = 0;  ///< rows of panels
  int layoutCols = 0;  ///< panels per row
  long cols = 0;       ///< values per row of a panel (x)
  long rows = 0;       ///< rows of a panel (y, or t)
  double x0 = 0;       ///< x of the first column
  double dx = 1;       ///< x spacing
  double y0 = 0;       ///< y (or t) of the first row
  double dy = 1;       ///< y (or t) spacing
  std::string yLabel = "y";  ///< y, or t for a 1-D grid (space-time)
  std::string field;         ///< the pictured field's name (chi; u for a complex field)
  bool modulus = false;      ///< the values are |field| and the differences |field - field_fom|
};

/// Collective: the picture's panels (a 2-D grid's columns at the saved states nearest `fieldTimes`, output.fieldTimes), gathered onto rank 0 (the other ranks get the layout only).
FieldPicture fieldPicture(const std::vector<double>& fieldTimes, const FomResult& fom, const FieldOutput& out);

/// Rank 0: draws the picture into `png` with gnuplot; false when gnuplot fails.
bool drawFieldPicture(const FieldPicture& picture, const std::string& png);

}  // namespace gphr
