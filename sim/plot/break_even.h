// Break-even maps: over a grid of two swept costs, which method is cheapest
// in each cell and by how much. A cell's hue names the winner (legend), its
// strength the margin (runner-up cycles / winner cycles: pale at 1x, full at
// `full_margin` and above); cells where no method could run are grey. Cells
// where the 90 % band of the winner's lead over the preset's cost draws
// reaches 1.0 (another method wins in more than 5 % of the draws) are hatched.
#pragma once

#include "sim/plot/image.h"

#include <array>
#include <string>
#include <vector>

namespace rtc {

// One point of a map: its winner (-1: none), the lead (runner-up / winner
// cycles) and the lead's 90 % band over the cost draws ({lead, lead} without).
struct BreakEvenCell {
    int winner = -1;
    double margin = 1.0;
    std::array<double, 2> band{1.0, 1.0};
};

struct BreakEvenGrid {
    int nx = 0, ny = 0;                 // cells along x (left to right) and y (bottom to top)
    std::vector<int> winner;            // nx * ny, row 0 = bottom; -1 = none
    std::vector<double> margin;         // runner-up / winner (>= 1; inf when alone)
    std::vector<std::string> methods;   // winner index -> name
    double x_lo = 0, x_hi = 1, y_lo = 0, y_hi = 1;  // axis values at the grid's edges (log axes)
    std::string x_label, y_label, title, caption;
    // A point to mark (the preset's own costs), in axis values; drawn when set.
    bool has_mark = false;
    double mark_x = 0, mark_y = 0;
    std::string mark_label;
    BreakEvenCell at_mark;              // the map at the mark itself
    // Per cell, the 90 % band of the winner's lead over `draws` cost draws
    // (empty without draws); the cell is in doubt when the band reaches 1.0.
    std::vector<double> band_lo, band_hi;
    int draws = 0;
    [[nodiscard]] bool uncertain(std::size_t cell) const {
        return cell < band_lo.size() && winner[cell] >= 0 && band_lo[cell] <= 1.0;
    }
};

struct BreakEvenOptions {
    int cell_pixels = 6;
    double full_margin = 2.0;
    int scale = 1;  // the finished picture magnified (2: text of ~14 px, like the heat maps)
};

[[nodiscard]] Image render_break_even(const BreakEvenGrid& grid, const BreakEvenOptions& options = {});

}  // namespace rtc
